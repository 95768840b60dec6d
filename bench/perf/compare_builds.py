#!/usr/bin/python3
"""Two builds of lrigid side by side: body-steps per CPU-second of every scene in scenes/ (the
scene's own effects, N bodies, one thread), for each integrator, measured alternately in one run
so that a noisy machine slows both alike. For a change that must not cost speed (every scene
within 3 % of OLD):

    bench/perf/compare_builds.py OLD_LRIGID NEW_LRIGID [--n 10000] [--rounds 3]
        [--integrators splitting,euler,rk4] [--scenes a.json,b.json] [--json OUT]
        [--contacts scene|stop] [--old-without-contacts]

The two builds run alternately, --rounds times each. Shown: the ratio of the best run of each
(other jobs only ever slow a run down) and the median of the rounds' ratios (each round's two
runs are side by side in time: robust to the load changing during the comparison). On a shared
virtual machine the memory-bound sampling varies by +-15 % run to run; read both columns. Scenes
whose field file is missing (results/grids/ from ./Allrun, ./Allrun -all) are skipped and listed.

Builds without contacts do not know the keys `walls`, `outside`,
`ground.contact` and `bodies[].contact`: --old-without-contacts gives OLD a copy of each scene
without them (OLD then stops bodies at the ground, as it always did). --contacts stop gives NEW
the scene with ground and walls in "stop" mode, so that a comparison of the physics steps is not
confounded with the cost of the contacts (measured on its own in bench/contacts/).

--new-without-crossing: NEW runs each scene with "turbulence": {"crossing_trajectories": false},
the seen-velocity model of builds that predate the crossing-trajectory correction, so that a
comparison with such a build weighs the step's code on the same physics (the correction's own
cost is then the difference with a run without this flag).

--icount: instead of CPU time, instructions per body-step under valgrind's callgrind (the
difference of a 40-step and a 10-step run, so that setup cancels; N = --n). Repeatable to the
instruction whatever else the machine does, so it works on a loaded machine; but valgrind has no
AVX-512, so the batched loops run their AVX2 version, and instructions are not cycles.
"""
import argparse
import contextlib
import glob
import json
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def field_present(scene):
    s = json.load(open(scene))
    f = s.get("fluid", {}).get("field")
    if not f:
        return True
    return os.path.exists(os.path.join(os.path.dirname(scene), f))


@contextlib.contextmanager
def scene_variant(scene, edit):
    """A copy of the scene edited by edit(dict), beside it (so that its relative field path still
    resolves), removed afterwards; the scene itself when edit is None."""
    if edit is None:
        yield scene
        return
    s = json.load(open(scene))
    edit(s)
    fd, path = tempfile.mkstemp(suffix=".json", prefix=".cmp_", dir=os.path.dirname(scene))
    try:
        with os.fdopen(fd, "w") as f:
            json.dump(s, f)
        yield path
    finally:
        os.unlink(path)


def without_contacts(s):
    s.pop("walls", None)
    s.pop("outside", None)
    if isinstance(s.get("ground"), dict):
        s["ground"].pop("contact", None)
    s.pop("contact", None)
    for b in s.get("bodies", []):
        if isinstance(b, dict):
            b.pop("contact", None)


def contacts_stop(s):
    if isinstance(s.get("ground"), dict):
        s["ground"]["contact"] = "stop"
    s["walls"] = {"contact": "stop"}


def without_crossing(s):
    t = s.get("turbulence")
    if not isinstance(t, dict):
        t = s["turbulence"] = {}
    t["crossing_trajectories"] = False


def combined(*edits):
    edits = [e for e in edits if e is not None]
    if not edits:
        return None

    def edit(s):
        for e in edits:
            e(s)
    return edit


def rate(lrigid, scene, n, integrator, body_steps):
    with tempfile.NamedTemporaryFile(suffix=".json") as out:
        subprocess.run([lrigid, "bench", scene, "--n", str(n), "--threads", "1",
                        "--integrators", integrator, "--effects", "auto", "--body-steps",
                        str(body_steps), "--min-steps", "10", "--warmup", "2", "--quiet",
                        "--json", out.name], check=True)
        return json.load(open(out.name))["runs"][0]["body_steps_per_cpu_s"]


def icount(lrigid, scene, n, integrator):
    def count(steps):
        env = dict(os.environ, OMP_NUM_THREADS="1")
        r = subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null",
                            lrigid, "bench", scene, "--n", str(n), "--threads", "1",
                            "--integrators", integrator, "--effects", "auto", "--body-steps", "1",
                            "--min-steps", str(steps), "--warmup", "0", "--quiet"],
                           env=env, capture_output=True, text=True, check=True)
        for line in r.stderr.splitlines():
            if "Collected :" in line:
                return int(line.split()[-1])
        raise RuntimeError("no callgrind total in: " + r.stderr[-500:])
    # per body-step; a higher rate is better, as for the CPU-time mode
    return 1.0 / ((count(40) - count(10)) / (30.0 * n))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--n", type=int, default=10000)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--integrators", default="splitting")
    ap.add_argument("--scenes", default="")
    ap.add_argument("--body-steps", type=float, default=1e6)
    ap.add_argument("--json", default="")
    ap.add_argument("--contacts", choices=["scene", "stop"], default="scene",
                    help="NEW runs the scene as it is, or with ground and walls in stop mode")
    ap.add_argument("--old-without-contacts", action="store_true",
                    help="OLD runs a copy of each scene without the contact keys")
    ap.add_argument("--new-without-crossing", action="store_true",
                    help="NEW runs each scene without the crossing-trajectory correction")
    ap.add_argument("--icount", action="store_true",
                    help="body-steps per instruction under callgrind instead of per CPU-second")
    a = ap.parse_args()
    scenes = a.scenes.split(",") if a.scenes else sorted(glob.glob(os.path.join(ROOT, "scenes",
                                                                                "*.json")))
    rows, skipped = [], []
    unit = "instr/step" if a.icount else "/cpu-s"
    print(f"{'scene':28s} {'integrator':10s} {'old ' + unit:>16s} {'new ' + unit:>16s} "
          f"{'new/old speed':>14s} {'median':>7s}")
    for scene in scenes:
        if not field_present(scene):
            skipped.append(os.path.basename(scene))
            continue
        old_edit = without_contacts if a.old_without_contacts else None
        new_edit = combined(contacts_stop if a.contacts == "stop" else None,
                            without_crossing if a.new_without_crossing else None)
        with scene_variant(scene, old_edit) as old_scene, \
                scene_variant(scene, new_edit) as new_scene:
            for integ in a.integrators.split(","):
                best = {"old": 0.0, "new": 0.0}
                ratios = []
                if a.icount:
                    best = {"old": icount(a.old, old_scene, a.n, integ),
                            "new": icount(a.new, new_scene, a.n, integ)}
                    ratios = [best["new"] / best["old"]]
                for _ in range(0 if a.icount else a.rounds):
                    r_old = rate(a.old, old_scene, a.n, integ, a.body_steps)
                    r_new = rate(a.new, new_scene, a.n, integ, a.body_steps)
                    best["old"] = max(best["old"], r_old)
                    best["new"] = max(best["new"], r_new)
                    ratios.append(r_new / r_old)
                ratio = best["new"] / best["old"] if best["old"] > 0 else float("nan")
                median = statistics.median(ratios)
                rows.append({"scene": os.path.basename(scene), "integrator": integ,
                             "old": best["old"], "new": best["new"], "ratio": ratio,
                             "median_ratio": median, "ratios": ratios})
                shown = {w: (1.0 / best[w] if a.icount else best[w]) for w in best}
                print(f"{os.path.basename(scene):28s} {integ:10s} {shown['old']:16.4g} "
                      f"{shown['new']:16.4g} {ratio:14.3f} {median:7.3f}", flush=True)
    if skipped:
        print("skipped (field file missing): " + ", ".join(skipped))
    if a.json:
        json.dump({"n": a.n, "rounds": a.rounds, "icount": a.icount, "contacts": a.contacts,
                   "old_without_contacts": a.old_without_contacts,
                   "new_without_crossing": a.new_without_crossing, "rows": rows,
                   "skipped": skipped},
                  open(a.json, "w"), indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
