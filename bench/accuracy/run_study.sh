#!/bin/bash
# The whole error-versus-cost study (docs/accuracy.md), about 20-30 minutes on 2 shared cores:
#   1. accuracy_study on the standard scenes whose fields exist (uniform box always; leaves in
#      the wind after ./Allrun, debris in the tank after ./Allrun -all), two processes per
#      scene (stochastic sweep; the others), side by side;
#   2. the grid sweep, alongside: one converted case at 32^3 .. 256^3 points against the finest
#      (the wind case: $ACCURACY_WIND_CASE, default results/cases/windCourtyard, copied first;
#      else the tiny OpenFOAM case, run here);
#   3. make_report.py: docs/accuracy/error_vs_cost.png, tolerance_table.json, docs/accuracy.md.
# usage: bench/accuracy/run_study.sh [BUILD_DIR]   (default: build; needs accuracy_study, foam2grid)
set -euo pipefail
src=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "${1:-$src/build}" && pwd)
work=$build/accuracy_work
out=$src/docs/accuracy
mkdir -p "$work" "$out"
t0=$SECONDS
load0=$(cut -d' ' -f1-3 /proc/loadavg)

wind_case=${ACCURACY_WIND_CASE:-$src/results/cases/windCourtyard}
if [ -d "$wind_case" ]; then
  name=windCourtyard
  case_dir=$work/windCourtyard_case
  [ -d "$case_dir" ] || cp -r "$wind_case" "$case_dir"   # foam2grid never writes the source
  bounds=(--bounds -20 60 -25 25 0 25)
  base=$src/scenes/leaves_wind.json
  res=(32 64 128 256)
else
  name=tiny
  case_dir=$work/tiny
  bounds=()
  if [ ! -f "$case_dir/.done" ]; then
    rm -rf "$case_dir"
    cp -r "$src/foam_cases/tiny" "$case_dir"
    FOAM_CASES_DIR=$src/foam_cases "$case_dir/Allrun" > "$work/log.tiny" 2>&1
    touch "$case_dir/.done"
  fi
  base=$src/bench/accuracy/tiny_scene.json.in
  res=(16 32 64 128)
fi
files=()
for n in "${res[@]}"; do
  f=$work/grid_${name}_$n.vti
  [ -f "$f" ] || "$build/bin/foam2grid" "$case_dir" -o "$f" "${bounds[@]}" --resolution "$n" "$n" "$n" -q
  files+=("$f")
done
# the scene on the finest grid (replaced per run); the wind's leaves spawned 0.5-3 m high for
# 4 s, as in the main study, so that the landing points are compared too
scene=$work/grid_scene.json
/usr/bin/python3 - "$base" "${files[-1]}" "$scene" "$name" <<'PY'
import json, sys
s = json.loads(open(sys.argv[1]).read().replace("@FIELD@", sys.argv[2]))
s["fluid"]["field"] = sys.argv[2]
s["duration"] = min(s["duration"], 2.0)
if sys.argv[4] == "windCourtyard":
    s["duration"] = 4.0
    for b in s["bodies"]:
        b["spawn_box"][0][2], b["spawn_box"][1][2] = 0.5, 3.0
json.dump(s, open(sys.argv[3], "w"), indent=1)
PY
list=$(IFS=,; echo "${files[*]}")

# every scene's stochastic sweep, its other sweeps and the grid sweep side by side, each in
# its own process (one thread: the cost is the process's CPU time); logs in $work/log.<job>
# rk4's stochastic sweep costs as much again as euler's and splitting's together (4 force
# evaluations per step at the finest steps): ACCURACY_STOCH_INTEGRATORS=euler,rk4,splitting
stoch_schemes=${ACCURACY_STOCH_INTEGRATORS:-euler,splitting}
jobs_=()
for s in uniform_box leaves_wind debris_tank; do jobs_+=("$s.det" "$s.stoch"); done
jobs_+=(grid)
pids=()
done_lines=""
for j in "${jobs_[@]}"; do
  case $j in
    grid) args=(--scenes none --grids "$name:$scene:$list") ;;
    *.det) args=(--scenes "${j%.det}" --sweeps det,effects) ;;
    *.stoch) args=(--scenes "${j%.stoch}" --sweeps stoch --integrators "$stoch_schemes") ;;
  esac
  "$build/bin/accuracy_study" --source-dir "$src" --out "$work/$j" "${args[@]}" \
    > "$work/log.$j" 2>&1 &
  pids+=($!)
done
for k in "${!jobs_[@]}"; do
  if wait "${pids[$k]}"; then
    took=$(sed -n 's/.* in \([0-9.]*\) s$/\1/p' "$work/log.${jobs_[$k]}" | tail -1)
    line="${jobs_[$k]} ${took%.*} s"
    echo "run_study: $line"
    done_lines+="${done_lines:+; }$line"
  else
    # a scene whose field is missing is skipped (its log says why); the others still report
    echo "run_study: ${jobs_[$k]} failed, see $work/log.${jobs_[$k]}" >&2
    rm -f "$work/${jobs_[$k]}/accuracy.csv"
  fi
done

csvs=()
for j in "${jobs_[@]}"; do csvs+=("$work/$j/accuracy.csv"); done
/usr/bin/python3 "$src/bench/accuracy/make_report.py" --csv "${csvs[@]}" --out "$out" \
  --doc "$src/docs/accuracy.md" --study-seconds $((SECONDS - t0)) \
  --note "Runtime measured: commit $(git -C "$src" rev-parse --short HEAD) (contains main at \
$(git -C "$src" merge-base HEAD main 2>/dev/null | cut -c1-7)). Processes (wall, one \
thread each, side by side): $done_lines; load average $load0 at the start, \
$(cut -d' ' -f1-3 /proc/loadavg) at the end (2 cores)."
