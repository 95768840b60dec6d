#!/bin/bash
# The explicit schemes on the batched step against a peer, measured in one run: lrigid's
# splitting, euler and rk4 on the leaves scene (batched, and on the scalar step: a copy of the
# scene with "batched": false), and MuJoCo 2.2's RK4 and Euler on the same falling plate
# (mujoco_harness --body leaf: the scene's leaf, a free box 6 x 4 x 0.04 cm of 600 kg/m^3, MuJoCo's
# ellipsoid fluid model, one body per model). All per CPU second of one thread. Prints a markdown
# table (docs/physics/integrators.md) and writes OUTDIR/explicit_schemes.json.
#
#   bench/peers/explicit_schemes.sh OUTDIR [--scene FILE] [--n N] [--build DIR]
#
# The scene's field must exist (scenes/leaves_wind.json: results/grids/windCourtyard.vti from
# ./Allrun). Run it niced on a shared machine: nice -n 19 bench/peers/explicit_schemes.sh OUT
set -euo pipefail

HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
OUT=${1:?usage: explicit_schemes.sh OUTDIR [--scene FILE] [--n N] [--build DIR]}
shift
SCENE="$ROOT/scenes/leaves_wind.json"
N=10000
BUILD="$ROOT/build"
while [ $# -gt 0 ]; do
  case "$1" in
    --scene) SCENE=$2; shift 2 ;;
    --n) N=$2; shift 2 ;;
    --build) BUILD=$2; shift 2 ;;
    *) echo "explicit_schemes.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)
SCENE=$(cd "$(dirname "$SCENE")" && pwd)/$(basename "$SCENE")
for b in lrigid mujoco_harness; do
  [ -x "$BUILD/bin/$b" ] || { echo "explicit_schemes.sh: $BUILD/bin/$b missing" >&2; exit 1; }
done
LOAD_START=$(cut -d' ' -f1-3 /proc/loadavg)
DATE=$(date -u +%Y-%m-%dT%H:%M:%SZ)

# the scene with the batched step off, beside it (its relative field path still resolves)
SCALAR=$(mktemp "$(dirname "$SCENE")/.explicit_XXXXXX.json")
trap 'rm -f "$SCALAR"' EXIT
/usr/bin/python3 - "$SCENE" "$SCALAR" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s.setdefault("integrator", {})["batched"] = False
json.dump(s, open(sys.argv[2], "w"))
PY

DT=$(/usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["integrator"]["dt"])' "$SCENE")
"$BUILD/bin/mujoco_harness" --n "$N" --dt "$DT" --steps 100 --body leaf > "$OUT/mujoco_leaf.json"
"$BUILD/bin/lrigid" bench "$SCENE" --n "$N" --integrators splitting,euler,rk4 --threads 1 \
  --quiet --json "$OUT/batched.json"
"$BUILD/bin/lrigid" bench "$SCALAR" --n "$N" --integrators splitting,euler,rk4 --threads 1 \
  --body-steps 1000000 --quiet --json "$OUT/scalar.json"
LOAD_END=$(cut -d' ' -f1-3 /proc/loadavg)

/usr/bin/python3 - "$OUT" "$DATE" "$LOAD_START" "$LOAD_END" "$N" "$DT" <<'PY'
import json, os, sys
out, date, load0, load1, n, dt = sys.argv[1:]
mj = json.load(open(os.path.join(out, "mujoco_leaf.json")))["one_body_per_model"]


def rates(name):
    d = json.load(open(os.path.join(out, name)))
    return {r["integrator"]: r["body_steps_per_cpu_s"] for r in d["runs"]}


b, s = rates("batched.json"), rates("scalar.json")
peer = {"euler": mj["euler"], "rk4": mj["rk4"]}
res = {"date": date, "load": "%s (start) / %s (end)" % (load0, load1), "n": int(n),
       "dt": float(dt), "batched": b, "scalar": s, "mujoco_leaf": peer}
json.dump(res, open(os.path.join(out, "explicit_schemes.json"), "w"), indent=1)


def m(x):
    return "%.3g M" % (x / 1e6) if x >= 1e6 else "%.0f k" % (x / 1e3)


print("%s, N = %s, dt = %s s, load %s" % (date, n, dt, res["load"]))
print("")
print("| scheme | scalar step | batched step | batched / scalar | batched / batched `splitting` "
      "| MuJoCo on the leaf | lrigid batched / MuJoCo |")
print("|---|---|---|---|---|---|---|")
for k in ("splitting", "euler", "rk4"):
    p = peer.get(k)
    print("| `%s` | %s | %s | %.1f | %.2f | %s | %s |" % (
        k, m(s[k]), m(b[k]), b[k] / s[k], b[k] / b["splitting"],
        ("%s %s" % ("Euler" if k == "euler" else "RK4", m(p))) if p else "",
        ("%.1f" % (b[k] / p)) if p else ""))
PY
