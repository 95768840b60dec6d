#!/bin/bash
# Ranks x threads scaling of `lrigid run`: `mpirun -np R lrigid run SCENE
# --threads T` on the wind scene scaled to N bodies, for every R x T <= the number of cores (more
# would oversubscribe the cores and measure the scheduler, not the code). Writes OUT/scaling.json
# (read by bench/perf/make_report.py for docs/scaling.md): per (R, T) the integration wall (the
# slowest rank's, summary.json wall_seconds: the step only, no set-up, gathers or writes), the
# process wall, CPU user+sys of all ranks and peak RSS (/usr/bin/time -v), and the speedup and
# efficiency against R = T = 1; and body-steps per CPU second of the steps alone (two runs of
# `steps` and 2 x `steps` steps: the difference), which the other jobs on a shared machine do not
# change, so R x T x that rate's efficiency estimates the speedup on idle cores.
#
#   bench/perf/scaling_bench.sh OUT [--n N] [--steps S] [--build DIR] [--repeat K]
#                                [--max-cores C]
#     --n        bodies (default 100000: the step dominates set-up and output)
#     --steps    time steps (default 50, dt = 0.002 s)
#     --repeat   runs per configuration, the fastest kept (default 2)
#     --max-cores  largest R x T (default: nproc)
# Ranks run with --bind-to none, so a rank's T threads may use every core.
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$PWD
out=${1:?usage: scaling_bench.sh OUT [--n N] [--steps S] [--build DIR] [--repeat K]}
shift
n=100000
steps=50
build=build
repeat=2
maxc=$(nproc)
while [ $# -gt 0 ]; do
  case "$1" in
    --n) n=$2; shift 2 ;;
    --steps) steps=$2; shift 2 ;;
    --build) build=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --max-cores) maxc=$2; shift 2 ;;
    *) echo "scaling_bench.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
lrigid=$root/$build/bin/lrigid
[ -x "$lrigid" ] || lrigid=$build/bin/lrigid
[ -x "$lrigid" ] || { echo "scaling_bench.sh: $lrigid missing: build lrigid" >&2; exit 1; }
[ -f results/grids/windCourtyard.vti ] ||
  { echo "scaling_bench.sh: results/grids/windCourtyard.vti missing (./Allrun)" >&2; exit 1; }
command -v mpirun > /dev/null || { echo "scaling_bench.sh: no mpirun (openmpi-bin)" >&2; exit 1; }
mkdir -p "$out"
out=$(cd "$out" && pwd)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

# the wind scene with n bodies in its proportions, `steps` steps (scene.1.json) and 2 x `steps`
# (scene.2.json), one output at the end: the CPU time of the second minus the first is the CPU
# time of `steps` steps alone (set-up, MPI start-up and the writes cancel)
for k in 1 2; do
/usr/bin/python3 - scenes/leaves_wind.json "$root/results/grids/windCourtyard.vti" "$n" \
  "$((k * steps))" "$out/scene.$k.json" <<'PY'
import json, sys
src, field, n, steps, dst = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), sys.argv[5]
s = json.load(open(src))
s["fluid"]["field"] = field
total = sum(b["count"] for b in s["bodies"])
left = n
for i, b in enumerate(s["bodies"]):
    c = left if i == len(s["bodies"]) - 1 else round(n * b["count"] / total)
    b["count"] = min(c, left)
    left -= b["count"]
s["duration"] = steps * s["integrator"]["dt"]
s["output"] = {"dir": "out", "every": s["duration"], "formats": ["csv"]}
json.dump(s, open(dst, "w"), indent=1)
PY
done

load_before=$(cut -d' ' -f1-3 /proc/loadavg)
runs=()
for r in 1 2 4 8; do
  for t in 1 2 4 8; do
    [ $((r * t)) -le "$maxc" ] || continue
    for i in $(seq "$repeat"); do
      spec="$r $t"
      for k in 1 2; do
        log=$out/time.r$r.t$t.$i.$k.log
        rm -rf "$out/run"
        /usr/bin/time -v mpirun --bind-to none -np "$r" "$lrigid" run "$out/scene.$k.json" \
          -o "$out/run" --threads "$t" --quiet 2> "$log" || { cat "$log" >&2; exit 1; }
        cp "$out/run/summary.json" "$out/summary.r$r.t$t.$i.$k.json"
        spec+=" $log $out/summary.r$r.t$t.$i.$k.json"
      done
      runs+=("$spec")
      echo "scaling_bench.sh: $r rank(s) x $t thread(s), run $i done" >&2
    done
  done
done
load_after=$(cut -d' ' -f1-3 /proc/loadavg)
rm -rf "$out/run"

/usr/bin/python3 bench/perf/collect.py scaling "$out/scaling.json" "$n" "$steps" "$maxc" \
  "$load_before" "$load_after" "${runs[@]}"
echo "scaling_bench.sh: wrote $out/scaling.json" >&2
