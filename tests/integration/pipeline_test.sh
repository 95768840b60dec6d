#!/bin/bash
# End to end: the tiny OpenFOAM case -> foam2grid -> lrigid run, in the build tree.
# Checks: the run completes with no failed body; results are bitwise identical for 1 and 2
# threads; tracers released upstream are carried downstream by the mean flow and leave through
# the outlet; a run whose grid is missing fails with exit code 3 and leaves no output.
# usage: pipeline_test.sh SOURCE_DIR BINARY_DIR
set -u
src=$1
bin=$2
work=$bin/tests/integration/pipeline
fail() { echo "FAIL: $*" >&2; exit 1; }

mkdir -p "$work"
cd "$work" || exit 1
if [ ! -f tiny/.done ]; then
  rm -rf tiny
  cp -r "$src/foam_cases/tiny" tiny
  FOAM_CASES_DIR=$src/foam_cases ./tiny/Allrun > tiny.log 2>&1 || { tail -20 tiny.log; fail "tiny case"; }
  touch tiny/.done
fi
"$bin/bin/foam2grid" tiny -o tiny.vti --resolution 49 17 13 -q || fail "foam2grid"

cat > scene.json <<'JSON'
{
  "version": 1,
  "fluid": { "density": 1.2, "kinematic_viscosity": 1.5e-5, "field": "tiny.vti" },
  "gravity": [0, 0, -9.81],
  "effects": ["gravity", "buoyancy", "added_mass", "drag", "mean_flow", "turbulence"],
  "integrator": { "scheme": "strang", "dt": 0.001 },
  "duration": 1.5,
  "seed": 3,
  "turbulence": { "model": "seen", "drift": "stationary" },
  "bodies": [
    { "name": "tracer", "shape": { "type": "sphere", "radius": 5e-5 }, "density": 1.2,
      "count": 100, "spawn_box": [[0.02, 0.03, 0.18], [0.08, 0.37, 0.27]] },
    { "name": "flake", "shape": { "type": "box", "size": [0.01, 0.008, 0.0005] }, "density": 400,
      "count": 50, "spawn_box": [[0.02, 0.03, 0.18], [0.08, 0.37, 0.27]], "orientation": "random" }
  ],
  "output": { "every": 0.05, "formats": ["csv", "pvd"] }
}
JSON
"$bin/bin/lrigid" run scene.json -o out1 --threads 1 --quiet || fail "lrigid run (1 thread)"
"$bin/bin/lrigid" run scene.json -o out2 --threads 2 --quiet || fail "lrigid run (2 threads)"
cmp -s out1/trajectories.csv out2/trajectories.csv || fail "results differ between 1 and 2 threads"
for f in summary.json bodies.pvd trajectories.csv; do [ -s out1/$f ] || fail "missing out1/$f"; done
ls out1/bodies/bodies_*.vtp > /dev/null || fail "no .vtp frames"

/usr/bin/python3 - out1 <<'PY' || fail "result checks"
import csv, json, sys
d = sys.argv[1]
s = json.load(open(d + "/summary.json"))
assert s["bodies"] == 150, s["bodies"]
assert s["failed"] == 0, s["stopped"]
last = {}
first = {}
for r in csv.DictReader(open(d + "/trajectories.csv")):
    b = int(r["body"])
    first.setdefault(b, r)
    last[b] = r
# tracers (air-density spheres of 0.1 mm) follow the 2 m/s mean flow: by 1.5 s every one has
# left the grid; each stops at the grid's boundary (outlet, or the channel walls that turbulent
# dispersion carries it to) or at the cube's surface, never in the open fluid
h = 0.025  # grid spacing
def at_boundary(r):
    x, y, z = (float(r[k]) for k in "xyz")
    near_box = x > 1.2 - 2 * h or y < 2 * h or y > 0.4 - 2 * h or z < 2 * h or z > 0.3 - 2 * h
    near_cube = 0.3 - 2 * h < x < 0.45 + 2 * h and 0.125 - 2 * h < y < 0.275 + 2 * h and z < 0.15 + 2 * h
    return near_box or near_cube
tracers = [b for b in last if last[b]["type"] == "tracer"]
assert all(last[b]["t"] != first[b]["t"] for b in tracers)
stopped = {e["body"]: e for e in s["stopped"]}
assert all(b in stopped and stopped[b]["status"] == "exited" for b in tracers), "a tracer still moving"
inside = [b for b in tracers if not at_boundary(last[b])]
assert not inside, f"tracers stopped in the open fluid: {inside}"
out = [b for b in tracers if float(last[b]["x"]) > 1.15]
print(f"tracers leaving through the outlet: {len(out)}/{len(tracers)}, the rest at the walls")
assert len(out) >= 0.8 * len(tracers), len(out)
# downstream mean speed: the outlet is 1.1 m away; a tracer in a 2 m/s stream takes ~0.55 s
t_out = sorted(stopped[b]["t"] for b in out)
median = t_out[len(t_out) // 2]
print(f"median time to the outlet: {median:.3f} s; bodies {s['bodies']}, exited {s['exited']}, failed {s['failed']}")
assert 0.35 < median < 0.8, median
PY

# a missing grid: exit code 3, the message names the file, nothing written
sed 's/tiny.vti/missing.vti/' scene.json > bad.json
rm -rf out_bad
"$bin/bin/lrigid" run bad.json -o out_bad --quiet 2> bad.err
rc=$?
[ $rc -eq 3 ] || fail "missing grid: exit code $rc, expected 3"
grep -q "missing.vti" bad.err || fail "missing grid: message does not name the file: $(cat bad.err)"
[ ! -e out_bad/summary.json ] && [ ! -e out_bad/trajectories.csv ] || fail "partial output left"
echo "1 passed, 0 failed"
