#!/bin/bash
# What streaming a transient field costs and saves: `lrigid run
# --stream-field on` and `off` on the tank scene's .pvd series (scenes/debris_tank.json), each
# under /usr/bin/time -v. Writes OUT/stream.json (read by bench/perf/make_report.py):
#   per mode: process wall and CPU (user+sys) s, peak RSS, the integration wall, the time spent
#   reading frames (summary.json: field_load_seconds, plus field_stream.read_seconds when
#   streamed), frames read and most frames resident; and the series' grid bytes per frame.
#
#   bench/perf/stream_bench.sh OUT [--build DIR] [--series FILE.pvd] [--duration S]
#                               [--threads T] [--repeat R]
#     --series    the tank .pvd series (default results/grids/tankJet.pvd, from ./Allrun -all)
#     --duration  simulated seconds (default: the scene's 20 s, which reads every frame)
#     --threads   lrigid threads (default 1: CPU time = work, the wall least disturbed)
#     --repeat    runs per mode, the fastest kept (default 2)
# The frames come from the page cache after the first run (the series is small): the read time is
# decompression and parsing, not disk. Run it niced on a shared machine.
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$PWD
out=${1:?usage: stream_bench.sh OUT [--build DIR] [--series FILE.pvd] [--duration S]}
shift
build=build
series=results/grids/tankJet.pvd
duration=""
threads=1
repeat=2
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build=$2; shift 2 ;;
    --series) series=$2; shift 2 ;;
    --duration) duration=$2; shift 2 ;;
    --threads) threads=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    *) echo "stream_bench.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
lrigid=$root/$build/bin/lrigid
[ -x "$lrigid" ] || lrigid=$build/bin/lrigid
[ -x "$lrigid" ] || { echo "stream_bench.sh: $lrigid missing: build lrigid" >&2; exit 1; }
[ -f "$series" ] || { echo "stream_bench.sh: $series missing (./Allrun -all, or --series)" >&2; exit 1; }
series=$(cd "$(dirname "$series")" && pwd)/$(basename "$series")
mkdir -p "$out"
out=$(cd "$out" && pwd)

# the tank scene with the series' absolute path (and the duration, if given)
/usr/bin/python3 - scenes/debris_tank.json "$series" "$out/scene.json" "$duration" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s["fluid"]["field"] = sys.argv[2]
if sys.argv[4]:
    s["duration"] = float(sys.argv[4])
json.dump(s, open(sys.argv[3], "w"), indent=1)
PY

load_before=$(cut -d' ' -f1-3 /proc/loadavg)
runs=()
for mode in off on; do
  for i in $(seq "$repeat"); do
    log=$out/time.$mode.$i.log
    rm -rf "$out/run.$mode"
    /usr/bin/time -v "$lrigid" run "$out/scene.json" -o "$out/run.$mode" --threads "$threads" \
      --stream-field "$mode" --quiet 2> "$log" || { cat "$log" >&2; exit 1; }
    cp "$out/run.$mode/summary.json" "$out/summary.$mode.$i.json"
    runs+=("$mode $log $out/summary.$mode.$i.json")
    echo "stream_bench.sh: --stream-field $mode run $i done" >&2
  done
done
load_after=$(cut -d' ' -f1-3 /proc/loadavg)

/usr/bin/python3 bench/perf/collect.py stream "$out/stream.json" "$series" "$threads" \
  "$load_before" "$load_after" "${runs[@]}"
rm -rf "$out/run.on" "$out/run.off"
echo "stream_bench.sh: wrote $out/stream.json" >&2
