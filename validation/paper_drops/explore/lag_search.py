#!/usr/bin/python3
"""Fit the separation point's lag (lag_state.patch, README.md here) on the paper squares.

    lag_search.py --bin LR random --seed S --count N      random configurations, squares only
    lag_search.py --bin LR refine --seed S --count N --centre JSON   log-normal steps around it
    lag_search.py --bin LR check --cfg JSON [--seed-square S]   squares and circles

Knobs of lag_state.patch (on top of stall_blend.patch's): LR_LAG, the separation point's
relaxation time tau1 in planform widths over the speed (0: no state, the quasi-steady blend);
LR_TAU, the delay tau2 of the angle in the quasi-steady target, in the same unit; LR_XINIT, the
separation point at release (< 0: its quasi-steady value). The configuration's "cd1_span": 1
gives the attached drag C_D1 Helmbold's share h of Li et al.'s 5 (as C_L1 has it: the attached
normal force C_L1 sin a tilted), per shape; "cd1_span": 0 keeps 5. Other LR_* keys go to the
binary as they are. Each configuration prints one line as coefficient_search.py does.
"""
import argparse
import json
import math
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import coefficient_search as cs  # noqa: E402
from vcommon import np  # noqa: E402

# Helmbold's h at the planform's aspect ratio (docs/physics/lift.md): square, disk
SPAN = {"square": 0.236, "circle": 0.291}
CD1 = 5.0  # Li et al.'s C_D1


def knobs(cfg, kind):
    k = {key: v for key, v in cfg.items() if key.startswith("LR_")}
    if cfg.get("cd1_span"):
        k["LR_CD1"] = CD1 * SPAN[kind]
    return k


def run(lrigid, cfg, kinds, n, work):
    res = {}
    for kind in kinds:
        res.update(cs.evaluate(lrigid, knobs(cfg, kind), (kind,), n, work))
    return res


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--bin", required=True, help="lrigid built with lag_state.patch")
    p.add_argument("mode", choices=("random", "refine", "check"))
    p.add_argument("--centre", help="refine: the configuration to step around, JSON")
    p.add_argument("--step", type=float, default=0.35, help="refine: the log-normal step")
    p.add_argument("--wide", action="store_true",
                   help="random: also the blend's stall angle and width, C_L1, C_R and mu")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--count", type=int, default=50)
    p.add_argument("--n", type=int, default=80, help="drops per radius bin (run.py: 80)")
    p.add_argument("--cfg", help="check: the configuration, JSON")
    p.add_argument("--seed-square", type=int,
                   help="the squares' seed (the circles' is one more; run.py's: 7)")
    a = p.parse_args()
    if a.seed_square is not None:
        cs.SEEDS.update(square=a.seed_square, circle=a.seed_square + 1)
    rng = np.random.default_rng(a.seed)
    with tempfile.TemporaryDirectory() as work:
        if a.mode == "check":
            cfgs, kinds = [json.loads(a.cfg)], ("square", "circle")
        else:
            cfgs, kinds = [], ("square",)
            c0 = json.loads(a.centre) if a.centre else {}
            for _ in range(a.count):
                if a.mode == "refine":
                    c = dict(c0)
                    for key in ("LR_LAG", "LR_CP0", "LR_CP1", "LR_TAU"):
                        if c.get(key, 0) > 0:
                            c[key] = round(c[key] * math.exp(rng.normal(0, a.step)), 4)
                    cfgs.append(c)
                    continue
                cfgs.append(dict(
                    LR_LAG=round(math.exp(rng.uniform(math.log(0.03), math.log(5))), 3),
                    LR_TAU=round(rng.uniform(0, 2), 2) if rng.uniform() < 0.5 else 0.0,
                    LR_CP0=round(rng.uniform(0, 0.3), 3),
                    LR_CP1=round(rng.uniform(0, 3.5), 2),
                    LR_XINIT=float(rng.choice([-1.0, 0.0, 1.0])),
                    cd1_span=int(rng.uniform() < 0.5)))
                if a.wide:
                    cfgs[-1].update(LR_A0=round(rng.uniform(8, 30), 1),
                                    LR_DELTA=round(rng.uniform(3, 15), 1),
                                    LR_CL1=round(math.exp(rng.uniform(-0.7, 0.7)), 3),
                                    LR_CR=round(math.exp(rng.uniform(-0.7, 0.7)), 3),
                                    LR_MU1=round(math.exp(rng.uniform(-0.7, 1.1)), 3),
                                    LR_MU2=round(math.exp(rng.uniform(-0.7, 1.1)), 3))
        for cfg in cfgs:
            res = run(a.bin, cfg, kinds, a.n, work)
            print(json.dumps(dict(cfg=cfg, loss=cs.loss(res), passes=cs.passes(res), res=res)),
                  flush=True)


if __name__ == "__main__":
    main()
