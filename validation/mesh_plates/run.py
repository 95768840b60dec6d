#!/usr/bin/python3
"""Mesh plates against the analytic plates of the same planform (docs/physics/lift.md, "The
planform"): 70 g/m² paper squares as "box" and as an OBJ closed prism of 8 vertices, drawn along
the file's axes and turned by 45° about its normal in the file, and paper disks as a thin oblate
ellipsoid and as an OBJ 48-gon prism, falling 1 m in still air.

Paper as in validation/paper_drops (70 g/m², thickness 0.0694 mm, 1008 kg/m³; the ellipsoid of
centre thickness 0.0694 mm and the same mass per area, 1512 kg/m³). Half sides or radii R = 1.5 and
4.5 cm. Per shape and size 40 drops of the squares (N_DROPS), 200 of the disks (DISK_DROPS), from
z = 1 m, effects "auto", strang, dt = 5e-4 s,
states every 0.01 s; release: half horizontal, half vertical, each tilted by a random 0–5° about a
random horizontal axis and spinning at a random 0–1 rad/s about a random axis
(paper_drops.run.tilt_quat, RELEASE_SPIN). The analytic and the mesh plate of a pair get the same
releases (same seed, same body order: the draws are keyed by seed and body).

Per drop: its segments' descent speeds as paper_drops cuts them (the speed that study checks
against Howison et al.), the whole-drop descent speed (0.95 m over the time to reach 5 cm) and
whether it tumbles (the normal turns over at least twice, four sign changes of its vertical
component, as paper_drops counts a tumbling segment). Checks per pair (the issue's "falls
like"): the mesh's median segment and whole-drop descent speeds within 3 % of the analytic
plate's, its tumbling fraction within 0.1.

The squares are the same planform exactly (a rectangle, w = 1): the same model to round-off, so
the same drops. The turned square (square45) is the same square drawn turned by 45° in its OBJ:
its tightest rectangle is the box's, turned, so it is the box turned by 45° about its normal
(its bounding box along the file's axes would make it R = 1/2, the ellipse's model). Its pair
releases the box at the squares' orientations q and the OBJ at q Rz(-45°), the same square in the
world, and gives both the same release spins in the world frame (drawn here with the scene's
law, a uniform rate in [0, RELEASE_SPIN] about a uniform axis: the scene's "variation" draws its
axis in the body frame, which differs between the two), so that the pair is the same drops
again. A 48-gon's outline fills 0.997 of its circle
and 0.7865 of its tightest square, so its planform is essentially the ellipse of its area
(w = 0.005; plate coefficients and added mass within 1 % of the ellipsoid's), but the bodies
differ: the prism's moment of inertia about a diameter is the flat disk's, 5/4 of the thin
ellipsoid's of the same mass, and its equivalent ellipsoid is sqrt(4/pi) thicker at 2/3 the
density, which raises APW's velocity scale sqrt((rho_b/rho_f - 1) g b) by 6 %. Their drops can
only agree in distribution: DISK_DROPS = 200 per disk pair (at 40 the median of these spread-out
descents, 0.63-1.38 m/s at 4.5 cm, wanders by about 2.5 %).
"""
import importlib.util
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "lib"))
import vcommon as vc  # noqa: E402
from vcommon import np  # noqa: E402

# validation/paper_drops/run.py: the paper, the releases, the segments, the 48-gon OBJ (it
# imports its neighbour paths.py)
sys.path.append(os.path.join(HERE, "..", "paper_drops"))
_spec = importlib.util.spec_from_file_location(
    "paper_drops_run", os.path.join(HERE, "..", "paper_drops", "run.py"))
paper = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(paper)

N_DROPS = 40      # per square pair and size (the reproduction)
DISK_DROPS = 200  # per disk pair and size: the pair differs in inertia, so only the
                  # distributions can agree, and the median of 40 wanders by about 2.5 %
SIZES = (0.015, 0.045)  # half side or radius R, m
Z0 = 1.0


def write_square_obj(path, R, h=paper.H, turn_deg=0.0):
    """A closed, outward square prism of half side R and thickness h: 8 vertices, 12 triangles,
    turned by turn_deg about z in the file."""
    c, s = math.cos(math.radians(turn_deg)), math.sin(math.radians(turn_deg))
    v = [(c * x - s * y, s * x + c * y, z)
         for z in (-h / 2, h / 2) for (x, y) in ((-R, -R), (R, -R), (R, R), (-R, R))]
    f = [(1, 3, 2), (1, 4, 3), (5, 6, 7), (5, 7, 8)]
    for i in range(4):
        j = (i + 1) % 4
        f += [(i + 1, j + 1, j + 5), (i + 1, j + 5, i + 5)]
    fmt = "v %.9g %.9g %.9g\n" if turn_deg == 0 else "v %.17g %.17g %.17g\n"
    with open(path + ".tmp", "w") as o:
        for p in v:
            o.write(fmt % p)
        for t in f:
            o.write("f %d %d %d\n" % t)
    os.replace(path + ".tmp", path)


def quat_mul(a, b):
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return [w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2]


def world_spins(n, seed):
    """n release spins in the world frame (rad/s): a uniform rate in [0, RELEASE_SPIN] about a
    uniformly random axis"""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        a = rng.normal(size=3)
        out.append((rng.uniform(0, paper.RELEASE_SPIN) * a / np.linalg.norm(a)).tolist())
    return out


def scene(shape, density, n, seed, turn_deg=0.0, spins=None):
    """n drops of one shape; turn_deg: each body's orientation is the release's times a turn by
    -turn_deg about its z (a mesh drawn turned by turn_deg in its file then lies as the unturned
    shape does); spins: world-frame release spins instead of the scene's random ones"""
    rng = np.random.default_rng(seed)
    h = math.radians(turn_deg) / 2
    q_turn = [math.cos(h), 0.0, 0.0, -math.sin(h)]
    bodies = []
    for i in range(n):
        vertical = i % 2 == 1
        q = paper.tilt_quat(rng, vertical)
        b = {"name": "plate_%d" % i, "shape": shape, "density": density, "count": 1,
             "position": [0, 0, Z0], "orientation": quat_mul(q, q_turn) if turn_deg else q}
        if spins is None:
            b["variation"] = {"spin": [0.0, paper.RELEASE_SPIN]}
        else:
            b["angular_velocity"] = spins[i]
        bodies.append(b)
    return {"version": 1, "fluid": vc.uniform_fluid(paper.RHO_F, paper.NU),
            "gravity": [0, 0, -paper.G], "effects": "auto",
            "integrator": {"scheme": vc.SCHEME, "dt": 5e-4}, "duration": 6.0, "seed": seed,
            "ground": {"z": 0.0}, "bodies": bodies,
            "output": {"every": paper.DT_OUT, "formats": ["csv"]}}


def drops(args, st, name, shape, density, n, seed, R, turn_deg=0.0, spins=None):
    """(median segment descent speed, median whole-drop descent speed, tumbling fraction,
    landed) of n drops of half side or radius R"""
    tr, _, _ = vc.run_scene(args, scene(shape, density, n, seed, turn_deg, spins), st.path(name))
    speeds, tumbles, segs = [], [], []
    for j in range(n):
        segs += paper.segments(tr, j, R, j % 2 == 1)
        z = tr["z"][:, j]
        low = np.nonzero(z <= 0.05)[0]
        if len(low):
            speeds.append((Z0 - 0.05) / tr["t"][low[0], j])
        m = paper.airborne(z)
        qx, qy = tr["qx"][:m, j], tr["qy"][:m, j]
        tumbles.append(paper.flips(1 - 2 * (qx * qx + qy * qy)) >= 4)
    return (paper.bin_stats(segs)["median_speed"],
            float(np.median(speeds)) if speeds else math.nan, float(np.mean(tumbles)),
            len(speeds))


def main():
    args = vc.parse_args()
    st = vc.Study("mesh_plates", "Mesh plates against analytic plates of the same planform: "
                  "paper squares (box vs OBJ prism) and disks (ellipsoid vs 48-gon)", args)
    lines = ["| pair | R (cm) | analytic: segment, whole-drop speed (m/s), tumbling, landed | "
             "mesh: segment, whole-drop speed (m/s), tumbling, landed | speed ratios mesh / "
             "analytic |", "|---|---|---|---|---|"]
    for kind in ("square", "square45", "disk"):
        n = 8 if args.quick else (DISK_DROPS if kind == "disk" else N_DROPS)
        for k, R in enumerate(SIZES):
            seed = 11 + k
            turn, spins = 0.0, None
            if kind == "square":
                obj = st.path("square_R%g.obj" % R)
                write_square_obj(obj, R)
                ana = ({"type": "box", "size": [2 * R, 2 * R, paper.H]}, paper.RHO_BOX)
            elif kind == "square45":
                obj = st.path("square45_R%g.obj" % R)
                write_square_obj(obj, R, turn_deg=45.0)
                ana = ({"type": "box", "size": [2 * R, 2 * R, paper.H]}, paper.RHO_BOX)
                turn, spins = 45.0, world_spins(n, 1000 + seed)
            else:
                obj = st.path("disk_R%g.obj" % R)
                paper.write_disk_obj(obj, R)
                ana = ({"type": "ellipsoid", "semi_axes": [R, R, paper.H / 2]}, paper.RHO_ELL)
            a = drops(args, st, "%s_R%g_analytic" % (kind, R), ana[0], ana[1], n, seed, R,
                      spins=spins)
            m = drops(args, st, "%s_R%g_mesh" % (kind, R), {"type": "mesh", "file": obj},
                      paper.RHO_BOX, n, seed, R, turn_deg=turn, spins=spins)
            lines.append("| %s | %.3g | %.3f, %.3f, %.2f, %d | %.3f, %.3f, %.2f, %d | %.3f, %.3f |"
                         % ((kind, 100 * R) + a + m + (m[0] / a[0], m[1] / a[1])))
            if args.quick and kind == "disk":
                continue  # 8 drops of two different bodies: a smoke run, no verdict
            label = {"square": "box vs 8-vertex OBJ",
                     "square45": "box vs 8-vertex OBJ turned by 45° in its file",
                     "disk": "ellipsoid vs 48-gon OBJ"}[kind]
            src = "the analytic plate of the same planform (issue: within 3 %)"
            st.check("%s R = %.3g cm (%s): median segment descent speed" % (kind, 100 * R, label),
                     m[0], a[0], 0.03, src, unit="m/s", rel=True)
            st.check("%s R = %.3g cm (%s): median whole-drop descent speed"
                     % (kind, 100 * R, label), m[1], a[1], 0.03, src, unit="m/s", rel=True)
            st.check("%s R = %.3g cm (%s): tumbling fraction" % (kind, 100 * R, label), m[2],
                     a[2], 0.1, "the analytic plate of the same planform (issue: within 0.1)")
    st.table(["Drops from 1 m (squares %d, disks %d per shape and size), the same releases for "
              "both of a pair (square45: an OBJ drawn turned by 45° in its file, released "
              "turned back, with the box's spins in the world frame):"
              % (8 if args.quick else N_DROPS, 8 if args.quick else DISK_DROPS),
              ""] + lines)
    print("\n".join(lines))
    st.finish()


if __name__ == "__main__":
    main()
