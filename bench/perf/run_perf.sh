#!/bin/bash
# Measures the runtime's throughput and this machine's limits and writes docs/performance.md
# (issue 11). Run from the repository root after a Release build:
#   bench/perf/run_perf.sh [--quick] [--peers PEERS.json] [--build DIR] [--out DIR]
#   --quick   N up to 10^5 and shorter runs (a check of the script, not for the docs)
#   --no-flops skip the lackey flop count (slow: minutes)
#   --peers   bench/peers/run_peers.sh's OUTDIR/peers.json: ratios against the peers
# Needs results/grids/windCourtyard.vti (./Allrun) and valgrind (instruction and flop counts).
set -euo pipefail
cd "$(dirname "$0")/../.."
build=build
out=build/perf
peers=""
quick=0
flops=1
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1 ;;
    --no-flops) flops=0 ;;
    --peers) peers="$2"; shift ;;
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
  ns=1000,10000,100000; bsteps=3e5
else
  ns=1000,10000,100000,1000000; bsteps=1e6
fi
echo "run_perf.sh: lrigid bench (N = $ns)" >&2
"$bin/lrigid" bench $scene --n $ns --threads 1,2 --body-steps $bsteps --min-steps 2 --json "$out/bench.json"
echo "run_perf.sh: kernels" >&2
"$bin/step_bench" --benchmark_min_time=0.3 --benchmark_format=json \
  --benchmark_out="$out/step_bench.json" --benchmark_out_format=json > /dev/null
"$bin/roofline_bench" --benchmark_min_time=0.5 --benchmark_out="$out/roofline.json" \
  --benchmark_out_format=json > /dev/null

# instructions per body-step inside step_body (callgrind), and the top self costs of splitting
echo "run_perf.sh: callgrind" >&2
py='import json,sys; print(json.load(open(sys.argv[1]))["runs"][0]["body_steps"])'
cgjson="{\"per_body_step\": {"
sep=""
for integ in euler rk4 splitting; do
  f="$out/callgrind.$integ.out"
  valgrind --tool=callgrind --callgrind-out-file="$f" --toggle-collect='lrigid::step_body*' \
    "$bin/lrigid" bench $scene --n 1000 --integrators $integ --threads 1 --body-steps 4000 \
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
flops() {  # integrator steps -> F64 and V128 operations (lackey's AluOps column)
  valgrind --tool=lackey --detailed-counts=yes "$bin/lrigid" bench $scene --n 200 \
    --integrators "$1" --threads 1 --body-steps 1 --min-steps "$2" --warmup 0 --quiet 2>&1 |
    awk '$2 == "F64" || $2 == "V128" {v = $5; gsub(",", "", v); c[$2] = v}
         END {print c["F64"] + 0, c["V128"] + 0}'
}
fjson="{"
sep=""
for integ in euler rk4 splitting; do
  read -r a64 a128 <<< "$(flops $integ 2)"
  read -r b64 b128 <<< "$(flops $integ 6)"
  # flops ~ scalar F64 operations + 2 per 128-bit vector operation (an upper bound: V128 also
  # counts integer and logic vector operations)
  fjson+="$sep\"$integ\": $(awk -v a="$a64" -v b="$b64" -v c="$a128" -v d="$b128" \
    'BEGIN {printf "%.1f", ((b - a) + 2 * (d - c)) / (4 * 200)}')"
  sep=", "
done
fjson+=", \"samples_per_step\": {\"euler\": 3, \"rk4\": 6, \"splitting\": 4}}"
echo "$fjson" > "$out/flops.json"
fi

/usr/bin/python3 - "$out/machine.json" <<'EOF'
import json, sys
m = json.load(open(sys.argv[1]))
m["load_after"] = " ".join(open("/proc/loadavg").read().split()[:3])
json.dump(m, open(sys.argv[1], "w"))
EOF
args=("$out")
[ -n "$peers" ] && args+=(--peers "$peers")
/usr/bin/python3 bench/perf/make_report.py "${args[@]}" --out docs/performance.md
echo "run_perf.sh: wrote docs/performance.md (data in $out)" >&2
