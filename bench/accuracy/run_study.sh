#!/bin/bash
# The whole error-versus-cost study (docs/accuracy.md), about 20-30 minutes on 2 shared cores:
#   1. accuracy_study on the standard scenes whose fields exist (uniform box always; leaves in
#      the wind after ./Allrun, debris in the tank after ./Allrun -all), two processes per
#      scene (stochastic sweep; the others), side by side;
#   2. the grid sweep, alongside: one converted case at 32^3 .. 256^3 points against the finest
#      (the wind case: $ACCURACY_WIND_CASE, default results/cases/windCourtyard, copied first;
#      else the tiny OpenFOAM case, run here);
#   3. make_report.py: docs/accuracy/error_vs_cost.png, tolerance_table.json, docs/accuracy.md.
# usage: bench/accuracy/run_study.sh [-q] [BUILD_DIR]   (default: build; needs accuracy_study,
#   foam2grid). Progress (step k of n, elapsed, time remaining; validation/lib/progress.py):
#   a bar on a terminal, plain lines when piped; -q silences it.
set -euo pipefail
if [ "${1:-}" = -q ]; then export LRIGID_PROGRESS=quiet; shift; fi
src=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "${1:-$src/build}" && pwd)
work=$build/accuracy_work
out=$src/docs/accuracy
mkdir -p "$work" "$out"
t0=$SECONDS
start=$(date +%s)
step() {  # step K NAME LOG COMMAND...: one step of nsteps under the progress display
  local k=$1 name=$2 log=$3
  shift 3
  /usr/bin/python3 "$src/validation/lib/progress.py" --label run_study --start "$start" \
    --step "$k" --of "$nsteps" --name "$name" --history "$work/progress_history.json" \
    ${log:+--log "$log"} -- "$@"
}
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
# steps: one conversion per resolution, the processes side by side, the report
nsteps=$((${#res[@]} + 2))
k=0
files=()
for n in "${res[@]}"; do
  f=$work/grid_${name}_$n.vti
  k=$((k + 1))
  [ -f "$f" ] || step $k "foam2grid $name ${n}^3" "" \
    "$build/bin/foam2grid" "$case_dir" -o "$f" "${bounds[@]}" --resolution "$n" "$n" "$n" -q
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

# every scene's stochastic sweep, its other sweeps and the grid sweep side by side
step $((nsteps - 1)) "accuracy_study: 7 processes side by side" "" \
  "$src/bench/accuracy/run_jobs.sh" "$build" "$src" "$work" \
  "${ACCURACY_STOCH_INTEGRATORS:-euler,splitting,strang}" "$name" "$scene" "$list"
done_lines=$(paste -sd';' "$work/jobs.txt" | sed 's/;/; /g')
jobs_=(uniform_box.det uniform_box.stoch leaves_wind.det leaves_wind.stoch debris_tank.det \
  debris_tank.stoch grid)

csvs=()
for j in "${jobs_[@]}"; do csvs+=("$work/$j/accuracy.csv"); done
# stochastic sweeps rerun with 16000 bodies (bench/accuracy/run_fine_mc.sh), where kept
fine_note=""
for fine in "$src"/docs/accuracy/*_stoch_16000.csv; do
  [ -f "$fine" ] || continue
  csvs+=("$fine")
  fine_note+=" $(basename "$fine" _stoch_16000.csv) (committed at \
$(git -C "$src" log -1 --format=%h -- "$fine")),"
done
[ -z "$fine_note" ] || fine_note=" Also read: the stochastic sweeps rerun with 16000 bodies \
instead of 1000-1200 (bench/accuracy/run_fine_mc.sh, docs/accuracy/*_stoch_16000.csv) of\
${fine_note%,}; of a point measured in both, the report keeps the run with more bodies."
step $nsteps "report" "" /usr/bin/python3 "$src/bench/accuracy/make_report.py" \
  --csv "${csvs[@]}" --out "$out" \
  --doc "$src/docs/accuracy.md" --study-seconds $((SECONDS - t0)) \
  --note "Runtime measured: commit $(git -C "$src" rev-parse --short HEAD) (contains main at \
$(git -C "$src" merge-base HEAD main 2>/dev/null | cut -c1-7)). Processes (wall, one \
thread each, side by side): $done_lines; load average $load0 at the start, \
$(cut -d' ' -f1-3 /proc/loadavg) at the end (2 cores).$fine_note"
