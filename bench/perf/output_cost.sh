#!/bin/bash
# The outputs' cost against the simulation on the default scene (docs/performance.md,
# "Output cost"). Two measurements:
#  1. build/bin/writers_bench: each writer (csv, bodies .vtp, shapes .vtp, glb) timed on its own
#     at every output frame of scenes/leaves_wind.json, next to the simulation's time between
#     two frames; then lrigid run's own writer (csv + pvd, the .vtp frames on their thread).
#  2. lrigid run on the same scene, 1 thread, with formats [] / csv / pvd / csv+pvd: CPU time
#     (user + sys, /usr/bin/time) of the whole run and the simulation's wall time (summary.json).
# Usage: bench/perf/output_cost.sh [BUILD_DIR] [OTHER_LRIGID]  (OTHER_LRIGID: a second binary,
# e.g. an older build, measured the same way for comparison). Needs results/grids/windCourtyard.vti
# (./Allrun). Takes about a minute; prints Markdown-ready lines.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build}
other=${2:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "date (UTC): $(date -u '+%Y-%m-%d %H:%M'); CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) cores; load before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "commit: $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)"
echo
echo "## writers_bench (scenes/leaves_wind.json, 1 thread)"
"$build/bin/writers_bench" --threads 1
echo
for f in none csv pvd csv+pvd; do
  case $f in
    none) formats='[]' ;; csv) formats='["csv"]' ;; pvd) formats='["pvd"]' ;;
    csv+pvd) formats='["csv", "pvd"]' ;;
  esac
  /usr/bin/python3 - "$root" "$formats" "$work/$f.json" <<'PY'
import json, os, sys
root, formats, out = sys.argv[1], json.loads(sys.argv[2]), sys.argv[3]
s = json.load(open(os.path.join(root, "scenes", "leaves_wind.json")))
s["fluid"]["field"] = os.path.join(root, "results", "grids", "windCourtyard.vti")
s["output"]["formats"] = formats
json.dump(s, open(out, "w"))
PY
done
measure() {  # measure LABEL BINARY
  local label=$1 bin=$2 f
  echo "## lrigid run, 1 thread: $label ($bin)"
  printf '%-8s %10s %10s %12s %10s\n' formats cpu_s wall_s sim_wall_s out_MB
  for f in none csv pvd csv+pvd; do
    rm -rf "$work/out"
    /usr/bin/time -f '%U %S %e' -o "$work/time" "$bin" run "$work/$f.json" -o "$work/out" \
      --threads 1 --quiet
    read -r u s e < "$work/time"
    sim=$(/usr/bin/python3 -c "import json; print(json.load(open('$work/out/summary.json'))['wall_seconds'])")
    mb=$(du -sm "$work/out" | cut -f1)
    printf '%-8s %10.2f %10.2f %12.3f %10s\n' "$f" "$(echo "$u + $s" | bc)" "$e" "$sim" "$mb"
  done
}
measure "this build" "$build/bin/lrigid"
[ -n "$other" ] && measure "other build" "$other"
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
