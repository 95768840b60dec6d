#!/usr/bin/python3
"""Instructions per body per simulated second of a scene at chosen (scheme, dt) points: the
study's cost axis (docs/accuracy.md, CPU seconds, which other jobs on a shared machine move by
tens of per cent) counted by callgrind instead, so two points compare exactly.

Each point steps N bodies of the scene (`lrigid bench`, one thread, no warm-up) for the same
simulated time T (the steps are T / dt); the figure is `simulate`'s inclusive instructions / N / T.

    bench/accuracy/instructions_per_second.py --scene scenes/debris_tank.json \\
        --point splitting:1e-3 --point strang:5e-3 [--n 200] [--duration 2] [--lrigid build/bin/lrigid]

A field path in the scene is taken relative to the scene file, as lrigid does.
"""
import argparse
import json
import os
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "bench", "lib"))
from callgrind_count import callgrind  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scene", required=True)
    ap.add_argument("--point", action="append", required=True, metavar="SCHEME:DT",
                    help="an integrator and its step, s (repeat)")
    ap.add_argument("--n", type=int, default=200, help="bodies")
    ap.add_argument("--duration", type=float, default=2.0, help="simulated time T, s")
    ap.add_argument("--lrigid", default=os.path.join(ROOT, "build/bin/lrigid"))
    a = ap.parse_args()
    scene = json.load(open(a.scene))
    field = scene.get("fluid", {}).get("field")
    if field and not os.path.isabs(field):
        scene["fluid"]["field"] = os.path.normpath(
            os.path.join(os.path.dirname(os.path.abspath(a.scene)), field))
    results = []
    with tempfile.TemporaryDirectory(prefix="ips") as work:
        for p in a.point:
            try:
                scheme, dt = p.split(":")
                dt = float(dt)
            except ValueError:
                sys.exit(f"instructions_per_second: --point {p!r}: expected SCHEME:DT, e.g. strang:5e-3")
            steps = round(a.duration / dt)
            s = json.loads(json.dumps(scene))
            s["integrator"] = dict(s.get("integrator", {}), scheme=scheme, dt=dt)
            path = os.path.join(work, f"{scheme}_{dt:g}.json")
            json.dump(s, open(path, "w"))
            ins = callgrind([a.lrigid, "bench", path, "--n", str(a.n), "--threads", "1",
                             "--integrators", scheme, "--warmup", "0", "--body-steps", "1",
                             "--min-steps", str(steps), "--quiet"],
                            os.path.join(work, f"{scheme}_{dt:g}.cg"))
            results.append((p, steps, ins / a.n / a.duration))
    print(f"{a.scene}: {a.n} bodies, {a.duration:g} s simulated, `simulate` inclusive (callgrind)")
    for p, steps, ips in results:
        print(f"  {p:>16}: {steps} steps, {ips:.4g} instructions per body per simulated s"
              f" ({ips / results[0][2]:.3g} x the first point)")


if __name__ == "__main__":
    main()
