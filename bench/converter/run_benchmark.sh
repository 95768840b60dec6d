#!/usr/bin/env bash
# Benchmark of foam2grid (not a test): resampling a mesh of about a million cells to 128^3.
# Builds the case from foam_cases/tiny refined 6x per direction (240 x 72 x 60 = 1.04M cells
# minus the cube), runs a few simpleFoam iterations for non-trivial fields, then times
# foam2grid (ascii and binary copies of the case) with /usr/bin/time -v and writes the figures,
# with machine and date, into docs/converter.md between the bench markers.
#   bench/converter/run_benchmark.sh [BUILD_DIR] [WORK_DIR]
#     BUILD_DIR  holds bin/foam2grid (default: build)
#     WORK_DIR   where the case goes (default: /tmp/foam2grid-bench); reused when present
# Environment: OMP_NUM_THREADS (default 2), REPEAT (runs per variant, default 3),
#              ITERATIONS (simpleFoam iterations, default 3).
set -euo pipefail
here=$(cd "${0%/*}" && pwd)
src=$(cd "$here/../.." && pwd)
build=$(cd "${1:-$src/build}" && pwd)
work=${2:-/tmp/foam2grid-bench}
bin=$build/bin/foam2grid
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-2}
repeat=${REPEAT:-3}
iterations=${ITERATIONS:-3}
[ -x "$bin" ] || { echo "run_benchmark: $bin not found: build the foam2grid target" >&2; exit 1; }
[ -x /usr/bin/time ] || { echo "run_benchmark: no /usr/bin/time (scripts/install-deps)" >&2; exit 1; }

export WM_PROJECT_DIR=/usr/share/openfoam
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

case_dir=$work/cube1M
if [ ! -f "$case_dir/.done" ]; then
  echo "run_benchmark: building the 1M-cell case in $case_dir"
  rm -rf "$case_dir"
  mkdir -p "$work"
  cp -r "$src/foam_cases/tiny" "$case_dir"
  cd "$case_dir"
  sed -i 's/(40 12 10)/(240 72 60)/' system/blockMeshDict
  grep -q '(240 72 60)' system/blockMeshDict || { echo "cannot refine blockMeshDict" >&2; exit 1; }
  foamDictionary -entry endTime -set "$iterations" system/controlDict > /dev/null
  foamDictionary -entry writeInterval -set "$iterations" system/controlDict > /dev/null
  foamDictionary -entry functions -remove system/controlDict > /dev/null
  /usr/bin/blockMesh > log.blockMesh 2>&1
  /usr/bin/topoSet > log.topoSet 2>&1
  /usr/bin/subsetMesh fluid -patch obstacle -overwrite > log.subsetMesh 2>&1
  rm -rf 0 && cp -r 0.orig 0
  echo "run_benchmark: simpleFoam, $iterations iterations"
  /usr/bin/simpleFoam > log.simpleFoam 2>&1
  # a binary copy (same values) to separate parsing from resampling
  rm -rf "$work/cube1M_binary"
  cp -r "$case_dir" "$work/cube1M_binary"
  (cd "$work/cube1M_binary" &&
   foamDictionary -entry writeFormat -set binary system/controlDict > /dev/null &&
   /usr/bin/foamFormatConvert > log.foamFormatConvert 2>&1)
  touch "$case_dir/.done"
fi
cd "$work"
ncells=$(sed -n 's/.*nCells:\([0-9]*\).*/\1/p' "$case_dir/constant/polyMesh/owner" | head -1)

load_before=$(cut -d' ' -f1-3 /proc/loadavg)
results=()
for variant in cube1M cube1M_binary; do
  best_wall=""; worst_rss=0
  for i in $(seq "$repeat"); do
    /usr/bin/time -v "$bin" "$work/$variant" -o "$work/$variant.vti" --resolution 128 128 128 \
      > "$work/log.$variant.$i" 2>&1 || { cat "$work/log.$variant.$i" >&2; exit 1; }
    wall=$(sed -n 's/.*Elapsed (wall clock) time (h:mm:ss or m:ss): //p' "$work/log.$variant.$i" |
           awk -F: '{ if (NF == 3) print $1*3600 + $2*60 + $3; else print $1*60 + $2 }')
    rss=$(sed -n 's/.*Maximum resident set size (kbytes): //p' "$work/log.$variant.$i")
    cpu=$(awk -F': ' '/User time|System time/ { t += $2 } END { print t }' "$work/log.$variant.$i")
    echo "run_benchmark: $variant run $i: wall $wall s, cpu $cpu s, peak RSS $((rss / 1024)) MB"
    if [ -z "$best_wall" ] || awk "BEGIN{exit !($wall < $best_wall)}"; then
      best_wall=$wall
      best_cpu=$cpu
    fi
    [ "$rss" -gt "$worst_rss" ] && worst_rss=$rss
  done
  phases=$(grep -E 'mesh:|fields read|resampled|written' "$work/log.$variant.$repeat" |
           sed 's/^foam2grid //' | tr '\n' ';' | sed 's/;$//')
  results+=("| $variant | $best_wall | $best_cpu | $((worst_rss / 1024)) | $phases |")
done

cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)
mem=$(awk '/MemTotal/ { printf "%.1f GB", $2 / 1048576 }' /proc/meminfo)
block="<!-- bench:begin (written by bench/converter/run_benchmark.sh) -->
Measured $(date -u '+%Y-%m-%d %H:%M UTC') on $(hostname): $cpu, $(nproc) cores visible,
$mem RAM, OMP_NUM_THREADS=$OMP_NUM_THREADS, load average before / after the runs
$load_before / $(cut -d' ' -f1-3 /proc/loadavg) (other jobs share the cores).
Case: foam_cases/tiny refined to 240 x 72 x 60
($ncells cells after cutting out the cube), $iterations simpleFoam iterations; grid 128^3
(2 097 152 points, U k epsilon nut valid). Best wall time of $repeat runs, largest peak RSS
(\`/usr/bin/time -v\`); the phases are the cumulative times foam2grid logs in its last run.

| case files | wall time (s) | CPU user+sys (s) | peak RSS (MB) | phases (cumulative wall, cpu) |
|---|---|---|---|---|
$(printf '%s\n' "${results[@]}")
<!-- bench:end -->"

doc=$src/docs/converter.md
if [ -f "$doc" ] && grep -q '<!-- bench:begin' "$doc"; then
  BLOCK="$block" /usr/bin/python3 - "$doc" <<'PY'
import os, re, sys
p = sys.argv[1]
s = open(p).read()
s = re.sub(r"<!-- bench:begin.*?<!-- bench:end -->", lambda m: os.environ["BLOCK"], s, flags=re.S)
open(p, "w").write(s)
PY
  echo "run_benchmark: figures written to $doc"
else
  echo "run_benchmark: no bench markers in $doc; figures:"
fi
echo "$block"
