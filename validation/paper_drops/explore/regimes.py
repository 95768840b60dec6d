#!/usr/bin/python3
"""Scratch exploration (not run by run_all): the regimes of validation/falling_plates'
strips (side ratio 5, Re ~ 10^3, released at 10° and 45°) and Field et al.'s disks for an lrigid
built with plate_knobs.patch (README.md beside this file), each with its own LR_* factors.

  regimes.py --bin LR [--strip-knobs JSON] [--disk-knobs JSON] [--strips I*_s ...] [--disks I*_d ...]

Prints one line per run: the regime as falling_plates classifies it (and, for disks, the regime
Field et al.'s map gives at the measured Re and I*_d).
"""
import argparse
import json
import math
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "falling_plates"))
sys.path.insert(0, os.path.join(HERE, "..", "..", "lib"))
import run as fp  # noqa: E402  (validation/falling_plates/run.py: the scenes and classifiers)
from knobs import run_with_knobs  # noqa: E402

NU = 1e-6  # the strips' Re ~ 10^3 row, and Field's disks at 1e-6 m^2/s


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--bin", required=True, help="lrigid built with plate_knobs.patch")
    p.add_argument("--strip-knobs", default="{}")
    p.add_argument("--disk-knobs", default="{}")
    p.add_argument("--strips", nargs="*", type=float, default=[1.2, 2.0, 3.0])
    p.add_argument("--disks", nargs="*", type=float, default=[0.005, 0.015, 0.03, 0.06, 0.1])
    a = p.parse_args()
    with open(os.path.join(HERE, "..", "..", "falling_plates", "field1997.json")) as f:
        field = json.load(f)
    with tempfile.TemporaryDirectory() as work:
        for istar in a.strips:
            for th0 in (10.0, 45.0):
                sc = fp.scene(istar, NU, fp.strip_duration(istar))
                th = math.radians(th0)
                sc["bodies"][0]["orientation"] = [math.cos(th / 2), 0, math.sin(th / 2), 0]
                tr = run_with_knobs(a.bin, sc, json.loads(a.strip_knobs), work, "s%g_%g" % (istar, th0))
                reg, U, _, p2p, _ = fp.classify(tr)
                print("strip I*_s = %g, released at %g°: %s (pitch %.0f°, Re = %.3g)"
                      % (istar, th0, reg, p2p, U * fp.W / NU), flush=True)
        for istar in a.disks:
            tr = run_with_knobs(a.bin, fp.disk_scene(istar, NU, fp.disk_duration(istar)),
                     json.loads(a.disk_knobs), work, "d%g" % istar)
            reg, U, swing = fp.classify_disk(tr)
            re = U * fp.DISK_D / NU
            print("disk I*_d = %g: %s (Field's map: %s; Re = %.3g, tilt swing %.0f°)"
                  % (istar, reg, fp.field_regime(field, re, istar), re, swing), flush=True)


if __name__ == "__main__":
    main()
