#!/bin/bash
# The box pile side by side: lrigid, Bullet 3.24 and MuJoCo 2.2 (Debian's packages) drop the same
# pile of boxes onto the ground under gravity, at the same time step, from the same initial
# poses (bench/peers/pile.md). Writes OUTDIR/pile.json:
#   {"lrigid"|"bullet"|"mujoco": {"body_steps_per_s", "max_overlap_m", "final_overlap_m",
#    "kinetic_energy_J", "height_m", "params", "n", ...}, "n", "dt", "steps", "machine", "date",
#    "commit", "load"}
# and each engine's full report (with the measures every 0.1 s) as OUTDIR/<engine>.json.
# All rates are per core (one process, one thread), the stepping only.
#
#   bench/peers/run_pile.sh OUTDIR [--n N] [--steps S] [--mujoco-n M] [--build DIR]
#                           [--skip-lrigid] [--skip-bullet] [--skip-mujoco]
#                           [--bullet-args "..."] [--mujoco-args "..."]
#
# --n: bodies (default: pile.json's count, 10000); --steps: steps (default: its duration / dt).
# --mujoco-n: MuJoCo's pile (default min(N, 600)): MuJoCo 2.2 cannot hold more in one model
# (pile_mujoco.cpp); it gets the pile of the same recipe with M boxes, the same height.
# lrigid runs pile.json's scene only when the lrigid binary accepts its "body_contact" key;
# otherwise its entry says so and holds no numbers.
#
# Run it niced on a shared machine: nice -n 19 bench/peers/run_pile.sh OUT
set -euo pipefail

HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
usage="usage: run_pile.sh OUTDIR [--n N] [--steps S] [--mujoco-n M] [--build DIR] [--skip-lrigid] [--skip-bullet] [--skip-mujoco] [--bullet-args ARGS] [--mujoco-args ARGS]"
[ $# -ge 1 ] && [ "${1#-}" = "$1" ] || { echo "run_pile.sh: $usage" >&2; exit 2; }
OUT=$1
shift
N=""
STEPS=""
MJ_N=""
BUILD="$ROOT/build"
DO_LRIGID=1
DO_BULLET=1
DO_MUJOCO=1
BULLET_ARGS=""
MUJOCO_ARGS=""
int_arg() {  # flag value
  [[ "$2" =~ ^[1-9][0-9]*$ ]] || { echo "run_pile.sh: $1 needs a positive integer, got '$2'" >&2; exit 2; }
}
while [ $# -gt 0 ]; do
  case "$1" in
    --n) [ $# -ge 2 ] || { echo "run_pile.sh: --n needs a value" >&2; exit 2; }; int_arg "$1" "$2"; N=$2; shift 2 ;;
    --steps) [ $# -ge 2 ] || { echo "run_pile.sh: --steps needs a value" >&2; exit 2; }; int_arg "$1" "$2"; STEPS=$2; shift 2 ;;
    --mujoco-n) [ $# -ge 2 ] || { echo "run_pile.sh: --mujoco-n needs a value" >&2; exit 2; }; int_arg "$1" "$2"; MJ_N=$2; shift 2 ;;
    --build) [ $# -ge 2 ] || { echo "run_pile.sh: --build needs a value" >&2; exit 2; }; BUILD=$2; shift 2 ;;
    --bullet-args) [ $# -ge 2 ] || { echo "run_pile.sh: --bullet-args needs a value" >&2; exit 2; }; BULLET_ARGS=$2; shift 2 ;;
    --mujoco-args) [ $# -ge 2 ] || { echo "run_pile.sh: --mujoco-args needs a value" >&2; exit 2; }; MUJOCO_ARGS=$2; shift 2 ;;
    --skip-lrigid) DO_LRIGID=0; shift ;;
    --skip-bullet) DO_BULLET=0; shift ;;
    --skip-mujoco) DO_MUJOCO=0; shift ;;
    *) echo "run_pile.sh: unknown option $1; $usage" >&2; exit 2 ;;
  esac
done
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)
LOAD_START=$(cut -d' ' -f1-3 /proc/loadavg)
PY=/usr/bin/python3

# the pile: poses, lrigid's scene, the harnesses' flags (one definition: pile.json)
gen_args=()
[ -n "$N" ] && gen_args+=(--n "$N")
[ -n "$STEPS" ] && gen_args+=(--steps "$STEPS")
FLAGS=$($PY "$HERE/pile_poses.py" "$HERE/pile.json" "$OUT/pile" "${gen_args[@]}")
N=$(echo "$FLAGS" | sed -n 's/.*--n \([0-9]*\).*/\1/p')
STEPS=$(echo "$FLAGS" | sed -n 's/.*--steps \([0-9]*\).*/\1/p')
DT=$(echo "$FLAGS" | sed -n 's/.*--dt \([^ ]*\).*/\1/p')
COMMON="--poses $OUT/pile/poses.csv $FLAGS"

for e in lrigid bullet mujoco; do echo '{"status": "skipped"}' > "$OUT/$e.json"; done
if [ "$DO_LRIGID" = 1 ]; then
  L="$BUILD/bin/lrigid"
  M="$BUILD/bin/pile_measure"
  [ -x "$L" ] || { echo "run_pile.sh: $L missing (build lrigid)" >&2; exit 1; }
  [ -x "$M" ] || { echo "run_pile.sh: $M missing (build pile_measure)" >&2; exit 1; }
  set +e
  CHECK=$("$L" explain "$OUT/pile/pile_lrigid.json" 2>&1 >/dev/null)
  RC=$?
  set -e
  if [ $RC -ne 0 ] && echo "$CHECK" | grep -q 'unknown key "body_contact"'; then
    echo "run_pile.sh: this lrigid ($L) does not accept the scene key \"body_contact\" yet: no lrigid numbers" >&2
    echo '{"status": "not run: this lrigid does not accept the scene key \"body_contact\" (collisions between bodies) yet"}' > "$OUT/lrigid.json"
  elif [ $RC -ne 0 ]; then
    echo "run_pile.sh: lrigid explain refused the pile's scene:" >&2
    echo "$CHECK" >&2
    exit 1
  else
    rm -rf "$OUT/lrigid_run"
    "$L" run "$OUT/pile/pile_lrigid.json" -o "$OUT/lrigid_run" --threads 1 --quiet
    read -r BS WS < <($PY -c '
import json, sys
s = json.load(open(sys.argv[1]))
print(s["body_steps"], s["wall_seconds"])' "$OUT/lrigid_run/summary.json")
    "$M" --trajectories "$OUT/lrigid_run/trajectories.csv" --body-steps "$BS" --seconds "$WS" \
      --params '{"scene": "bench/peers/pile.json", "threads": 1, "timing": "summary.json wall_seconds (integration only)"}' \
      $COMMON > "$OUT/lrigid.json"
  fi
fi

if [ "$DO_BULLET" = 1 ]; then
  B="$BUILD/bin/pile_bullet"
  [ -x "$B" ] || { echo "run_pile.sh: $B missing (install libbullet-dev, build pile_bullet)" >&2; exit 1; }
  # shellcheck disable=SC2086
  "$B" $COMMON $BULLET_ARGS > "$OUT/bullet.json"
fi

if [ "$DO_MUJOCO" = 1 ]; then
  H="$BUILD/bin/pile_mujoco"
  [ -x "$H" ] || { echo "run_pile.sh: $H missing (install libmujoco-dev, build pile_mujoco)" >&2; exit 1; }
  [ -n "$MJ_N" ] || MJ_N=$(( N < 600 ? N : 600 ))
  if [ "$MJ_N" = "$N" ]; then
    MJ_COMMON=$COMMON
  else
    MJ_FLAGS=$($PY "$HERE/pile_poses.py" "$HERE/pile.json" "$OUT/pile_mujoco" --n "$MJ_N" --steps "$STEPS")
    MJ_COMMON="--poses $OUT/pile_mujoco/poses.csv $MJ_FLAGS"
  fi
  # shellcheck disable=SC2086
  # in OUTDIR: MuJoCo writes its warnings to MUJOCO_LOG.TXT in the working directory
  (cd "$OUT" && "$H" $MJ_COMMON $MUJOCO_ARGS > "$OUT/mujoco.json")
fi

LOAD_END=$(cut -d' ' -f1-3 /proc/loadavg)
MACHINE="$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1), $(nproc) cores"
COMMIT=$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)
# the summary: each engine's report without its samples, which stay in OUTDIR/<engine>.json
$PY - "$OUT" <<EOF
import json, os, sys
def short(engine):
    d = json.load(open(os.path.join(sys.argv[1], engine + ".json")))
    d.pop("samples", None)
    return d
out = {
    "lrigid": short("lrigid"),
    "bullet": short("bullet"),
    "mujoco": short("mujoco"),
    "n": $N, "dt": $DT, "steps": $STEPS,
    "rates": "body-steps per second of one process on one thread, stepping only (CPU time; lrigid: integration wall time with --threads 1)",
    "nice": $(nice),
    "machine": "$MACHINE",
    "date": "$(date -u +%Y-%m-%dT%H:%M:%SZ)",
    "commit": "$COMMIT",
    "load": "$LOAD_START (start) / $LOAD_END (end)",
}
json.dump(out, open(os.path.join(sys.argv[1], "pile.json.tmp"), "w"), indent=2)
EOF
mv "$OUT/pile.json.tmp" "$OUT/pile.json"
cat "$OUT/pile.json"
