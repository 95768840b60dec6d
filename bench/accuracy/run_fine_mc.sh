#!/bin/bash
# A scene's stochastic sweep again with 16000 bodies (uniform_box by default: 16 times the main
# study's), for splitting and strang: on uniform_box, with 1000 bodies the weak variance's Monte Carlo floor (2 standard errors of the paired
# differences) is about 0.026, so no point can show 1 % (docs/accuracy.md); with 16000 it is
# about 0.0065. Writes docs/accuracy/<scene>_stoch_16000.csv, which run_study.sh's report
# reads beside the main study's CSVs (make_report.py keeps, of a point measured twice, the run
# with more bodies). About 30 minutes on 2 shared cores (1859 s at load 3-5, 2026-12-03).
# usage: bench/accuracy/run_fine_mc.sh [BUILD_DIR [SCENE]]   (default: build uniform_box; the
#   leaves_wind and debris_tank scenes need ./Allrun's and ./Allrun -all's grids)
set -euo pipefail
src=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "${1:-$src/build}" && pwd)
scene=${2:-uniform_box}
work=$build/accuracy_work/$scene.stoch16000
mkdir -p "$work"
"$build/bin/accuracy_study" --scenes "$scene" --sweeps stoch --integrators splitting,strang \
  --bodies-stoch 16000 --threads 2 --out "$work"
dest=$src/docs/accuracy/${scene}_stoch_16000.csv
cp "$work/accuracy.csv" "$dest.tmp"
mv "$dest.tmp" "$dest"
echo "run_fine_mc.sh: wrote $dest; rerun the report" \
  "(bench/accuracy/run_study.sh, or make_report.py with it among --csv)"
