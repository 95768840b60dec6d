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
Each run is lrigid run on a scene written here, read back from trajectories.csv.
"""
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
            "integrator": {"scheme": "splitting", "dt": dt}, "duration": duration, "seed": 1,
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
    st.finish()


if __name__ == "__main__":
    main()
