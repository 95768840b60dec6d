#!/usr/bin/python3
"""The leaves scene with two lrigid builds side by side (a change of the plate model against
the build before it): per body kind, the median descent speed over each body's first 3 s, and
what summary.json counts at the end; then the scene's A6 paper sheets dropped in still air
(20 drops from 5 m, the median speed over the first 4 m), to tell the wind's part from the
model's. Needs the wind grid (./Allrun: results/grids/windCourtyard.vti).

    validation/paper_drops/explore/leaves_scene.py OLD_LRIGID NEW_LRIGID
"""
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..", "..")
sys.path.insert(0, os.path.join(HERE, ".."))
sys.path.insert(0, os.path.join(ROOT, "validation", "lib"))
import run as pd  # noqa: E402  (validation/paper_drops/run.py: the tilted releases)
import vcommon as vc  # noqa: E402
from vcommon import np  # noqa: E402


def leaves(lrigid, work):
    with open(os.path.join(ROOT, "scenes", "leaves_wind.json")) as f:
        sc = json.load(f)
    sc["fluid"]["field"] = os.path.abspath(os.path.join(ROOT, "results", "grids",
                                                        "windCourtyard.vti"))
    sc["output"] = {"every": 0.1, "formats": ["csv"]}
    sp = vc.write_scene(os.path.join(work, "leaves.json"), sc)
    out = os.path.join(work, "leaves_out")
    subprocess.run([lrigid, "run", sp, "-o", out, "--quiet", "--threads", "1"], check=True)
    tr = vc.read_traj(os.path.join(out, "trajectories.csv"))
    with open(os.path.join(out, "summary.json")) as f:
        summ = json.load(f)
    parts, first = [], 0
    for b in sc["bodies"]:
        ids = range(first, first + b["count"])
        first += b["count"]
        v = [(tr["z"][0, j] - tr["z"][30, j]) / (tr["t"][30, j] - tr["t"][0, j]) for j in ids]
        parts.append("%s %.3f m/s" % (b["name"], float(np.median(v))))
    c = summ["contacts"]
    return "first 3 s: " + ", ".join(parts) + "; contact events %d, removed %d" % (
        c["events"], c["removed"])


def a6_still_air(lrigid, work):
    rng = np.random.default_rng(3)
    bodies = [{"name": "p%d" % i, "shape": {"type": "box", "size": [0.148, 0.105, 0.0001]},
               "density": 800, "count": 1, "position": [10 * i, 0, 5],
               "orientation": pd.tilt_quat(rng, i % 2 == 1)} for i in range(20)]
    sc = {"version": 1, "fluid": vc.uniform_fluid(1.204, 1.5e-5), "gravity": [0, 0, -9.81],
          "effects": "auto", "integrator": {"scheme": "strang", "dt": 0.002}, "duration": 20,
          "seed": 1, "bodies": bodies, "output": {"every": 0.05, "formats": ["csv"]}}
    sp = vc.write_scene(os.path.join(work, "a6.json"), sc)
    out = os.path.join(work, "a6_out")
    subprocess.run([lrigid, "run", sp, "-o", out, "--quiet"], check=True)
    tr = vc.read_traj(os.path.join(out, "trajectories.csv"))
    v = []
    for j in range(20):
        k = np.nonzero(tr["z"][:, j] <= 1.0)[0]
        v.append(4.0 / tr["t"][k[0], j] if len(k) else 0.0)
    return "A6 sheets in still air: median %.3f m/s over 4 m" % float(np.median(v))


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    for lrigid in sys.argv[1:]:
        with tempfile.TemporaryDirectory() as work:
            print("%s: %s; %s" % (lrigid, leaves(lrigid, work), a6_still_air(lrigid, work)))


if __name__ == "__main__":
    main()
