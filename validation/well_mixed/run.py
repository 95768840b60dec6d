#!/usr/bin/python3
"""Study 4: the well-mixed condition (Thomson 1987) in inhomogeneous turbulence.

A grid field at rest (U = 0) whose k grows 16-fold along x (k = 0.01 → 0.16 m²/s² across
x = 0…2 m, constant beyond; ε = k/τ with τ = 3 s, so T_L ≈ 0.7–0.8 s). k depends on x only, and
the grid spans 1000 m in y and z (two points), so no tracer reaches a side in y or z and the
x-distribution is that of an unbounded slab. In x the box is open (x ∈ [−4, 6] m; bodies leaving
it stop), so concentration is counted only in the window x ∈ [−0.5, 2.5] m, more than 3
dispersion lengths from either end for the run time (10 T_L of the high-k side). Tracers (10 µm
neutrally buoyant spheres) start uniformly spread. A well-mixed model keeps the window's histogram
along the gradient flat: chi-square of 6 bins against uniform below its 0.1 % point (20.5 for 5
degrees of freedom) and the low-k/high-k count ratio within 4 standard errors of 1, after 5 and
10 Lagrangian times.

Run for the `seen` model (with Thomson's drift correction) and for the `body` model (the seed
method's OU velocity, no drag, no correction: expected to gather tracers where k is low).
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "lib"))
import gridgen  # noqa: E402
import vcommon as vc  # noqa: E402
from vcommon import np, plt  # noqa: E402

K0, RATIO, TAU = 0.01, 16.0, 3.0
X0, X1 = -4.0, 6.0
WIN = (-0.5, 2.5)
SIDE = 1000.0
NBIN = 6
CHI2_999 = 20.515  # chi-square, 5 dof, upper 0.1 % point


def kfield(x):
    s = np.clip(x / 2.0, 0, 1)
    s = s * s * (3 - 2 * s)
    return K0 * RATIO ** s


def main():
    args = vc.parse_args()
    st = vc.Study("well_mixed", "Well-mixed condition in a k gradient", args)
    h = 0.1
    xs = np.arange(X0, X1 + 1e-9, h)
    shape = (len(xs), 2, 2)
    k = np.broadcast_to(kfield(xs)[:, None, None], shape).copy()
    eps = k / TAU
    grid = st.path("kgradient.vti")
    gridgen.write_vti(grid, (X0, 0.0, 0.0), (h, SIDE, SIDE), shape, np.zeros(shape + (3,)), k,
                      eps, 1.5e-5)
    c0_high = 6.5 / (1 + 140 * math.sqrt(20 / 3 * 0.16 * TAU / 1.5e-5) ** (-4 / 3))
    tl_high = 4 * TAU / (3 * c0_high)
    dur = 10 * tl_high
    n = 20000 if args.quick else 40000
    fig, ax = plt.subplots(figsize=(6, 4))
    edges = np.linspace(WIN[0], WIN[1], NBIN + 1)
    for model in ("seen", "body"):
        effects = ["gravity", "buoyancy", "added_mass", "turbulence"] + (
            ["drag"] if model == "seen" else [])
        sc = {"version": 1, "fluid": {"density": 1.204, "kinematic_viscosity": 1.5e-5,
                                      "field": grid},
              "gravity": [0, 0, -9.81], "effects": effects,
              "integrator": {"scheme": vc.SCHEME, "dt": tl_high / 10}, "duration": dur,
              "seed": 4, "turbulence": {"model": model, "drift": "stationary"},
              "bodies": [{"name": "tracer", "shape": {"type": "sphere", "radius": 5e-6},
                          "density": 1.204, "count": n,
                          "spawn_box": [[X0 + 1e-3, 0.4 * SIDE, 0.4 * SIDE],
                                        [X1 - 1e-3, 0.6 * SIDE, 0.6 * SIDE]]}],
              "output": {"every": dur / 2, "formats": ["csv"]}}
        tr, summ, _ = vc.run_scene(args, sc, st.path(model), threads=2)
        for j in range(tr["t"].shape[0]):
            x = tr["x"][j]
            inw = (x >= WIN[0]) & (x <= WIN[1])
            cnt, _ = np.histogram(x[inw], edges)
            expct = cnt.sum() / NBIN
            chi2 = float(np.sum((cnt - expct) ** 2 / expct))
            lo, hi = cnt[:2].sum(), cnt[-2:].sum()
            ratio = lo / hi
            se = ratio * math.sqrt(1 / lo + 1 / hi)
            t = tr["t"][j, 0]
            if j == 0:
                continue
            lab = "%s model, t = %.0f T_L" % (model, t / tl_high)
            ax.plot(0.5 * (edges[1:] + edges[:-1]), cnt / expct, "o-", label=lab)
            st.check("%s: chi-square of %d x-bins vs uniform (%d tracers in window)" % (
                lab, NBIN, cnt.sum()), chi2, 0.0, CHI2_999, "Thomson 1987 well-mixed condition",
                tol_text="≤ %.1f (χ²₅ 0.1 %% point)" % CHI2_999,
                verdict="PASS" if chi2 <= CHI2_999 else "FAIL")
            st.check("%s: count ratio low-k third / high-k third" % lab, ratio, 1.0, 4 * se,
                     "Thomson 1987 well-mixed condition",
                     tol_text="±%.3f (4 SE, SE %.3f)" % (4 * se, se))
    ax.axhline(1, color="k", lw=0.8)
    ax2 = ax.twinx()
    xx = np.linspace(WIN[0], WIN[1], 200)
    ax2.plot(xx, kfield(xx), "k:", label="k")
    ax2.set_ylabel("k [m²/s²] (dotted)")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("concentration / uniform")
    ax.legend(fontsize=7, loc="upper center")
    st.savefig(fig, "concentration.png", "Tracer concentration across a 16-fold k gradient after "
               "5 and 10 Lagrangian times (1 = uniform)")
    st.note("The body model has no drift correction (docs/physics/langevin.md describes the "
            "correction for the seen model only); its rows show whether tracers gather at low k.")
    st.finish()


if __name__ == "__main__":
    main()
