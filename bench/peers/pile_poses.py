#!/usr/bin/env python3
"""The box pile's initial poses, from bench/peers/pile.json (bench/peers/pile.md).

    pile_poses.py PILE_JSON OUTDIR [--n N] [--steps S]

Writes OUTDIR/poses.csv (body,x,y,z,qw,qx,qy,qz: every engine starts from it) and
OUTDIR/pile_lrigid.json, the lrigid scene of the same pile: pile.json with its one body entry
replaced by one entry of one body per pose (lrigid's spawn_box draws positions at random, which
would overlap), and duration S * dt. Prints the harnesses' flags for the pile's parameters
(--size, --density, --friction, --restitution, --gravity, --dt, --steps) on stdout.

The pile: the entry's `count` boxes (or N) in a loose lattice, `LAYERS` layers high, of
nx = ny = ceil(sqrt(N / LAYERS)) columns, centred on x = y = 0 and filled from the bottom layer
up; lattice spacing 1.1 times the box's diagonal, so no two boxes overlap whatever their
orientation, each moved sideways by a random offset that keeps them apart, and turned by a
uniform random rotation (the scene's seed). Its footprint grows with N as sqrt(N), so the pile
settles to the same height, a few boxes deep, for any N.
"""
import argparse
import copy
import json
import math
import os
import random
import sys

LAYERS = 5


def fail(msg):
    print(f"pile_poses.py: {msg}", file=sys.stderr)
    sys.exit(2)


def uniform_quaternion(rng):
    """A uniform random rotation (Shoemake 1992), as (w, x, y, z)."""
    u1, u2, u3 = rng.random(), rng.random(), rng.random()
    a, b = math.sqrt(1 - u1), math.sqrt(u1)
    return (b * math.cos(2 * math.pi * u3), a * math.sin(2 * math.pi * u2),
            a * math.cos(2 * math.pi * u2), b * math.sin(2 * math.pi * u3))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("pile_json")
    ap.add_argument("outdir")
    ap.add_argument("--n", type=int, default=None, help="bodies (default: the entry's count)")
    ap.add_argument("--steps", type=int, default=None,
                    help="steps (default: the scene's duration / dt)")
    a = ap.parse_args()
    try:
        with open(a.pile_json) as f:
            scene = json.load(f)
    except (OSError, ValueError) as e:
        fail(f"{a.pile_json}: {e}")
    if len(scene.get("bodies", [])) != 1 or scene["bodies"][0].get("shape", {}).get("type") != "box":
        fail(f"{a.pile_json}: needs exactly one body entry, a box")
    entry = scene["bodies"][0]
    size = entry["shape"]["size"]
    n = a.n if a.n is not None else entry["count"]
    if n < 1:
        fail(f"--n must be >= 1, got {n}")
    dt = scene["integrator"]["dt"]
    steps = a.steps if a.steps is not None else int(round(scene["duration"] / dt))
    if steps < 1:
        fail(f"--steps must be >= 1, got {steps}")
    g = scene["gravity"]
    if g[0] != 0 or g[1] != 0 or not g[2] < 0:
        fail(f"{a.pile_json}: gravity must point along -z, got {g}")
    mat = scene.get("contact", {})
    mat.update(entry.get("contact", {}))

    diag = math.sqrt(sum(s * s for s in size))
    spacing = 1.1 * diag
    # sideways offsets of at most `jit` along x and y keep neighbours' bounding spheres apart
    jit = 0.45 * (spacing - diag) / math.sqrt(2)
    side = math.ceil(math.sqrt(n / LAYERS))
    rng = random.Random(scene["seed"])
    poses = []
    for i in range(n):
        layer, k = divmod(i, side * side)
        iy, ix = divmod(k, side)
        x = (ix - (side - 1) / 2) * spacing + rng.uniform(-jit, jit)
        y = (iy - (side - 1) / 2) * spacing + rng.uniform(-jit, jit)
        z = (layer + 0.5) * spacing
        poses.append((x, y, z) + uniform_quaternion(rng))

    os.makedirs(a.outdir, exist_ok=True)
    with open(os.path.join(a.outdir, "poses.csv"), "w") as f:
        f.write("body,x,y,z,qw,qx,qy,qz\n")
        for i, p in enumerate(poses):
            f.write(f"{i}," + ",".join(f"{v:.9g}" for v in p) + "\n")

    lr = copy.deepcopy(scene)
    lr["duration"] = steps * dt
    one = {k: v for k, v in entry.items() if k not in ("count", "spawn_box", "orientation")}
    lr["bodies"] = []
    for p in poses:
        b = dict(one)
        b["count"] = 1
        b["position"] = [round(v, 9) for v in p[:3]]
        b["orientation"] = [round(v, 9) for v in p[3:]]
        lr["bodies"].append(b)
    with open(os.path.join(a.outdir, "pile_lrigid.json"), "w") as f:
        json.dump(lr, f, separators=(",", ":"))

    print(f"--size {size[0]} {size[1]} {size[2]} --density {entry['density']} "
          f"--friction {mat.get('friction', 0.5)} --restitution {mat.get('restitution', 0.3)} "
          f"--gravity {-g[2]} --dt {dt} --steps {steps} --n {n}")


if __name__ == "__main__":
    main()
