#!/usr/bin/python3
"""Scratch (not run by run_all): which paper_drops segments make a radius bin's median lateral
displacement. Drops one shape as run.py does (its seed, the measured release mix and height,
80 per bin unless --n) with an lrigid built with a knobs patch (README.md here) and prints per
bin the median of all segments and, per label (steady start, tumbling, chaotic) and release
(h: horizontal, v: vertical), their count and median lateral displacement (m).

  segment_split.py --bin LR square '{"LR_CR": 1.0}'
"""
import argparse
import json
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, ".."))
import coefficient_search as cs  # noqa: E402  (its SEEDS and REF: run.py's)
import run as pd  # noqa: E402
from knobs import run_with_knobs  # noqa: E402
from vcommon import np  # noqa: E402


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--bin", required=True, help="lrigid built with a knobs patch")
    p.add_argument("kind", choices=("square", "circle"))
    p.add_argument("cfg", help="the LR_* knobs, JSON")
    p.add_argument("--n", type=int, default=80, help="drops per radius bin")
    a = p.parse_args()
    with tempfile.TemporaryDirectory() as work:
        sc, meta = pd.drop_scene(a.kind, a.n, cs.SEEDS[a.kind], cs.REF[a.kind])
        tr = run_with_knobs(a.bin, sc, json.loads(a.cfg), work, "drops")
    for R in pd.RADII:
        by = {}
        for j, (r, vertical, _) in enumerate(meta):
            if r != R:
                continue
            for label, _, lateral in pd.segments(tr, j, R, vertical):
                by.setdefault((label, "v" if vertical else "h"), []).append(lateral)
        every = [x for v in by.values() for x in v]
        print("R %.3g cm: median %.3f m;" % (100 * R, np.median(every)),
              ", ".join("%s/%s %d at %.2f" % (k[0], k[1], len(v), np.median(v))
                        for k, v in sorted(by.items())))


if __name__ == "__main__":
    main()
