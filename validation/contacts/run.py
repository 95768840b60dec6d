#!/usr/bin/python3
"""Study: contacts with the ground (docs/contacts.md), each against a closed form.

1. A sphere dropped on the ground with the fluid's forces off (effects: gravity only) bounces
   with apex heights h_{n+1} / h_n = e^2 (Newton's restitution: the rebound speed is e times the
   impact speed, and a ballistic flight turns speed v into height v^2 / 2g). Tolerance 2 %.
2. A box on a plane inclined by theta (gravity tilted by theta: the same dynamics) slides with
   acceleration g (sin theta - mu cos theta) when mu < tan theta (Coulomb friction mu N against
   the slip, N = m g cos theta). Tolerance 2 %.
3. The same box with mu > tan theta stays: displacement below 1e-6 m over 10 s (friction holds
   it; the contact adds no creep), with and without sleeping.
4. The wind scene (scenes/leaves_wind.json on the windCourtyard grid with its wall_distance;
   --quick: 200 bodies, 10 s; LRIGID_WIND_GRID=FILE: another conversion of the case): at every
   output time no contact point of a body (box: its corners; ellipsoid: 26 points of its
   surface) lies deeper than 1 cm inside a solid (the grid's interpolated wall distance, read by
   the Python module's Grid.sample) or below the ground; no body stopped against a wall (every exited body was removed at the grid's edge);
   and, reported, how many end up resting or sliding on the roof and ledges (above 0.5 m), on
   the ground, flying, and how many left the grid.
Each run is lrigid run on a scene written here, read back from trajectories.csv.
"""
import csv
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "lib"))
import vcommon as vc  # noqa: E402
from vcommon import np, plt  # noqa: E402

G = 9.81
NEWTON = "Newton's restitution, ballistic flight: h_{n+1}/h_n = e^2"
COULOMB = "Coulomb friction on an incline: a = g (sin th - mu cos th)"


def scene(body, gravity, duration, dt, every):
    return {"version": 1, "fluid": vc.uniform_fluid(1.204, 1.5e-5),
            "gravity": list(gravity), "effects": ["gravity"],
            "integrator": {"scheme": vc.SCHEME, "dt": dt}, "duration": duration, "seed": 1,
            "ground": {"z": 0.0, "contact": "collide"},
            "bodies": [body], "output": {"every": every, "formats": ["csv"]}}


def apexes(z):
    k = np.where((z[1:-1] > z[:-2]) & (z[1:-1] >= z[2:]))[0] + 1
    return z[k]


def main():
    args = vc.parse_args()
    st = vc.Study("contacts", "Contacts: bouncing, sliding and resting on the ground", args)
    r = 0.05
    # 1. bounces
    fig, ax = plt.subplots(figsize=(6, 3.5))
    for e in (0.8, 0.5):
        body = {"name": "ball", "shape": {"type": "sphere", "radius": r}, "density": 1000,
                "count": 1, "position": [0, 0, 1.0 + r],
                "contact": {"restitution": e, "friction": 0.3}}
        dt = 1e-4
        _, summ, out = vc.run_scene(args, scene(body, (0, 0, -G), 2.5, dt, dt),
                                    st.path("bounce_e%g" % e))
        tr = vc.read_traj(os.path.join(out, "trajectories.csv"))
        t, z = tr["t"][:, 0], tr["z"][:, 0] - r
        ax.plot(t, z, label="e = %g" % e)
        h = np.concatenate([[z[0]], apexes(z)])
        for n in range(3 if e > 0.6 else 2):
            st.check("e = %g: apex ratio h%d/h%d / e^2" % (e, n + 1, n), h[n + 1] / h[n] / e ** 2,
                     1.0, 0.02, NEWTON, rel=True)
        st.check("e = %g: lowest point of the ball (m, below the ground if negative)" % e,
                 z.min(), 0.0, math.sqrt(2 * G) * dt, "at most one step's travel",
                 tol_text="±v dt = %.2g m" % (math.sqrt(2 * G) * dt))
        st.check("e = %g: contact events counted in summary.json" % e,
                 summ["contacts"]["events"], len(h) - 1, len(h), "one per bounce (and rest)",
                 tol_text="≥ bounces", verdict="PASS" if summ["contacts"]["events"] >= len(h) - 1
                 else "FAIL")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("height of the ball's lowest point [m]")
    ax.legend()
    ax.grid(alpha=0.3)
    st.savefig(fig, "bounce.png", "A ball dropped from 1 m on the ground (fluid forces off): "
               "each apex is e^2 times the one before.")
    # 2. and 3. a box on an incline
    fig, ax = plt.subplots(figsize=(6, 3.5))
    box = {"name": "box", "shape": {"type": "box", "size": [0.1, 0.08, 0.04]}, "density": 600,
           "count": 1, "position": [0, 0, 0.02]}
    for th_deg, mu in ((20, 0.2), (30, 0.3), (20, 0.5)):
        th = math.radians(th_deg)
        b = dict(box, contact={"restitution": 0.0, "friction": mu})
        gvec = (G * math.sin(th), 0, -G * math.cos(th))
        slides = mu < math.tan(th)
        dur = 2.0 if slides else 10.0
        _, summ, out = vc.run_scene(args, scene(b, gvec, dur, 1e-3, 0.01),
                                    st.path("incline_%d_mu%g" % (th_deg, mu)))
        tr = vc.read_traj(os.path.join(out, "trajectories.csv"))
        t, x = tr["t"][:, 0], tr["x"][:, 0] - tr["x"][0, 0]
        ax.plot(t, x, label="th = %d°, mu = %g" % (th_deg, mu))
        if slides:
            a_ref = G * (math.sin(th) - mu * math.cos(th))
            a = np.polyfit(t, x, 2)[0] * 2  # x = a t^2 / 2 (from rest)
            st.check("th = %d°, mu = %g: sliding acceleration" % (th_deg, mu), a, a_ref, 0.02,
                     COULOMB, unit="m/s²", rel=True)
        else:
            d = math.hypot(x[-1], tr["y"][-1, 0] - tr["y"][0, 0])
            st.check("th = %d°, mu = %g > tan th: displacement over 10 s" % (th_deg, mu), d, 0.0,
                     1e-6, "static friction holds the box", unit="m")
            st.check("th = %d°, mu = %g: final state" % (th_deg, mu),
                     "sleeping" if summ["states"]["sleeping"] == 1 else "not sleeping",
                     "sleeping", 0, "resting for 0.5 s puts a body to sleep",
                     verdict="PASS" if summ["states"]["sleeping"] == 1 else "FAIL",
                     tol_text="-")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("distance down the slope [m]")
    ax.legend()
    ax.grid(alpha=0.3)
    st.savefig(fig, "incline.png", "A box on an incline: it slides with g (sin th − mu cos th) "
               "when mu < tan th and stays when mu > tan th.")
    wind_scene(args, st)
    st.finish()


def surface_points(shape):
    """contact points of a shape in its body frame (box: corners; ellipsoid: 26 directions)"""
    if shape["type"] == "box":
        h = np.array(shape["size"]) / 2
        return np.array([[sx * h[0], sy * h[1], sz * h[2]] for sx in (-1, 1) for sy in (-1, 1)
                         for sz in (-1, 1)])
    a = np.array(shape["semi_axes"] if shape["type"] == "ellipsoid" else [shape["radius"]] * 3)
    u = np.array([[i, j, k] for i in (-1, 0, 1) for j in (-1, 0, 1) for k in (-1, 0, 1)
                  if (i, j, k) != (0, 0, 0)], dtype=float)
    return u / np.sqrt(((u / a) ** 2).sum(axis=1))[:, None]


def rotate(q, p):
    """world offsets of body-frame points p (m, 3) for quaternions q (n, 4: w x y z): (n, m, 3)"""
    w, x, y, z = q[:, 0], q[:, 1], q[:, 2], q[:, 3]
    R = np.stack([np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], -1),
                  np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], -1),
                  np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], -1)],
                 1)
    return np.einsum("nij,mj->nmi", R, p)


def wind_scene(args, st):
    s, why = vc.wind_scene_json(args.quick)
    if s is None:
        st.note("wind scene skipped: %s" % why)
        return
    try:
        lr = vc.import_lrigid(args)
    except SystemExit as e:
        st.note("wind scene skipped: %s" % e)
        return
    _, summ, out = vc.run_scene(args, s, st.path("wind"), threads=2)
    rows = list(csv.DictReader(open(os.path.join(out, "trajectories.csv"))))
    nb = max(int(r["body"]) for r in rows) + 1
    shapes = {b["name"]: surface_points(b["shape"]) for b in s["bodies"]}
    g = lr.Grid(s["fluid"]["field"])
    ground = s["ground"]["z"]
    deepest, where = 0.0, ""
    by_type = {}
    for r in rows:
        if r["state"] == "exited":
            continue
        by_type.setdefault(r["type"], []).append(r)
    for name, rs in by_type.items():
        x = np.array([[float(r[c]) for c in ("x", "y", "z")] for r in rs])
        q = np.array([[float(r[c]) for c in ("qw", "qx", "qy", "qz")] for r in rs])
        pts = x[:, None, :] + rotate(q, shapes[name])
        flat = pts.reshape(-1, 3)
        wd = np.asarray(g.sample(flat)["wall_distance"]).reshape(pts.shape[:2])
        depth = np.maximum(-wd, ground - pts[:, :, 2]).max(axis=1)
        k = int(np.argmax(depth))
        if depth[k] > deepest:
            deepest = float(depth[k])
            where = "%s body %s at t = %s s (%s), (%.2f, %.2f, %.2f) m" % (
                name, rs[k]["body"], rs[k]["t"], rs[k]["state"], x[k, 0], x[k, 1], x[k, 2])
    st.check("wind scene (%d bodies, %g s): deepest contact point inside a solid or the ground "
             "at any output time" % (nb, s["duration"]), deepest, 0.0, 0.01,
             "contacts keep bodies out of the solids", unit="m", note=where)
    states = summ["states"]
    removed = summ["contacts"]["removed"]
    st.check("wind scene: bodies stopped against a wall (exited but not removed at the grid's "
             "edge, or landed)", states["exited"] - removed + states.get("landed", 0), 0, 0,
             "walls and ground collide: nothing stops in mid-air")
    last = [r for r in rows if float(r["t"]) == max(float(x["t"]) for x in rows[-nb:])]
    on = [r for r in last if r["state"] in ("resting", "sleeping", "sliding")]
    roof = sum(float(r["z"]) > 0.5 for r in on)
    st.note("wind scene, %d bodies, %g s: at the end %d on the roof or a ledge (z > 0.5 m), "
            "%d on the ground, %d flying, %d left the grid (removed); final states %s; %d "
            "touched the ground, %d contact events" % (
                nb, s["duration"], roof, len(on) - roof,
                sum(r["state"] == "flying" for r in last), removed,
                ", ".join("%s %d" % kv for kv in sorted(states.items()) if kv[1]),
                summ["contacts"]["touched_ground"], summ["contacts"]["events"]))


if __name__ == "__main__":
    main()
