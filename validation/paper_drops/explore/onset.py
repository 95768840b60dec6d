#!/usr/bin/python3
"""Scratch exploration (not run by run_all): is a paper plate's broadside descent
unstable, and where does the growth end? One plate of validation/paper_drops (70 g/m²) released
broadside with a tiny tilt, 100 m up, for 20 s; prints its tilt from the horizontal over time.

  onset.py LRIGID KNOBS_JSON square|circle R TILT_DEG

LRIGID: an lrigid, or one built with plate_knobs.patch to apply KNOBS_JSON (README.md here).
"""
import json
import math
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
sys.path.insert(0, os.path.join(HERE, "..", "..", "lib"))
import run as pd  # noqa: E402  (validation/paper_drops/run.py: the paper's shapes)
import vcommon as vc  # noqa: E402
from knobs import run_with_knobs  # noqa: E402
from vcommon import np  # noqa: E402

B, knobs, kind = sys.argv[1], json.loads(sys.argv[2]), sys.argv[3]
R, tilt = float(sys.argv[4]), float(sys.argv[5])
sh, rho = pd.shape_of(kind, R)
th = math.radians(tilt)
sc = {"version": 1, "fluid": vc.uniform_fluid(pd.RHO_F, pd.NU), "gravity": [0, 0, -pd.G],
      "effects": "auto", "integrator": {"scheme": vc.SCHEME, "dt": 5e-4}, "duration": 20.0,
      "seed": 1,
      "bodies": [{"name": "p", "shape": sh, "density": rho, "count": 1, "position": [0, 0, 100],
                  "orientation": [math.cos(th / 2), math.sin(th / 2) * 0.6,
                                  math.sin(th / 2) * 0.8, 0]}],
      "output": {"every": 0.01, "formats": ["csv"]}}
with tempfile.TemporaryDirectory() as d:
    tr = run_with_knobs(B, sc, knobs, d, "onset")
qx, qy = tr["qx"][:, 0], tr["qy"][:, 0]
tiltd = np.degrees(np.arccos(np.clip(np.abs(1 - 2 * (qx * qx + qy * qy)), 0, 1)))
t = tr["t"][:, 0]
for T in (1, 2, 5, 10, 20):
    i = min(len(t) - 1, int(T / 0.01))
    print("t=%g s: tilt %.3g deg (max so far %.3g)" % (t[i], tiltd[i], tiltd[:i + 1].max()))
