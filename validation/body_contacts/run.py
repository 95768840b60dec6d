#!/usr/bin/python3
"""Study: contacts between bodies (body_contact "collide", docs/contacts.md "Bodies against each
other"), each against a closed form. The fluid is still air and its forces are off (effects:
gravity only), so only gravity and the contacts act.

1. Two spheres head-on, unequal masses (m2 = 3 m1), restitution e = 0, 0.5, 1: after the impact
   u1' = (m1 u1 + m2 u2 - m2 e (u1 - u2)) / (m1 + m2), u2' = (m1 u1 + m2 u2 + m1 e (u1 - u2)) /
   (m1 + m2) (Newton's restitution with momentum conserved). Tolerance 1 % of |u1 - u2|.
   Off-centre, frictionless, impact parameter = radius: along the line of centres at contact the
   head-on rule, across it the velocities unchanged. Tolerance 1 % of the relative speed.
2. Newton's cradle, three equal spheres 1 mm apart (the sequential-collision idealization), e = 1,
   no friction: the last leaves with the first's speed, the first two stop (1 %). Reported: the
   same spheres touching (gap 0), where one simultaneous solve of both contacts does not give the
   textbook cradle.
3. Five boxes (4 x 3 x 2 cm, 1000 kg/m3, friction 0.5, e = 0) stacked on the ground stand 10 s:
   every box moves less than 0.1 mm (at every output), and the stack ends asleep.
4. A block (4 x 4 x 2 cm) sliding at v0 = 0.5 m/s on a heavy base (12 x 10 x 2 cm, 5000 kg/m3) on
   the ground, friction 0.4: Coulomb friction mu m g decelerates it to a stop after
   v0^2 / (2 mu g) (2 %); the base does not move (0.1 mm).
5. A heap: 60 spheres (r = 1 cm, e 0.2, friction 0.5, rolling resistance 0.3) dropped in layers of
   3 x 3 onto the ground: no two overlap by more than 1 mm at any output (centre distance below
   2 r - 1 mm, from trajectories.csv), all resting or sleeping at the end, and a heap (some
   centre above 2 cm, i.e. on other spheres).
6. The wind scene (scenes/leaves_wind.json with body_contact collide, on the windCourtyard grid;
   LRIGID_WIND_GRID=FILE: another conversion of the case; --quick: 200 bodies, 10 s): no body
   inside another at the end (summary.json body_contact.deepest_overlap_end below 1 mm);
   reported: how many end asleep or resting, and the touching pair-steps.
Each run is lrigid run on a scene written here, read back from trajectories.csv and summary.json.
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
NEWTON = "Newton's restitution, momentum conserved"
OBLIQUE = "Newton's restitution along the normal, frictionless: tangential parts unchanged"
CRADLE = "sequential elastic impacts of equal masses"
COULOMB = "Coulomb friction: stops after v0^2 / (2 mu g)"


def scene(bodies, gravity, duration, dt, every, ground=False):
    s = {"version": 1, "fluid": vc.uniform_fluid(1.204, 1.5e-5),
         "gravity": list(gravity), "effects": ["gravity"],
         "integrator": {"scheme": vc.SCHEME, "dt": dt}, "duration": duration, "seed": 1,
         "body_contact": "collide",
         "bodies": bodies, "output": {"every": every, "formats": ["csv"]}}
    if ground:
        s["ground"] = {"z": 0.0, "contact": "collide"}
    return s


def body(name, shape, density, x, v=(0, 0, 0), e=0.0, mu=0.0, **contact):
    c = {"restitution": e, "friction": mu}
    c.update(contact)
    return {"name": name, "shape": shape, "density": density, "count": 1,
            "position": list(x), "velocity": list(v), "contact": c}


def sphere(r):
    return {"type": "sphere", "radius": r}


def box(lx, ly, lz):
    return {"type": "box", "size": [lx, ly, lz]}


def states(out):
    """the state column of trajectories.csv, shaped (frames, bodies)"""
    rows = list(csv.DictReader(open(os.path.join(out, "trajectories.csv"))))
    nb = max(int(r["body"]) for r in rows) + 1
    return np.array([r["state"] for r in rows]).reshape(len(rows) // nb, nb)


def masses(summ):
    return [t["mass"] for t in sorted(summ["body_types"], key=lambda t: t["first_body"])]


def head_on(args, st):
    r, u1, u2 = 0.01, 1.0, -0.5
    du = abs(u1 - u2)
    for e in (0.0, 0.5, 1.0):
        bs = [body("a", sphere(r), 1000, (-0.03, 0, 0), (u1, 0, 0), e, 0.3),
              body("b", sphere(r), 3000, (0.03, 0, 0), (u2, 0, 0), e, 0.3)]
        tr, summ, _ = vc.run_scene(args, scene(bs, (0, 0, 0), 0.05, 1e-4, 0.01),
                                   st.path("head_on_e%g" % e))
        m1, m2 = masses(summ)
        ref = ((m1 * u1 + m2 * u2 - m2 * e * (u1 - u2)) / (m1 + m2),
               (m1 * u1 + m2 * u2 + m1 * e * (u1 - u2)) / (m1 + m2))
        for k, name in enumerate(("u1'", "u2'")):
            st.check("head-on, m2 = 3 m1, e = %g: %s" % (e, name), tr["vx"][-1, k], ref[k],
                     0.01 * du, NEWTON, unit="m/s", tol_text="±1 %% of |u1 - u2| = %g m/s"
                     % (0.01 * du))


def off_centre(args, st):
    r, u = 0.01, 1.0
    # a moves along x; b sits off a's line by r: at contact the normal from b to a is
    n = np.array([-math.sqrt(3.0) * r, -r, 0.0]) / (2 * r)
    for e in (0.5, 1.0):
        bs = [body("a", sphere(r), 1000, (-0.03, 0, 0), (u, 0, 0), e, 0.0),
              body("b", sphere(r), 2000, (0.0, r, 0), (0, 0, 0), e, 0.0)]
        tr, summ, _ = vc.run_scene(args, scene(bs, (0, 0, 0), 0.05, 1e-4, 0.01),
                                   st.path("off_centre_e%g" % e))
        m1, m2 = masses(summ)
        ua, ub = np.array([u, 0, 0]), np.zeros(3)
        an, bn = ua @ n, ub @ n
        an2 = (m1 * an + m2 * bn - m2 * e * (an - bn)) / (m1 + m2)
        bn2 = (m1 * an + m2 * bn + m1 * e * (an - bn)) / (m1 + m2)
        got = [np.array([tr[c][-1, k] for c in ("vx", "vy", "vz")]) for k in (0, 1)]
        ref_n = (an2, bn2)
        ref_t = (ua - an * n, ub - bn * n)
        err_n = max(abs(got[k] @ n - ref_n[k]) for k in (0, 1))
        err_t = max(np.linalg.norm(got[k] - (got[k] @ n) * n - ref_t[k]) for k in (0, 1))
        note = "a: %s m/s, b: %s m/s after" % tuple(
            "(%.4f, %.4f, %.4f)" % tuple(g) for g in got)
        st.check("off-centre (impact parameter = r, m2 = 2 m1, mu = 0), e = %g: largest error "
                 "of the normal velocities / relative speed" % e, err_n / u, 0.0, 0.01,
                 NEWTON + " along the normal", note=note)
        st.check("off-centre, e = %g: largest change of the tangential velocities / relative "
                 "speed" % e, err_t / u, 0.0, 0.01, OBLIQUE)


def cradle(args, st):
    r, u = 0.01, 0.5
    out = {}
    for gap in (0.001, 0.0):
        d = 2 * r + gap
        bs = [body(nm, sphere(r), 1000, (x, 0, 0), (u if k == 0 else 0, 0, 0), 1.0, 0.0)
              for k, (nm, x) in enumerate((("a", -d), ("b", 0.0), ("c", d)))]
        tr, _, _ = vc.run_scene(args, scene(bs, (0, 0, 0), 0.02, 1e-4, 2e-4),
                                st.path("cradle_gap%gmm" % (gap * 1e3)))
        out[gap] = tr
    tr = out[0.001]
    for k, ref in enumerate((0.0, 0.0, u)):
        st.check("Newton's cradle, 3 equal spheres 1 mm apart, e = 1: velocity of sphere %d "
                 "after" % (k + 1), tr["vx"][-1, k], ref, 0.01 * u, CRADLE, unit="m/s",
                 tol_text="±1 %% of u = %g m/s" % (0.01 * u))
    v = out[0.0]["vx"][-1]
    st.note("Newton's cradle with the spheres touching (gap 0, e = 1, u = %g m/s on the first): "
            "velocities after %.4f, %.4f, %.4f m/s = (%.4f, %.4f, %.4f) u (momentum %.4f u, "
            "kinetic energy %.4f of the initial). One simultaneous solve of both contacts with "
            "Newton's restitution (separation speed e times the approach speed at each, the "
            "second contact approaching at 0) gives -u/3, 2u/3, 2u/3; the textbook cradle "
            "(0, 0, u) is the sequential idealization of check 2." % (
                u, v[0], v[1], v[2], v[0] / u, v[1] / u, v[2] / u, v.sum() / u,
                (v ** 2).sum() / u ** 2))
    fig, ax = plt.subplots(figsize=(6, 3.5))
    for gap, ls in ((0.001, "-"), (0.0, "--")):
        t = out[gap]["t"][:, 0]
        for k in range(3):
            ax.plot(t, out[gap]["vx"][:, k], ls, color="C%d" % k,
                    label="sphere %d, gap %g mm" % (k + 1, gap * 1e3))
    ax.set_xlabel("t [s]")
    ax.set_ylabel("velocity along the row [m/s]")
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    st.savefig(fig, "cradle.png", "Newton's cradle of three equal spheres, e = 1: 1 mm apart "
               "(solid) the last leaves with the first's speed; touching (dashed) one "
               "simultaneous solve shares it out (spheres 2 and 3 leave together).")


def stack(args, st):
    bs = [body("box%d" % k, box(0.04, 0.03, 0.02), 1000, (0, 0, 0.01 + 0.02 * k), e=0.0, mu=0.5)
          for k in range(5)]
    tr, _, out = vc.run_scene(args, scene(bs, (0, 0, -G), 10.0, 1e-3, 0.1, ground=True),
                                 st.path("stack"))
    d = np.sqrt((tr["x"] - tr["x"][0]) ** 2 + (tr["y"] - tr["y"][0]) ** 2 +
                (tr["z"] - tr["z"][0]) ** 2)
    f, k = np.unravel_index(np.argmax(d), d.shape)
    st.check("stack of 5 boxes on the ground, 10 s: largest displacement of any box at any "
             "output", d.max(), 0.0, 1e-4, "stacked boxes stand (static friction, no creep)",
             unit="m", note="box %d at t = %g s" % (k + 1, tr["t"][f, k]))
    last = states(out)[-1]
    asleep = int((last == "sleeping").sum())
    st.check("stack of 5 boxes: boxes asleep at the end", asleep, len(bs), 0,
             "an island at rest for sleep_time sleeps",
             note="final states %s" % ", ".join(last))


def slider(args, st):
    mu, v0, x0 = 0.4, 0.5, -0.03
    bs = [body("base", box(0.12, 0.10, 0.02), 5000, (0, 0, 0.01), e=0.0, mu=mu),
          body("slider", box(0.04, 0.04, 0.02), 1000, (x0, 0, 0.03), (v0, 0, 0), 0.0, mu)]
    tr, _, _ = vc.run_scene(args, scene(bs, (0, 0, -G), 0.5, 1e-3, 0.005, ground=True),
                               st.path("slider"))
    d_ref = v0 ** 2 / (2 * mu * G)
    t = tr["t"][:, 1]
    x = tr["x"][:, 1] - x0
    st.check("block sliding on a block (mu = %g, v0 = %g m/s): distance to the stop" % (mu, v0),
             x[-1], d_ref, 0.02, COULOMB, unit="m", rel=True,
             note="final speed %.2g m/s" % math.sqrt(tr["vx"][-1, 1] ** 2 +
                                                     tr["vy"][-1, 1] ** 2))
    base = np.sqrt((tr["x"][:, 0] - tr["x"][0, 0]) ** 2 + (tr["y"][:, 0] - tr["y"][0, 0]) ** 2 +
                   (tr["z"][:, 0] - tr["z"][0, 0]) ** 2)
    st.check("block sliding on a block: largest displacement of the base at any output",
             base.max(), 0.0, 1e-4, "ground friction holds the base (mu (m_base + m_block) g "
             "> mu m_block g)", unit="m")
    ts = v0 / (mu * G)
    tt = np.linspace(0, t[-1], 400)
    xr = np.where(tt < ts, v0 * tt - mu * G * tt ** 2 / 2, d_ref)
    fig, ax = plt.subplots(figsize=(6, 3.5))
    ax.plot(tt, xr * 1e3, "k--", label="closed form: v0 t - mu g t²/2 until t = v0/(mu g)")
    ax.plot(t, x * 1e3, "C0.", ms=3, label="lrigid: the block")
    ax.plot(t, (tr["x"][:, 0] - tr["x"][0, 0]) * 1e3, "C1-", label="lrigid: the base")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("displacement along x [mm]")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    st.savefig(fig, "slider.png", "A 4 x 4 x 2 cm block sliding at 0.5 m/s on a heavy base, "
               "friction 0.4: it stops after v0²/(2 mu g) = %.1f mm; the base stays." %
               (d_ref * 1e3))


def heap(args, st):
    r, n = 0.01, 60
    bs = []
    for i in range(n):
        layer = i // 9
        shift = 0.005 * (1 if layer % 2 == 0 else -1)
        x = (-0.022 + 0.022 * (i % 3) + shift, -0.022 + 0.022 * (i // 3 % 3),
             0.011 + 0.025 * layer)
        bs.append(body("ball%02d" % i, sphere(r), 1000, x, e=0.2, mu=0.5,
                       rolling_resistance=0.3))
    tr, _, out = vc.run_scene(args, scene(bs, (0, 0, -G), 3.0, 1e-3, 0.05, ground=True),
                                 st.path("heap"))
    p = np.stack([tr["x"], tr["y"], tr["z"]], axis=-1)  # (frames, bodies, 3)
    iu = np.triu_indices(n, 1)
    worst, when = 0.0, ""
    for f in range(p.shape[0]):
        dist = np.linalg.norm(p[f][:, None, :] - p[f][None, :, :], axis=-1)[iu]
        k = int(np.argmin(dist))
        if 2 * r - dist[k] > worst:
            worst = 2 * r - dist[k]
            when = "spheres %d and %d at t = %g s" % (iu[0][k], iu[1][k], tr["t"][f, 0])
    st.check("heap of 60 spheres: deepest overlap of two spheres at any output", worst, 0.0,
             1e-3, "no body inside another (2 r - centre distance)", unit="m", note=when,
             tol_text="< 1 mm", verdict="PASS" if worst < 1e-3 else "FAIL")
    last = states(out)[-1]
    still = int(np.isin(last, ("resting", "sleeping")).sum())
    speed = np.sqrt(tr["vx"][-1] ** 2 + tr["vy"][-1] ** 2 + tr["vz"][-1] ** 2).max()
    spin = np.sqrt(tr["wx"][-1] ** 2 + tr["wy"][-1] ** 2 + tr["wz"][-1] ** 2).max()
    st.check("heap of 60 spheres: resting or sleeping at the end (3 s)", still, n, 0,
             "the heap comes to rest", note="final states %s; largest speed %.2g m/s, spin "
             "%.2g rad/s" % (", ".join("%s %d" % (s, (last == s).sum()) for s in sorted(set(last))),
                             speed, spin))
    zmax = tr["z"][-1].max()
    st.check("heap of 60 spheres: highest centre at the end", zmax, 0.02, 0.0,
             "a heap, not one layer (a sphere on the ground has its centre at r = 1 cm)",
             unit="m", tol_text="> 0.02 m", verdict="PASS" if zmax > 0.02 else "FAIL")
    fig, ax = plt.subplots(figsize=(8, 3))
    cmap = plt.get_cmap("viridis")
    y = p[-1, :, 1]
    for k in np.argsort(-y):  # seen from -y: the nearer (smaller y) drawn last, in front
        ax.add_patch(plt.Circle((p[-1, k, 0] * 100, p[-1, k, 2] * 100), r * 100, ec="k",
                                lw=0.4, fc=cmap((y[k] - y.min()) / max(np.ptp(y), 1e-9))))
    ax.axhline(0, color="k", lw=1)
    ax.set_xlim(p[-1, :, 0].min() * 100 - 2, p[-1, :, 0].max() * 100 + 2)
    ax.set_ylim(-0.5, p[-1, :, 2].max() * 100 + 2)
    ax.set_aspect("equal")
    ax.set_xlabel("x [cm]")
    ax.set_ylabel("z [cm]")
    ax.grid(alpha=0.3)
    st.savefig(fig, "heap.png", "The heap of 60 spheres at the end, side view (colour: y, "
               "dark in front); "
               "centres above 2 cm lie on other spheres.")


def wind_scene(args, st):
    s, why = vc.wind_scene_json(args.quick)
    if s is None:
        st.note("wind scene skipped: %s" % why)
        return
    _, summ, _ = vc.run_scene(args, s, st.path("wind"), threads=2)
    nb = summ["bodies"]
    bc = summ["body_contact"]
    st.check("wind scene (%d bodies, %g s, body_contact %s): deepest overlap of two bodies at "
             "the end" % (nb, s["duration"], bc["mode"]), bc["deepest_overlap_end"], 0.0, 1e-3,
             "no body inside another", unit="m", tol_text="< 1 mm",
             verdict="PASS" if bc["deepest_overlap_end"] < 1e-3 else "FAIL")
    sts = summ["states"]
    st.note("wind scene, %d bodies, %g s: at the end %d asleep, %d resting, %d sliding, %d "
            "flying, %d left the grid; %d touching pair-steps, %d sleeping bodies woken by "
            "a contact" % (nb, s["duration"], sts["sleeping"], sts["resting"], sts["sliding"],
                           sts["flying"], sts["exited"], bc["pair_steps"], bc["woken"]))


def main():
    args = vc.parse_args()
    st = vc.Study("body_contacts", "Contacts between bodies: impacts, a cradle, a stack, a "
                  "sliding block, a heap", args)
    head_on(args, st)
    off_centre(args, st)
    cradle(args, st)
    stack(args, st)
    slider(args, st)
    heap(args, st)
    wind_scene(args, st)
    st.finish()


if __name__ == "__main__":
    main()
