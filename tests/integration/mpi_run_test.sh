#!/bin/bash
# mpirun -np 2 lrigid run writes the same result as one process (docs/scaling.md):
# every output file byte for byte, summary.json except its timing fields and "ranks".
# usage: mpi_run_test.sh SOURCE_DIR LRIGID
set -euo pipefail
src=$1 lrigid=$2
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
# the uniform box, short, with body counts that do not split evenly over the ranks
/usr/bin/python3 - "$src/scenes/uniform_box.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s["duration"] = 0.3
s["bodies"][0]["count"], s["bodies"][1]["count"] = 21, 20
s["output"] = {"dir": "out", "every": 0.05, "formats": ["csv", "pvd"]}
json.dump(s, open("scene.json", "w"), indent=1)
PY
"$lrigid" run scene.json -o serial --threads 1 --quiet
mpirun -np 2 "$lrigid" run scene.json -o ranks2 --threads 1 --quiet
mpirun -np 2 "$lrigid" run scene.json -o ranks2_seed8 --seed 8 --threads 1 --quiet

compare() {  # compare A B: 0 when every file but summary.json is identical and summary.json
             # differs only in ranks, wall_seconds and body_steps_per_second
  local a=$1 b=$2 f
  [ "$(cd "$a" && find . -type f | sort)" = "$(cd "$b" && find . -type f | sort)" ] || {
    echo "different file lists in $a and $b"; return 1; }
  for f in $(cd "$a" && find . -type f ! -name summary.json | sort); do
    cmp -s "$a/$f" "$b/$f" || { echo "$f differs between $a and $b"; return 1; }
  done
  /usr/bin/python3 - "$a/summary.json" "$b/summary.json" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
skip = {"ranks", "wall_seconds", "body_steps_per_second"}
diff = sorted(k for k in set(a) | set(b) if k not in skip and a.get(k) != b.get(k))
if diff:
    sys.exit("summary.json differs in %s" % ", ".join(diff))
if b.get("ranks") != 2:
    sys.exit("summary.json of the mpirun run does not say ranks = 2: %r" % b.get("ranks"))
PY
}
compare serial ranks2
echo "mpi_run_test: mpirun -np 2 gives the serial result ($(find serial -type f | wc -l) files)"
# the comparison can fail: another seed must give another result
if compare serial ranks2_seed8 > /dev/null 2>&1; then
  echo "mpi_run_test: FAILED: a run with another seed compared equal" >&2
  exit 1
fi
# bodies colliding with each other (body_contact "collide"): every rank steps every body, and
# pairs of bodies of both ranks' shares collide; the result is the serial one
cp "$src/tests/integration/body_contact_pile.json" pile.json
"$lrigid" run pile.json -o pile_serial --threads 1 --quiet
mpirun -np 2 "$lrigid" run pile.json -o pile_ranks2 --threads 1 --quiet
/usr/bin/python3 - pile_serial/summary.json <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
if not s["body_contact"]["pair_steps"] > 0:
    sys.exit("mpi_run_test: FAILED: the pile scene has no touching pairs: %r" % s["body_contact"])
PY
compare pile_serial pile_ranks2
echo "mpi_run_test: bodies colliding: mpirun -np 2 gives the serial result"
echo "mpi_run_test: passed"
