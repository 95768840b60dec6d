#!/bin/bash
# Measures the runtime's throughput, this machine's limits, the peers, the converter, streaming
# and ranks x threads scaling, and writes docs/performance.md and the generated tables of
# docs/scaling.md. Run from anywhere after a Release build, niced on a shared machine:
#   nice -n 19 bench/perf/run_perf.sh [--quick] [--no-flops] [--peers FILE]... [--no-peers]
#       [--wind-case DIR] [--no-converter] [--no-stream] [--no-scaling] [--no-batch]
#       [--tank-series FILE.pvd]
#       [--build DIR] [--out DIR]
#   --quick       N up to 10^5, shorter runs, one repeat, peers at N = 10^3 only (a check of the
#                 script, not for the docs: about 5 min)
#   --no-flops    skip the lackey flop count (slow: minutes)
#   --peers FILE  use bench/peers/run_peers.sh's peers.json (repeatable) instead of running the
#                 peers; --no-peers: neither
#   --wind-case   a solved windCourtyard case for the peers (else solved once, in OUT/peers_1000)
#   --no-converter, --no-stream, --no-scaling, --no-batch: skip bench/converter/run_benchmark.sh
#                 (1 M cells, its case cached in /tmp/foam2grid-bench), bench/perf/stream_bench.sh,
#                 bench/perf/scaling_bench.sh, bench/perf/batch_bench.py (the batched
#                 steps against the scalar one and the peers: docs/batched-step.md)
#   --tank-series the tank .pvd series for the streaming table (default results/grids/tankJet.pvd)
# Needs results/grids/windCourtyard.vti (./Allrun), results/grids/tankJet.pvd (./Allrun -all;
# for the streaming table), valgrind, mpirun, /usr/bin/time, OpenFOAM and mujoco_harness.
# The full run takes about 15 min on 2 cores (measured at load 5, niced).
set -euo pipefail
cd "$(dirname "$0")/../.."
build=build
out=build/perf
peers=()
run_peers=1
wind=""
quick=0
flops=1
converter=1
stream=1
scaling=1
batch=1
series=results/grids/tankJet.pvd
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1 ;;
    --no-flops) flops=0 ;;
    --peers) peers+=("$2"); run_peers=0; shift ;;
    --no-peers) run_peers=0 ;;
    --wind-case) wind="$2"; shift ;;
    --no-converter) converter=0 ;;
    --no-stream) stream=0 ;;
    --no-scaling) scaling=0 ;;
    --no-batch) batch=0 ;;
    --tank-series) series="$2"; shift ;;
    --build) build="$2"; shift ;;
    --out) out="$2"; shift ;;
    *) echo "run_perf.sh: unknown argument $1" >&2; exit 2 ;;
  esac
  shift
done
bin="$build/bin"
for x in lrigid step_bench roofline_bench; do
  [ -x "$bin/$x" ] || { echo "run_perf.sh: $bin/$x missing: build the Release tree first" >&2; exit 1; }
done
[ -f results/grids/windCourtyard.vti ] || { echo "run_perf.sh: results/grids/windCourtyard.vti missing (./Allrun)" >&2; exit 1; }
# what the later parts need, checked before the first half hour is spent
need() { [ "$1" = 0 ] || [ -e "$2" ] || { echo "run_perf.sh: $2 missing ($3)" >&2; exit 1; }; }
need $stream "$series" "./Allrun -all, or --tank-series FILE.pvd, or --no-stream"
need $converter "$bin/foam2grid" "build foam2grid, or --no-converter"
need $run_peers "$bin/mujoco_harness" "install libmujoco-dev and build, or --no-peers"
need $run_peers /usr/bin/icoUncoupledKinematicParcelFoam "OpenFOAM (scripts/install-deps), or --no-peers"
need $scaling "$(command -v mpirun || echo mpirun)" "openmpi-bin, or --no-scaling"
need 1 /usr/bin/time "the time package (scripts/install-deps)"
mkdir -p "$out"
scene=scenes/leaves_wind.json

# machine description
ghz=$(awk -F: '/cpu MHz/ {printf "%.2f", $2 / 1000; exit}' /proc/cpuinfo)
cat > "$out/machine.json" <<EOF
{"date": "$(date -u '+%Y-%m-%d %H:%M')",
 "cpu": "$(awk -F': ' '/model name/ {print $2; exit}' /proc/cpuinfo), ${ghz} GHz",
 "ghz": ${ghz:-0},
 "cores": "$(nproc)",
 "memory": "$(awk '/MemTotal/ {printf "%.1f GiB", $2 / 1048576}' /proc/meminfo)",
 "compiler": "$(${CXX:-c++} --version | head -1)",
 "flags": "$(grep -E '^CMAKE_BUILD_TYPE|^CMAKE_CXX_FLAGS_RELEASE' "$build/CMakeCache.txt" | sed 's/.*=//' | tr '\n' ' ')",
 "commit": "$(git rev-parse --short HEAD)$(git diff --quiet HEAD -- runtime || echo ' (modified)')",
 "load_before": "$(cut -d' ' -f1-3 /proc/loadavg)"}
EOF

if [ $quick = 1 ]; then
  ns=1000,10000,100000; bsteps=3e5; lin_steps=10
else
  ns=1000,10000,100000,1000000; bsteps=1e6; lin_steps=40
fi
echo "run_perf.sh: lrigid bench (N = $ns)" >&2
"$bin/lrigid" bench $scene --effects all --n $ns --threads 1,2 --body-steps $bsteps --min-steps 2 --json "$out/bench.json"
# linearity in N: the same steps (the same simulated window) at every N. The splitting step's
# cost changes along the trajectory (its implicit iterations are data-dependent), so the fixed
# body-step budget above gives each N a different window and a different cost.
# Two passes; the report takes the faster of the two at each point (this VM's host shows
# slow episodes of a minute or so that would otherwise read as a cost growing with N).
for pass in 1 2; do
  echo "run_perf.sh: lrigid bench, $lin_steps steps at every N (pass $pass of 2)" >&2
  "$bin/lrigid" bench $scene --effects all --n $ns --threads 1 --body-steps 1 --min-steps $lin_steps \
    --warmup 2 --json "$out/bench_linear.$pass.json"
done
rm -f "$out/bench_linear.json"
echo "run_perf.sh: kernels" >&2
"$bin/step_bench" --benchmark_min_time=0.3 --benchmark_format=json \
  --benchmark_out="$out/step_bench.json" --benchmark_out_format=json > /dev/null
"$bin/roofline_bench" --benchmark_min_time=0.5 --benchmark_out="$out/roofline.json" \
  --benchmark_out_format=json > /dev/null

# instructions per body-step inside the step (callgrind: step_body, and the batched blocks that
# take most bodies' steps; under valgrind their loops run the AVX2 build), and the top self
# costs of splitting
echo "run_perf.sh: callgrind" >&2
py='import json,sys; print(json.load(open(sys.argv[1]))["runs"][0]["body_steps"])'
cgjson="{\"per_body_step\": {"
sep=""
for integ in euler rk4 splitting; do
  f="$out/callgrind.$integ.out"
  valgrind --tool=callgrind --callgrind-out-file="$f" --toggle-collect='lrigid::step_body*' \
    --toggle-collect='lrigid::advance_*_block*' \
    "$bin/lrigid" bench $scene --effects all --n 1000 --integrators $integ --threads 1 --body-steps 4000 \
    --min-steps 4 --warmup 0 --quiet --json "$out/cg.$integ.json" 2> "$out/callgrind.$integ.log"
  ir=$(callgrind_annotate "$f" 2>/dev/null | awk '/PROGRAM TOTALS/ {gsub(",", "", $1); print $1}')
  bs=$(/usr/bin/python3 -c "$py" "$out/cg.$integ.json")
  cgjson+="$sep\"$integ\": $(awk -v a="$ir" -v b="$bs" 'BEGIN {printf "%.1f", a / b}')"
  sep=", "
done
top=$(callgrind_annotate --inclusive=no "$out/callgrind.splitting.out" 2>/dev/null |
  awk '/PROGRAM TOTALS/ {gsub(",", "", $1); tot = $1; next}
       /^ *[0-9,]+ +\( *[0-9.]+%\) +.*:/ && tot > 0 && n < 12 {
    v = $1; gsub(",", "", v); line = $0; sub(/^ *[0-9,]+ +\( *[0-9.]+%\) +/, "", line);
    sub(/^\?\?\?:/, "", line); gsub(/\(anonymous namespace\)/, "{anon}", line); sub(/\(.*/, "", line); gsub(/"/, "", line);
    printf "%s[\"%s\", %.4f]", (n ? ", " : ""), line, v / tot; n++}')
cgjson+="}, \"top\": [$top]}"
echo "$cgjson" > "$out/callgrind.json"

# floating-point operations per body-step: valgrind lackey's counts of F64/F32 operations of two
# runs that differ only in the number of steps (set-up cancels)
if [ $flops = 1 ]; then
echo "run_perf.sh: flop counts (lackey)" >&2
flops() {  # integrator steps -> F64, V128 and V256 operations (lackey's AluOps column)
  valgrind --tool=lackey --detailed-counts=yes "$bin/lrigid" bench $scene --effects all --n 200 \
    --integrators "$1" --threads 1 --body-steps 1 --min-steps "$2" --warmup 0 --quiet 2>&1 |
    awk '$2 == "F64" || $2 == "V128" || $2 == "V256" {v = $5; gsub(",", "", v); c[$2] = v}
         END {print c["F64"] + 0, c["V128"] + 0, c["V256"] + 0}'
}
fjson="{"
sep=""
for integ in euler rk4 splitting; do
  read -r a64 a128 a256 <<< "$(flops $integ 2)"
  read -r b64 b128 b256 <<< "$(flops $integ 6)"
  # flops ~ scalar F64 operations + 2 per 128-bit and 4 per 256-bit vector operation (an upper
  # bound: the vector counts include integer and logic operations)
  fjson+="$sep\"$integ\": $(awk -v a="$a64" -v b="$b64" -v c="$a128" -v d="$b128" \
    -v e="$a256" -v f="$b256" \
    'BEGIN {printf "%.1f", ((b - a) + 2 * (d - c) + 4 * (f - e)) / (4 * 200)}')"
  sep=", "
done
# field samples per body-step: the scalar euler and rk4 steps; the batched splitting step samples
# once (at the end of the step, which the next step and the Basset history reuse)
fjson+=", \"samples_per_step\": {\"euler\": 3, \"rk4\": 6, \"splitting\": 1}}"
echo "$fjson" > "$out/flops.json"
fi

/usr/bin/python3 - "$out/machine.json" <<'EOF'
import json, sys
m = json.load(open(sys.argv[1]))
m["load_after"] = " ".join(open("/proc/loadavg").read().split()[:3])
json.dump(m, open(sys.argv[1], "w"))
EOF
args=("$out")

# the peers at the same N as the bench (bench/peers/run_peers.sh): 2 x 10^6 parcel-steps
# each, since OpenFOAM's ExecutionTime has 0.01 s resolution; the wind case is solved once
if [ $run_peers = 1 ]; then
  if [ $quick = 1 ]; then pns="1000"; else pns="1000 10000"; fi
  for pn in $pns; do
    echo "run_perf.sh: peers, N = $pn" >&2
    psteps=$(( 2000000 / pn > 100 ? 2000000 / pn : 100 ))
    pargs=(--n "$pn" --steps "$psteps" --build "$build")
    # the first N solves the wind case into its directory (kept for reruns), the others use it
    [ -n "$wind" ] && pargs+=(--wind-case "$wind")
    bench/peers/run_peers.sh "$out/peers_$pn" "${pargs[@]}" > "$out/peers_$pn.log"
    [ -n "$wind" ] || wind=$out/peers_$pn/windCourtyard
    peers+=("$out/peers_$pn/peers.json")
  done
fi
for f in ${peers[@]+"${peers[@]}"}; do args+=(--peers "$f"); done

if [ $converter = 1 ]; then
  echo "run_perf.sh: converter (foam2grid, 1 M cells)" >&2
  if [ $quick = 1 ]; then rep=1; res=default; else rep=3; res="default 128"; fi
  REPEAT=$rep RESOLUTIONS=$res JSON="$out/converter.json" \
    bench/converter/run_benchmark.sh "$build" > "$out/converter.log"
  args+=(--converter "$out/converter.json")
fi
if [ $stream = 1 ]; then
  echo "run_perf.sh: streaming on/off (tank series)" >&2
  if [ $quick = 1 ]; then sargs=(--duration 5 --repeat 1); else sargs=(--repeat 2); fi
  bench/perf/stream_bench.sh "$out/stream" --build "$build" --series "$series" "${sargs[@]}"
  args+=(--stream "$out/stream/stream.json")
fi
if [ $scaling = 1 ]; then
  echo "run_perf.sh: ranks x threads" >&2
  if [ $quick = 1 ]; then
    cargs=(--n 20000 --steps 20 --repeat 1)
  else
    cargs=(--n 100000 --steps 50 --repeat 2)
  fi
  bench/perf/scaling_bench.sh "$out/scaling" --build "$build" "${cargs[@]}"
  args+=(--scaling "$out/scaling/scaling.json")
fi

if [ $batch = 1 ]; then
  echo "run_perf.sh: batched steps (batch_bench.py)" >&2
  bargs=(--build "$build" --out "$out/batch")
  [ $quick = 1 ] && bargs+=(--quick)
  if [ -n "$wind" ]; then
    bargs+=(--wind-case "$wind")
  elif [ $run_peers = 0 ]; then
    bargs+=(--no-peers)
  fi
  /usr/bin/python3 bench/perf/batch_bench.py "${bargs[@]}"
  args+=(--batch "$out/batch/batch.json")
fi
/usr/bin/python3 bench/perf/make_report.py "${args[@]}" --out docs/performance.md \
  --scaling-doc docs/scaling.md
echo "run_perf.sh: wrote docs/performance.md and docs/scaling.md (data in $out)" >&2
