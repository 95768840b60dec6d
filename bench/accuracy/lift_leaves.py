#!/usr/bin/python3
"""Where the first-order schemes lose: the lift of flat bodies (a 20-leaf case).

20 leaves (6 x 4 x 0.04 cm boxes, 600 kg/m^3) released with random orientations above the
courtyard in the wind grid, turbulence off, 1 s; the median over the leaves of the final position's
distance (m) to rk4 at dt = 2.5e-5 s, for each scheme and dt, with lift and without it. Needs the
wind grid (./Allrun: results/grids/windCourtyard.vti).

    bench/accuracy/lift_leaves.py [--lrigid build/bin/lrigid] [--grid results/grids/windCourtyard.vti]
        [--write docs/physics/integrators.md] [--uniform U] [--schemes strang,rk4]

--write puts the table between the lift-leaves markers of that file, with the machine and date.
What the table shows: strang at dt = 1e-3 s stays within 10x of rk4's error at the same step,
where splitting is about 2000x off.
"""
import argparse
import csv
import datetime
import json
import math
import os
import platform
import statistics
import subprocess
import sys
import tempfile

SRC = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCHEMES = ["splitting", "euler", "strang", "rk4"]
DTS = [1e-3, 2e-4, 1e-4, 5e-5]
DT_REF = 2.5e-5


def scene(grid, scheme, dt, lift):
    """grid: the .vti path, or a list [Ux, Uy, Uz] for a uniform wind (m/s)"""
    effects = ["gravity", "buoyancy", "added_mass", "drag", "mean_flow"] + (["lift"] if lift else [])
    fluid = {"density": 1.204, "kinematic_viscosity": 1.5e-5}
    if isinstance(grid, list):
        fluid["uniform"] = {"U": grid, "k": 0.0, "epsilon": 0.0}
    else:
        fluid["field"] = grid
    return {
        "version": 1,
        "fluid": fluid,
        "gravity": [0, 0, -9.81],
        "effects": effects,
        "integrator": {"scheme": scheme, "dt": dt},
        "duration": 1.0,
        "seed": 2026,
        "bodies": [{
            "name": "leaf",
            "shape": {"type": "box", "size": [0.06, 0.04, 0.0004]},
            "density": 600,
            "count": 20,
            "spawn_box": [[-12, -8, 14], [-4, 8, 20]],
            "orientation": "random",
        }],
        "output": {"every": 1.0, "formats": ["csv"]},
    }


def final_positions(lrigid, grid, scheme, dt, lift, work):
    tag = f"{scheme}_{dt:g}_{'lift' if lift else 'nolift'}"
    path = os.path.join(work, tag + ".json")
    with open(path, "w") as f:
        json.dump(scene(grid, scheme, dt, lift), f)
    out = os.path.join(work, tag)
    subprocess.run([lrigid, "run", path, "-o", out, "--quiet", "--threads", "1"], check=True)
    rows = list(csv.DictReader(open(os.path.join(out, "trajectories.csv"))))
    t_end = max(float(r["t"]) for r in rows)
    pos = {}
    for r in rows:
        if abs(float(r["t"]) - t_end) < 1e-9:
            pos[int(r["body"])] = (float(r["x"]), float(r["y"]), float(r["z"]))
    if abs(t_end - 1.0) > 1e-6:
        sys.exit(f"lift_leaves: {tag} ended at t = {t_end} s, not 1 s")
    return pos


def median_error(a, ref):
    return statistics.median(
        sum((a[i][k] - ref[i][k]) ** 2 for k in range(3)) ** 0.5 for i in ref)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--lrigid", default=os.path.join(SRC, "build/bin/lrigid"))
    ap.add_argument("--grid", default=os.path.join(SRC, "results/grids/windCourtyard.vti"))
    ap.add_argument("--write", help="a markdown file with lift-leaves markers")
    ap.add_argument("--uniform", type=float, metavar="U",
                    help="a uniform wind of U m/s along x instead of the grid (a smooth field: no "
                         "trilinear kinks between grid cells); prints, does not --write")
    ap.add_argument("--schemes", default=",".join(SCHEMES), help="comma-separated, rk4 included")
    a = ap.parse_args()
    schemes = a.schemes.split(",")
    if "rk4" not in schemes:
        sys.exit("lift_leaves: --schemes must include rk4 (the ratios are to rk4's error)")
    if a.uniform is not None:
        if a.write:
            sys.exit("lift_leaves: --write takes the grid case only (the table's)")
        grid = [a.uniform, 0.0, 0.0]
    else:
        grid = os.path.abspath(a.grid)
        if not os.path.isfile(grid):
            sys.exit(f"lift_leaves: the wind grid {grid} does not exist: run ./Allrun first")
    lines = ["| effects | scheme | " + " | ".join(f"dt = {dt:g} s" for dt in DTS) + " |",
             "|---|---|" + "---|" * len(DTS)]
    ratio, slopes = {}, {}
    with tempfile.TemporaryDirectory(prefix="lift_leaves") as work:
        for lift in (True, False):
            ref = final_positions(a.lrigid, grid, "rk4", DT_REF, lift, work)
            errs = {}
            for scheme in schemes:
                errs[scheme] = [median_error(final_positions(a.lrigid, grid, scheme, dt, lift, work),
                                             ref) for dt in DTS]
                lines.append(f"| {'with' if lift else 'without'} lift | {scheme} | " +
                             " | ".join(f"{e:.2g} m" for e in errs[scheme]) + " |")
            ratio[lift] = {s: errs[s][0] / max(errs["rk4"][0], 1e-300) for s in schemes}
            slopes[lift] = {s: [math.log(errs[s][k] / errs[s][k + 1]) / math.log(DTS[k] / DTS[k + 1])
                                if errs[s][k] > 0 and errs[s][k + 1] > 0 else float("nan")
                                for k in range(len(DTS) - 1)] for s in schemes}
    text = "\n".join(lines) + "\n\nAt dt = 1e-3 s, the error over rk4's at the same step: " + "; ".join(
        f"{'with' if lift else 'without'} lift " + ", ".join(
            f"{s} {ratio[lift][s]:.3g}x" for s in schemes if s != "rk4") for lift in (True, False))
    text += ("\n\nLocal slopes of log(error) against log(dt) between neighbouring steps: " +
             "; ".join(f"{'with' if lift else 'without'} lift " + ", ".join(
                 f"{s} " + "/".join(f"{x:.2f}" for x in slopes[lift][s]) for s in schemes)
                 for lift in (True, False)))
    if a.uniform is not None:
        text += f"\n\n(uniform wind {a.uniform:g} m/s along x, not the grid)"
    stamp = (f"Measured: {platform.node()}, {os.cpu_count()} cores, "
             f"{datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC; "
             f"`bench/accuracy/lift_leaves.py` (median over 20 leaves of |x - x_rk4(dt = {DT_REF:g} s)| "
             "after 1 s).")
    print(text)
    print(stamp)
    if a.write:
        doc = open(a.write).read()
        b, e = "<!-- lift-leaves begin -->", "<!-- lift-leaves end -->"
        if b not in doc or e not in doc:
            sys.exit(f"lift_leaves: {a.write} has no {b} ... {e} markers")
        new = doc[:doc.index(b) + len(b)] + "\n" + text + "\n\n" + stamp + "\n" + doc[doc.index(e):]
        tmp = a.write + f".tmp{os.getpid()}"
        with open(tmp, "w") as f:
            f.write(new)
        os.replace(tmp, a.write)


if __name__ == "__main__":
    main()
