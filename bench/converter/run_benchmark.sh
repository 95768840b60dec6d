#!/usr/bin/env bash
# Benchmark of foam2grid (not a test): resampling a mesh of about a million cells.
# Builds the case from foam_cases/tiny refined 6x per direction (240 x 72 x 60 = 1.04M cells
# minus the cube), runs a few simpleFoam iterations for non-trivial (nonuniform) fields, then
# times foam2grid (ascii and binary copies of the case) with /usr/bin/time -v at foam2grid's
# default grid (spacing = mean cell size, about as many points as mesh points) and at 128^3, and
# writes the figures, with machine, date and load, into docs/converter.md between the bench
# markers and, with JSON set, as JSON (read by bench/perf/make_report.py for docs/performance.md).
#   bench/converter/run_benchmark.sh [BUILD_DIR] [WORK_DIR]
#     BUILD_DIR  holds bin/foam2grid (default: build)
#     WORK_DIR   where the case goes (default: /tmp/foam2grid-bench); reused when present
# Environment: OMP_NUM_THREADS (default 2), REPEAT (runs per variant, default 3),
#              ITERATIONS (simpleFoam iterations, default 3), RESOLUTIONS (default "default 128":
#              foam2grid's default spacing, and 128^3), JSON (also write the figures there).
set -euo pipefail
here=$(cd "${0%/*}" && pwd)
src=$(cd "$here/../.." && pwd)
build=$(cd "${1:-$src/build}" && pwd)
work=${2:-/tmp/foam2grid-bench}
bin=$build/bin/foam2grid
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-2}
repeat=${REPEAT:-3}
iterations=${ITERATIONS:-3}
resolutions=${RESOLUTIONS:-default 128}
json=${JSON:-}
[ -z "$json" ] || [ "${json#/}" != "$json" ] || json=$PWD/$json
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
jrows=()
for res in $resolutions; do
  if [ "$res" = default ]; then resargs=(); else resargs=(--resolution "$res" "$res" "$res"); fi
  for variant in cube1M cube1M_binary; do
    best_wall=""; worst_rss=0
    for i in $(seq "$repeat"); do
      log=$work/log.$variant.$res.$i
      /usr/bin/time -v "$bin" "$work/$variant" -o "$work/$variant.$res.vti" "${resargs[@]}" \
        > "$log" 2>&1 || { cat "$log" >&2; exit 1; }
      wall=$(sed -n 's/.*Elapsed (wall clock) time (h:mm:ss or m:ss): //p' "$log" |
             awk -F: '{ if (NF == 3) print $1*3600 + $2*60 + $3; else print $1*60 + $2 }')
      rss=$(sed -n 's/.*Maximum resident set size (kbytes): //p' "$log")
      cpu=$(awk -F': ' '/User time|System time/ { t += $2 } END { print t }' "$log")
      echo "run_benchmark: $variant grid $res run $i: wall $wall s, cpu $cpu s, peak RSS $((rss / 1024)) MB"
      if [ -z "$best_wall" ] || awk "BEGIN{exit !($wall < $best_wall)}"; then
        best_wall=$wall
        best_cpu=$cpu
        best_log=$log
      fi
      [ "$rss" -gt "$worst_rss" ] && worst_rss=$rss
    done
    phases=$(grep -E '^foam2grid \[' "$best_log" | grep -E 'mesh:|fields read|resampled|written' |
             sed 's/^foam2grid //' | tr '\n' ';' | sed 's/;$//')
    dims=$("$bin" --info "$work/$variant.$res.vti" 2>&1 | sed -n 's/.*dimensions[: ]*\([0-9]* x [0-9]* x [0-9]*\).*/\1/p' | head -1)
    points=$(echo "$dims" | awk -F' x ' 'NF == 3 { print $1 * $2 * $3 }')
    size=$(stat -c %s "$work/$variant.$res.vti")
    results+=("| $variant | $dims | $best_wall | $best_cpu | $((worst_rss / 1024)) | $((size / 1048576)) | $phases |")
    jrows+=("{\"case\": \"$variant\", \"grid\": \"$res\", \"dimensions\": \"$dims\", \"points\": ${points:-null}, \"wall_s\": $best_wall, \"cpu_s\": $best_cpu, \"peak_rss_mb\": $((worst_rss / 1024)), \"vti_bytes\": $size, \"phases\": \"$phases\"}")
  done
done
load_after=$(cut -d' ' -f1-3 /proc/loadavg)

cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)
mem=$(awk '/MemTotal/ { printf "%.1f GB", $2 / 1048576 }' /proc/meminfo)
block="<!-- bench:begin (written by bench/converter/run_benchmark.sh) -->
Measured $(date -u '+%Y-%m-%d %H:%M UTC') on $(hostname): $cpu, $(nproc) cores visible,
$mem RAM, OMP_NUM_THREADS=$OMP_NUM_THREADS, load average before / after the runs
$load_before / $load_after (other jobs share the cores).
Case: foam_cases/tiny refined to 240 x 72 x 60
($ncells cells after cutting out the cube), $iterations simpleFoam iterations (nonuniform fields);
grids: foam2grid's default spacing (the mean cell size) and 128^3, U k epsilon nut valid.
Best wall time of $repeat runs, largest peak RSS (\`/usr/bin/time -v\`); the phases are the
cumulative times foam2grid logs in the best run.

| case files | grid points | wall time (s) | CPU user+sys (s) | peak RSS (MB) | .vti (MB) | phases (cumulative wall, cpu) |
|---|---|---|---|---|---|---|
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
if [ -n "$json" ]; then
  {
    echo "{\"date\": \"$(date -u '+%Y-%m-%d %H:%M')\", \"machine\": \"$cpu, $(nproc) cores, $mem\","
    echo " \"cells\": $ncells, \"simplefoam_iterations\": $iterations, \"omp_threads\": $OMP_NUM_THREADS,"
    echo " \"repeat\": $repeat, \"load_before\": \"$load_before\", \"load_after\": \"$load_after\","
    echo " \"runs\": [$(IFS=,; echo "${jrows[*]}")]}"
  } > "$json.tmp"
  mv "$json.tmp" "$json"
  echo "run_benchmark: figures written to $json"
fi
