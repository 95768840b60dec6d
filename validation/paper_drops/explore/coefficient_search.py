#!/usr/bin/python3
"""Scratch exploration (not a validation study, not run by run_all): how close can the 3D
plate model's coefficients, fitted to Howison et al.'s paper squares, bring the drops of
validation/paper_drops, and do the circles (not fitted) follow?

Needs an lrigid built with plate_knobs.patch (README.md beside this file): it scales every
plate's C_R, C_T, mu1, mu2 by the environment's LR_CR, LR_CT, LR_MU1, LR_MU2 and sets the edgewise
drag coefficient A - B to LR_E with the broadside A + B kept (the textbook C_D). Modes:

  coefficient_search.py --bin LR random --seed S --count N   random configurations, squares
  coefficient_search.py --bin LR refine --seed S --count N   log-normal steps around --centre
  coefficient_search.py --bin LR check --cfg JSON --n 10     squares and circles
  coefficient_search.py --bin LR check --cfg '{"square": JSON, "circle": JSON}' --n 10
                                                           each shape with its own factors
  ... check ... --ambient UPRIME L                         in stirred instead of still air
  ... check ... --half --height 1.0                        half/half releases from 1.0 m (the
                                                           set-up before the recorded one)
  ... --spin 0                                             no release spin (before 2026-12-05)
  ... check ... --seed-square S                            the squares' drops drawn with seed S
                                                           and the circles' with S + 1 (run.py:
                                                           7 and 8)

Each configuration prints one JSON line: the factors, the loss (the sum of squared log errors of
the median descent speed in units of 15 %, of the median lateral displacement in units of a
factor 1.5, and of the tumbling fraction), the number of paper_drops checks it would pass, and
per bin (speed, data, lateral, data, tumbling fraction, data), and per shape the median
straightness of the whole paths per bin (net lateral displacement over the horizontal path; the
data's in reference.json: 0.29-0.77).
"""
import argparse
import json
import math
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
sys.path.insert(0, os.path.join(HERE, "..", "..", "lib"))
import run as pd  # noqa: E402  (validation/paper_drops/run.py: the drops and their segments)
import vcommon as vc  # noqa: E402
from knobs import run_with_knobs  # noqa: E402
from vcommon import np  # noqa: E402

with open(os.path.join(HERE, "..", "reference.json")) as f:
    REF = json.load(f)
SEEDS = {"square": 7, "circle": 8}   # those of run.py


def evaluate(lrigid, cfg, kinds, n, work, ambient=None, half=False, height=None, spin=None):
    """ambient: (u', L) for still air stirred by turbulence of rms velocity u' (m/s) and integral
    scale L (m), i.e. k = 3/2 u'^2, epsilon = u'^3 / L (the Langevin effect); None: still air.
    half: half the drops released horizontally (instead of the recorded mix); height: release
    height in m (instead of the recorded one); spin: the release spin bound in rad/s (None:
    run.py's RELEASE_SPIN)"""
    res = {}
    for kind in kinds:
        rows = [dict(r) for r in REF[kind]]
        for r in rows:
            if half:
                r["n_drops_horizontal"] = r["n_drops_vertical"] = 1
            if height is not None:
                r["median_release_height"] = height
        sc, meta = pd.drop_scene(kind, n, SEEDS[kind], rows, spin=spin)
        if ambient:
            up, scale = ambient
            sc["fluid"] = vc.uniform_fluid(pd.RHO_F, pd.NU, k=1.5 * up * up, eps=up ** 3 / scale)
            # the effects "auto" chooses in still air, with the turbulence always (auto skips it
            # below u' of about 1 cm/s here)
            sc["effects"] = ["gravity", "buoyancy", "added_mass", "drag", "lift", "turbulence"]
        tr = run_with_knobs(lrigid, sc, cfg, work, kind)
        rows = []
        for r, m in zip(REF[kind], pd.radius_bins(tr, meta)):
            fr = r["n_tumbling"] / max(1, r["n_tumbling"] + r["n_chaotic"])
            rows.append((m["median_speed"], r["median_speed"], m["median_lateral"],
                         r["median_lateral"], m["tumbling_fraction"], fr))
        res[kind] = rows
        res[kind + "_straightness"] = [round(m["straightness"], 2)
                                       for m in pd.path_shapes(tr, meta)]
    return res


def loss(res):
    total = 0.0
    for kind, rows in res.items():
        if kind.endswith("_straightness"):
            continue
        for ms, rs, ml, rl, mf, rf in rows:
            total += (math.log(ms / rs) / 0.15) ** 2
            total += (math.log(max(ml, 1e-3) / rl) / math.log(1.5)) ** 2
            total += 4 * (mf - rf) ** 2 / 0.09 if not math.isnan(mf) else 4
    return total


def verdicts(kind, rows):
    """paper_drops' 9 checks on one shape, rows as evaluate returns them (speed, data, lateral,
    data, tumbling fraction, data per bin of run.py's RADII): (number passed, texts of the
    failed ones)"""
    n, failed = 0, []
    for R, (ms, rs, ml, rl, _, _) in zip(pd.RADII, rows):
        if abs(ms / rs - 1) <= 0.15:
            n += 1
        else:
            failed.append("%s R %g cm speed x%.2f" % (kind, 100 * R, ms / rs))
        if 1 / 1.5 <= max(ml, 1e-12) / rl <= 1.5:
            n += 1
        else:
            failed.append("%s R %g cm lateral x%.2f" % (kind, 100 * R, ml / rl))
    if rows[0][4] >= 0.5 and rows[-1][4] <= 0.3:
        n += 1
    else:
        failed.append("%s tumbling trend" % kind)
    return n, failed


def passes(res):
    """paper_drops' checks this result would pass (of 9 per shape)"""
    return sum(verdicts(kind, rows)[0] for kind, rows in res.items()
               if not kind.endswith("_straightness"))


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--bin", required=True, help="lrigid built with plate_knobs.patch")
    p.add_argument("mode", choices=("random", "refine", "check"))
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--count", type=int, default=100)
    p.add_argument("--n", type=int, default=6,
                   help="drops per radius bin, releases in the data's proportion (run.py: 40)")
    p.add_argument("--centre", default='{"LR_CR": 0.22, "LR_CT": 0.9, "LR_MU1": 0.35, '
                   '"LR_MU2": 0.18, "LR_E": 0.55}')
    p.add_argument("--cfg", help="check: the configuration, JSON")
    p.add_argument("--ambient", nargs=2, type=float, metavar=("UPRIME", "L"),
                   help="check: drop in air stirred at rms velocity UPRIME (m/s), scale L (m)")
    p.add_argument("--half", action="store_true",
                   help="half of each bin's drops horizontal instead of the recorded mix")
    p.add_argument("--height", type=float,
                   help="release height (m) instead of each bin's recorded one")
    p.add_argument("--spin", type=float,
                   help="release spin bound in rad/s (default run.py's RELEASE_SPIN; "
                   "none: --spin 0)")
    p.add_argument("--seed-square", type=int,
                   help="check: the squares' seed (the circles' is one more; run.py's: 7)")
    a = p.parse_args()
    if a.seed_square is not None:
        SEEDS.update(square=a.seed_square, circle=a.seed_square + 1)
    rng = np.random.default_rng(a.seed)
    with tempfile.TemporaryDirectory() as work:
        if a.mode == "check":
            cfg = json.loads(a.cfg)
            if set(cfg) <= {"square", "circle"}:  # per shape (factors that follow the planform)
                res = {}
                for kind, c in cfg.items():
                    res.update(evaluate(a.bin, c, (kind,), a.n, work, a.ambient, a.half,
                                        a.height, a.spin))
                print(json.dumps(dict(cfg=cfg, loss=loss(res), passes=passes(res), res=res)))
                return
            cfgs, kinds = [cfg], ("square", "circle")
        else:
            cfgs, kinds = [], ("square",)
            c0 = json.loads(a.centre)
            for _ in range(a.count):
                if a.mode == "random":
                    cfgs.append(dict(LR_CR=rng.uniform(0.1, 1.5), LR_CT=rng.uniform(0.2, 2.0),
                                     LR_MU1=math.exp(rng.uniform(-2.3, 1.1)),
                                     LR_MU2=math.exp(rng.uniform(-2.3, 1.1)),
                                     LR_E=rng.uniform(0.2, 0.8)))
                else:
                    c = {k: v * math.exp(rng.normal(0, 0.35)) for k, v in c0.items()}
                    c["LR_E"] = min(c["LR_E"], 0.9)
                    cfgs.append(c)
        for cfg in cfgs:
            res = evaluate(a.bin, cfg, kinds, a.n, work, a.ambient, a.half, a.height, a.spin)
            print(json.dumps(dict(cfg=cfg, loss=loss(res), passes=passes(res), res=res)),
                  flush=True)


if __name__ == "__main__":
    main()
