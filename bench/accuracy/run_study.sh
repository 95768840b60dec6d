#!/bin/bash
# The whole error-versus-cost study (docs/accuracy.md), about 10-15 minutes on 2 cores:
#   1. accuracy_study on the standard scenes whose fields exist (uniform box always; leaves in
#      the wind after ./Allrun, debris in the tank after ./Allrun -all);
#   2. the grid sweep: one converted case at several resolutions against the finest (the wind
#      case when results/cases/windCourtyard exists, else the tiny OpenFOAM case, run here);
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

grids=()
if [ -d "$src/results/cases/windCourtyard" ]; then
  name=windCourtyard
  case_dir=$src/results/cases/windCourtyard
  bounds=(--bounds -20 60 -25 25 0 25)
  base=$src/scenes/leaves_wind.json
  res=(32 64 128)
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
# steps: the main study, one conversion per resolution, the grid study, the report
nsteps=$((${#res[@]} + 3))
rm -f "$work/log.main"
step 1 "accuracy_study (scenes)" "$work/log.main" \
  "$build/bin/accuracy_study" --source-dir "$src" --out "$work/main"
k=1
files=()
for n in "${res[@]}"; do
  f=$work/grid_${name}_$n.vti
  k=$((k + 1))
  [ -f "$f" ] || step $k "foam2grid $name ${n}^3" "" \
    "$build/bin/foam2grid" "$case_dir" -o "$f" "${bounds[@]}" --resolution "$n" "$n" "$n" -q
  files+=("$f")
done
# the scene on the finest grid (replaced per run), at most 2 s
scene=$work/grid_scene.json
/usr/bin/python3 - "$base" "${files[-1]}" "$scene" <<'PY'
import json, sys
s = json.loads(open(sys.argv[1]).read().replace("@FIELD@", sys.argv[2]))
s["fluid"]["field"] = sys.argv[2]
s["duration"] = min(s["duration"], 2.0)
json.dump(s, open(sys.argv[3], "w"), indent=1)
PY
list=$(IFS=,; echo "${files[*]}")
rm -f "$work/log.grid"
step $((nsteps - 1)) "accuracy_study (grids)" "$work/log.grid" \
  "$build/bin/accuracy_study" --source-dir "$src" --out "$work/grid" --scenes none \
  --grids "$name:$scene:$list"

step $nsteps "report" "" /usr/bin/python3 "$src/bench/accuracy/make_report.py" \
  --csv "$work/main/accuracy.csv" "$work/grid/accuracy.csv" --out "$out" --doc "$src/docs/accuracy.md" \
  --study-seconds $((SECONDS - t0)) --note "Runtime measured: commit $(git -C "$src" rev-parse --short HEAD)."
