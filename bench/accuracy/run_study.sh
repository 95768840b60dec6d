#!/bin/bash
# The whole error-versus-cost study (docs/accuracy.md), about 10-15 minutes on 2 cores:
#   1. accuracy_study on the standard scenes whose fields exist (uniform box always; leaves in
#      the wind after ./Allrun, debris in the tank after ./Allrun -all);
#   2. the grid sweep: one converted case at several resolutions against the finest (the wind
#      case when results/cases/windCourtyard exists, else the tiny OpenFOAM case, run here);
#   3. make_report.py: docs/accuracy/error_vs_cost.png, tolerance_table.json, docs/accuracy.md.
# usage: bench/accuracy/run_study.sh [BUILD_DIR]   (default: build; needs accuracy_study, foam2grid)
set -euo pipefail
src=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "${1:-$src/build}" && pwd)
work=$build/accuracy_work
out=$src/docs/accuracy
mkdir -p "$work" "$out"
t0=$SECONDS

"$build/bin/accuracy_study" --source-dir "$src" --out "$work/main" 2>&1 | tee "$work/log.main"

grids=()
if [ -d "$src/results/cases/windCourtyard" ]; then
  name=windCourtyard
  case_dir=$src/results/cases/windCourtyard
  bounds=(--bounds -20 60 -25 25 0 25)
  scene=$src/scenes/leaves_wind.json
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
  scene=$work/tiny_scene.json
  sed "s|@FIELD@|$work/grid_${name}_0.vti|" "$src/bench/accuracy/tiny_scene.json.in" > "$scene"
  res=(16 32 64 128)
fi
files=()
for n in "${res[@]}"; do
  f=$work/grid_${name}_$n.vti
  [ -f "$f" ] || "$build/bin/foam2grid" "$case_dir" -o "$f" "${bounds[@]}" --resolution "$n" "$n" "$n" -q
  files+=("$f")
done
cp "${files[0]}" "$work/grid_${name}_0.vti"  # the scene's nominal field (replaced per run)
list=$(IFS=,; echo "${files[*]}")
"$build/bin/accuracy_study" --source-dir "$src" --out "$work/grid" --scenes none \
  --grids "$name:$scene:$list" 2>&1 | tee "$work/log.grid"

/usr/bin/python3 "$src/bench/accuracy/make_report.py" --csv "$work/main/accuracy.csv" \
  "$work/grid/accuracy.csv" --out "$out" --doc "$src/docs/accuracy.md" \
  --study-seconds $((SECONDS - t0))
