#!/bin/bash
# What fsync costs a run (docs/performance.md "Durability: what fsync costs"):
# a uniform-flow scene of BODIES spheres (default 1000), 2 s, an output every 0.01 s (201
# frames, csv + pvd), run twice: without checkpoints (fsync only at the finish) and with a
# checkpoint at every output (--checkpoint-every 1e-9: the worst case; the default is one every
# 300 s of wall time). For each: the number of fsync calls and the seconds spent in them
# (strace -c), and the run's wall and CPU seconds without strace (the best of REPEAT runs,
# default 3). With OTHER_LRIGID (a build from before fsync) the same runs with it, for the
# difference.
# usage: bench/perf/fsync_cost.sh [LRIGID] [OTHER_LRIGID] [BODIES] [REPEAT]
#   e.g. bench/perf/fsync_cost.sh build/bin/lrigid
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
lrigid=$(realpath "${1:-$here/build/bin/lrigid}")
other=${2:-}
[ -n "$other" ] && other=$(realpath "$other")
bodies=${3:-1000}
repeat=${4:-3}
command -v strace > /dev/null || { echo "fsync_cost: needs strace (scripts/install-deps)"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
cat > scene.json <<JSON
{
  "fluid": { "density": 1.2, "kinematic_viscosity": 1.5e-5,
             "uniform": { "U": [1, 0, 0], "k": 0.1, "epsilon": 0.05 } },
  "gravity": [0, 0, -9.81],
  "effects": "auto",
  "integrator": { "scheme": "splitting", "dt": 0.002 },
  "duration": 2, "seed": 1,
  "bodies": [ { "name": "bead", "shape": { "type": "sphere", "radius": 0.003 }, "density": 30,
                "count": $bodies, "spawn_box": [[0, 0, 10], [1, 1, 11]] } ],
  "output": { "dir": "out", "every": 0.01, "formats": ["csv", "pvd"], "checkpoint_every": 0 }
}
JSON
df -T . | tail -1 | awk '{print "fsync_cost: file system " $2 " (" $7 ")"}'
echo "fsync_cost: $bodies bodies, 201 frames, csv + pvd; load average $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%-8s %-22s %8s %10s %8s %8s\n' binary checkpoints fsyncs "fsync s" "wall s" "CPU s"
measure() {  # measure NAME BINARY CHECKPOINT_EVERY LABEL
  local name=$1 bin=$2 every=$3 label=$4 calls secs best_wall=1e9 best_cpu=1e9 w c k
  rm -rf out
  strace -f -c -o strace.txt -e trace=fsync,fdatasync \
    "$bin" run scene.json -o out --quiet --threads 1 --checkpoint-every "$every" 2> /dev/null
  calls=$(awk '$NF == "fsync" || $NF == "fdatasync" {n += $4} END {print n + 0}' strace.txt)
  secs=$(awk '$NF == "fsync" || $NF == "fdatasync" {s += $2} END {printf "%.3f", s + 0}' strace.txt)
  for ((k = 0; k < repeat; ++k)); do
    rm -rf out
    /usr/bin/time -f '%e %U %S' -o time.txt \
      "$bin" run scene.json -o out --quiet --threads 1 --checkpoint-every "$every" 2> /dev/null
    read -r w u s < time.txt
    c=$(awk -v u="$u" -v s="$s" 'BEGIN {print u + s}')
    best_wall=$(awk -v a="$w" -v b="$best_wall" 'BEGIN {print (a < b) ? a : b}')
    best_cpu=$(awk -v a="$c" -v b="$best_cpu" 'BEGIN {print (a < b) ? a : b}')
  done
  printf '%-8s %-22s %8s %10s %8s %8s\n' "$name" "$label" "$calls" "$secs" "$best_wall" "$best_cpu"
}
for pair in "this:$lrigid" ${other:+"other:$other"}; do
  name=${pair%%:*} bin=${pair#*:}
  measure "$name" "$bin" 0 "none (finish only)"
  measure "$name" "$bin" 1e-9 "at every output (201)"
done
