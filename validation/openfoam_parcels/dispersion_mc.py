#!/usr/bin/python3
"""Independent Monte Carlo of the two turbulent-dispersion models on a foam2grid field.

The spread of landing points with turbulent dispersion differs between lrigid and OpenFOAM by
construction; how much depends on the whole path (the shear of the mean flow, the variation of k
and epsilon along the fall, the flight time each particle happens to take), which a 1-D estimate
along the mean path misses. This module re-implements both models from their equations, in numpy,
on the same grid, so that the study can compare each code with its own model and take the
expected spread ratio from the same geometry:

* lrigid's "seen" Langevin model (docs/physics/langevin.md): the fluid fluctuation u' seen by
  the particle follows an Ornstein-Uhlenbeck process per component, alpha = 3/4 C0 eps/k
  ("stationary" drift), beta^2 = C0 eps, C0 from Sawford's fit of R_lambda, with Thomson's
  well-mixed drift 1/2 grad(sigma^2) + u' v.grad(sigma^2) / (2 sigma^2) along the parcel's path
  (v its velocity); u' starts from its stationary distribution at the release point. Crossing
  trajectories (Csanady): the time scale is 1/alpha divided by b = (1 + 0.64 vd^2/sigma^2)^1/2
  along the drift (down) and b' = (1 + 2.56 vd^2/sigma^2)^1/2 across it, the noise amplitude
  multiplied by sqrt(b), vd the particle's settling speed in still fluid.
* OpenFOAM's stochasticDispersionRAS (read from its source, v1912 = OpenFOAM-dev here): a
  random velocity sigma |xi| e, sigma = sqrt(2k/3), xi standard normal, e a uniform random
  direction, held for the eddy lifetime t_e = min(k/eps, 0.16432 k^1.5 / (eps |u_rel|)) and then
  redrawn; zero where t_e < dt; zero until the first lifetime has elapsed after injection.

Both: point particles with Schiller-Naumann drag, gravity and buoyancy, released at rest,
landing where they reach z = 0; particles that leave the fluid (the grid's valid points carry
less than half of the trilinear weight, the runtime's rule) are not counted. Differences from
the codes, stated so the comparison's tolerance can be judged: trilinear field values everywhere
(OpenFOAM's dispersion model reads the cell-centre k and epsilon); grad(sigma^2) by central
differences of the interpolated field; a semi-implicit Euler step of dt for the particle.
"""
import math

import numpy as np

CPS = 0.16432  # C_mu^(3/4), OpenFOAM's stochasticDispersionRAS


class Grid:
    """Trilinear sampling of a foam2grid .vti with the runtime's validity rule."""

    def __init__(self, path):
        import vtk
        from vtk.util import numpy_support as ns
        r = vtk.vtkXMLImageDataReader()
        r.SetFileName(path)
        r.Update()
        img = r.GetOutput()
        self.n = np.array(img.GetDimensions())
        self.o = np.array(img.GetOrigin())
        self.h = np.array(img.GetSpacing())
        pd = img.GetPointData()
        nx, ny, nz = self.n
        shape = (nz, ny, nx)

        def arr(name, comps=1):
            a = ns.vtk_to_numpy(pd.GetArray(name)).astype(float)
            return a.reshape(shape + ((comps,) if comps > 1 else ()))
        self.U = arr("U", 3)
        self.k = arr("k")
        self.eps = arr("epsilon")
        self.valid = arr("valid")

    def sample(self, x):
        """x (N,3) -> U (N,3), k (N), eps (N), inside (N bool)."""
        f = (x - self.o) / self.h
        i0 = np.clip(np.floor(f).astype(int), 0, self.n - 2)
        t = np.clip(f - i0, 0.0, 1.0)
        U = np.zeros((len(x), 3))
        k = np.zeros(len(x))
        e = np.zeros(len(x))
        W = np.zeros(len(x))
        for dz in (0, 1):
            for dy in (0, 1):
                for dx in (0, 1):
                    w = ((t[:, 0] if dx else 1 - t[:, 0]) * (t[:, 1] if dy else 1 - t[:, 1]) *
                         (t[:, 2] if dz else 1 - t[:, 2]))
                    ix, iy, iz = i0[:, 0] + dx, i0[:, 1] + dy, i0[:, 2] + dz
                    w = w * self.valid[iz, iy, ix]
                    W += w
                    U += w[:, None] * self.U[iz, iy, ix]
                    k += w * self.k[iz, iy, ix]
                    e += w * self.eps[iz, iy, ix]
        inside = (W >= 0.5) & np.all(f >= 0, axis=1) & np.all(f <= self.n - 1, axis=1)
        Ws = np.where(W > 0, W, 1.0)
        return U / Ws[:, None], k / Ws, e / Ws, inside


def langevin_coefficients(k, eps, nu):
    """alpha, beta^2, sigma^2 of lrigid's stationary-drift OU process (turbulence_coefficients.h)."""
    k = np.maximum(k, 1e-10)
    eps = np.maximum(eps, 1e-12)
    rl = np.sqrt(20.0 / 3.0 * k * k / (nu * eps))
    c0 = np.maximum(6.5 / (1.0 + 140.0 * rl ** (-4.0 / 3.0)), 1.0)
    beta2 = c0 * eps
    alpha = 0.75 * c0 * eps / k
    cap = np.sqrt(eps / nu)
    alpha_c = np.minimum(alpha, cap)
    sigma2 = beta2 / (2 * alpha)
    return alpha_c, 2 * alpha_c * sigma2, sigma2


def sigma2_at(grid, x, nu):
    _, k, e, _ = grid.sample(x)
    return langevin_coefficients(k, e, nu)[2]


def settling_speed(D, rho_p, rho_f, nu, gravity=9.81):
    """Terminal speed in still fluid with Schiller-Naumann drag, m/s (the drift lrigid's
    compile_model gives a sphere)."""
    gp = gravity * abs(1.0 - rho_f / rho_p)
    tau_st = rho_p * D * D / (18.0 * rho_f * nu)
    v = gp * tau_st
    for _ in range(200):
        v = gp * tau_st / (1.0 + 0.15 * (v * D / nu) ** 0.687)
    return v


def simulate(grid, release, n, model, *, D, rho_p, rho_f, nu, dt, t_end, seed=1,
             gravity=9.81, crossing=True):
    """Land n particles released at rest at `release` with dispersion model "lrigid" or
    "openfoam". crossing: lrigid's crossing-trajectory correction (on by default, as in its
    scenes). Returns (landing x,y array (m,2), number that left the fluid, number airborne)."""
    rng = np.random.default_rng(seed)
    x = np.tile(np.asarray(release, float), (n, 1))
    v = np.zeros((n, 3))
    g = np.array([0.0, 0.0, -gravity * (1.0 - rho_f / rho_p)])
    tau_st = rho_p * D * D / (18.0 * rho_f * nu)
    vd = settling_speed(D, rho_p, rho_f, nu, gravity) if crossing else 0.0
    alive = np.ones(n, bool)
    landed = np.full((n, 2), np.nan)
    left = 0
    up = np.zeros((n, 3))
    t_turb = np.zeros(n)
    if model == "lrigid":
        _, k, e, _ = grid.sample(x)
        up = np.sqrt(langevin_coefficients(k, e, nu)[2])[:, None] * rng.standard_normal((n, 3))
    d = 0.25 * grid.h
    steps = int(round(t_end / dt))
    for _ in range(steps):
        idx = np.nonzero(alive)[0]
        if len(idx) == 0:
            break
        xa, va, ua = x[idx], v[idx], up[idx]
        U, k, e, inside = grid.sample(xa)
        if model == "lrigid":
            alpha, beta2, s2 = langevin_coefficients(k, e, nu)
            grad = np.zeros((len(idx), 3))
            for c in range(3):
                dx = np.zeros(3)
                dx[c] = d[c]
                grad[:, c] = (sigma2_at(grid, xa + dx, nu) - sigma2_at(grid, xa - dx, nu)) / (
                    2 * d[c])
            # along the parcel's path (effects/turbulence.h): its velocity va
            drift = 0.5 * grad + ua * (np.sum(va * grad, axis=1) / (2 * s2))[:, None]
            # per axis: across the drift (x, y) and along it (z)
            r = np.where(s2 > 0, vd * vd / np.where(s2 > 0, s2, 1.0), 0.0)
            b = np.stack([np.sqrt(1 + 2.56 * r)] * 2 + [np.sqrt(1 + 0.64 * r)], axis=1)
            ab = alpha[:, None] * b
            decay = np.exp(-ab * dt)
            noise = np.sqrt(beta2[:, None] * b * -np.expm1(-2 * ab * dt) / (2 * ab))
            ua = decay * ua + dt * drift + noise * rng.standard_normal((len(idx), 3))
        else:
            urel = np.linalg.norm(va - U - ua, axis=1)
            te = np.minimum(k / (e + 1e-300), CPS * k ** 1.5 / (e + 1e-300) / (urel + 1e-15))
            perturbed = dt < te
            tt = t_turb[idx] + dt
            renew = perturbed & (tt > te)
            tt[renew] = 0.0
            m = int(renew.sum())
            if m:
                theta = rng.random(m) * 2 * math.pi
                uu = 2 * rng.random(m) - 1
                a = np.sqrt(1 - uu * uu)
                e_dir = np.stack([a * np.cos(theta), a * np.sin(theta), uu], axis=1)
                ua[renew] = (np.sqrt(2 * k[renew] / 3) * np.abs(rng.standard_normal(m)))[
                    :, None] * e_dir
            ua[~perturbed] = 0.0
            tt[~perturbed] = 1e300
            t_turb[idx] = tt
        uf = U + ua
        rel = np.linalg.norm(uf - va, axis=1)
        re = rel * D / nu
        tau = tau_st / (1.0 + 0.15 * re ** 0.687)
        vn = (va + dt * (g + uf / tau[:, None])) / (1.0 + dt / tau)[:, None]
        xn = xa + dt * vn
        # landing: the step crosses z = 0
        hit = xn[:, 2] <= 0.0
        s = np.where(hit, xa[:, 2] / np.maximum(xa[:, 2] - xn[:, 2], 1e-300), 1.0)
        land_xy = xa[:, :2] + s[:, None] * (xn[:, :2] - xa[:, :2])
        gone = ~inside & ~hit
        landed[idx[hit]] = land_xy[hit]
        left += int(gone.sum())
        x[idx], v[idx], up[idx] = xn, vn, ua
        alive[idx[hit | gone]] = False
    ok = ~np.isnan(landed[:, 0])
    return landed[ok], left, int(alive.sum())
