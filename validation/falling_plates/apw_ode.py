#!/usr/bin/python3
"""Andersen, Pesavento & Wang's 2D quasi-steady ODE for a falling strip, as a reference.

lrigid's plate model (docs/physics/lift.md) is APW's model generalized to 3D. Where the 3D model
and experiments disagree on the flutter-tumble boundary, this module answers the first question:
does APW's own 2D ODE, with its published coefficients, put the boundary where the experiments
do? Nondimensional form (physics-notes §4, thin-strip limit: ε = b/a → 0; x along the plate,
y normal; lengths in units of the half chord a, velocities in U = sqrt((ρ_s/ρ_f − 1) g b)):

    I* u' = (I* + 1) ω v − Γ v − sin θ − F_u
    (I* + 1) v' = −I* ω u + Γ u − cos θ − F_v
    (I* + 1/2)/4 ω' = −u v − (μ1 + μ2|ω|) ω,      θ' = ω
    Γ = (2/π)(−C_T u v/|V| + C_R ω),   F = (1/π)(A − B (u² − v²)/|V|²)|V| (u, v)

with C_T = 1.2, C_R = π, A = 1.4, B = 1.0, μ1 = μ2 = 0.2. Here I* = ρ_s b/(ρ_f a) is the plate's
mass over the fluid mass πρ_f a² of the circumscribed circle; a box of thickness h and width w has
the mass ratio (4/π) ρ_s h/(ρ_f w). Integrated with classical RK4 (dt = 0.01 in units of a/U) from
rest at 10° for 400 time units; the regime is read from the second half.
"""
import collections
import math

import numpy as np

# cop: apply the rotational circulation lift at Rayleigh's centre of pressure, a distance
# (3/4) l cos α/(4 + π sin α) ahead of the centre (l = 2a the chord, α the angle of attack),
# instead of at the centre. Not APW's model: the variant docs/physics/lift.md discusses.
# rect: the strip is a thin rectangle, not an ellipse: its own moment of inertia is m a²/3
# instead of m a²/4 (the added mass and inertia are the flat plate's either way: π ρ_f a² and
# π ρ_f a⁴/8), i.e. (I*/3 + 1/8) ω' instead of (I* + 1/2)/4 ω'. The 3D model's rectangular
# strip (validation/falling_plates, the box 2D limit) is this ODE.
Coeffs = collections.namedtuple("Coeffs", "C_T C_R A B mu1 mu2 cop rect")
APW = Coeffs(C_T=1.2, C_R=math.pi, A=1.4, B=1.0, mu1=0.2, mu2=0.2, cop=False, rect=False)


def rates(s, istar, c=APW):
    u, v, w, th = s
    V = math.hypot(u, v) + 1e-9
    G_rot = (2 / math.pi) * c.C_R * w
    G = (2 / math.pi) * (-c.C_T * u * v / V) + G_rot
    fd = (1 / math.pi) * (c.A - c.B * (u * u - v * v) / (V * V)) * V
    du = ((istar + 1) * w * v - G * v - math.sin(th) - fd * u) / istar
    dv = (-istar * w * u + G * u - math.cos(th) - fd * v) / (istar + 1)
    torque = -u * v - (c.mu1 + c.mu2 * abs(w)) * w
    if c.cop:
        x_cp = 2 * 3 * abs(u) / V / (4 * (4 + math.pi * abs(v) / V))   # in units of a
        torque += math.copysign(x_cp, u) * G_rot * u
    inertia = istar / 3 + 0.125 if c.rect else 0.25 * (istar + 0.5)
    dw = torque / inertia
    return np.array([du, dv, dw, w])


# Releases (u, v, ω, θ in the units above) for asking whether a regime depends on how the strip
# starts: from rest at 10° and at 60°, spinning at ω a/U = 0.5 and 1.5 from level, and moving
# along and across the plate while spinning
RELEASES = (("rest, 10°", (0.0, 0.0, 0.0, math.radians(10.0))),
            ("rest, 60°", (0.0, 0.0, 0.0, math.radians(60.0))),
            ("level, spin 0.5", (0.0, 0.0, 0.5, 0.0)),
            ("level, spin 1.5", (0.0, 0.0, 1.5, 0.0)),
            ("moving, spin 1", (1.0, -1.0, 1.0, 0.5)))


def trajectory(istar, c=APW, t_end=400.0, dt=0.01, theta0=math.radians(10.0), state0=None):
    """States (u, v, ω, θ) after each RK4 step from the release (state0, or rest at theta0), an
    array of shape (n, 4); None when the state overflows."""
    s = np.array(state0 if state0 is not None else [0.0, 0.0, 0.0, theta0], dtype=float)
    n = int(round(t_end / dt))
    out = np.empty((n, 4))
    for i in range(n):
        k1 = rates(s, istar, c)
        k2 = rates(s + 0.5 * dt * k1, istar, c)
        k3 = rates(s + 0.5 * dt * k2, istar, c)
        k4 = rates(s + dt * k3, istar, c)
        s = s + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        out[i] = s
        if not math.isfinite(s[0] + s[1] + s[2] + s[3]) or abs(s[2]) > 1e6:
            return None
    return out


def regime(istar, c=APW, t_end=400.0, dt=0.01, theta0=math.radians(10.0), state0=None):
    """("steady" | "flutter" | "chaotic" | "tumble" | "runaway", net turns and pitch peak-to-peak
    in degrees over the second half); "runaway" when the state overflows. state0: the release
    (u, v, ω, θ) instead of rest at theta0."""
    tr = trajectory(istar, c, t_end, dt, theta0, state0)
    if tr is None:
        return "runaway", math.nan, math.nan
    return classify_angle(tr[len(tr) // 2:, 3])


def tip_speed_ratio(istar, c=APW, t_end=400.0):
    """(regime, mean|ω| a / mean|V|) over the second half, released from rest at 10°: how fast
    the strip turns against how fast it moves (ω a/|V| in the ODE's units)."""
    tr = trajectory(istar, c, t_end)
    if tr is None:
        return "runaway", math.nan
    h = tr[len(tr) // 2:]
    return (classify_angle(h[:, 3])[0],
            float(np.mean(np.abs(h[:, 2])) / np.mean(np.hypot(h[:, 0], h[:, 1]))))


def classify_angle(phi):
    """Regime of a pitch-angle history (radians, unwrapped, uniformly sampled): tumble when it
    turns more than once in total and keeps one sense of rotation (≥ 90 % of the samples); chaotic
    when it swings through more than a full turn but reverses; flutter for swings of 20° to a
    turn; steady below 5°. Returns (regime, net turns, peak-to-peak in degrees)."""
    d = np.diff(phi)
    net = (phi[-1] - phi[0]) / (2 * math.pi)
    p2p = math.degrees(np.ptp(phi))
    same = max(np.mean(d > 0), np.mean(d < 0)) if len(d) else 0.0
    if abs(net) > 1 and same >= 0.9:
        reg = "tumble"
    elif p2p > 360:
        reg = "chaotic"
    elif p2p > 20:
        reg = "flutter"
    elif p2p < 5:
        reg = "steady"
    else:
        reg = "unclassified"
    return reg, net, p2p


def release_regimes(istar, c=APW, t_end=400.0):
    """[(release label, regime)] for every release of RELEASES."""
    return [(label, regime(istar, c, t_end=t_end, state0=s0)[0]) for label, s0 in RELEASES]


def transition(istars=(0.2, 0.4, 0.6, 0.8, 1.0, 1.2, 1.5, 2.0, 3.0), c=APW):
    return [(i,) + regime(i, c) for i in istars]


# One change at a time (coefficients scaled by 0 to 3, or a torque added): does any
# of them move the model's flutter-tumble boundary down to the experiments' I*?
LEVERS = (("C_T x 0.5", APW._replace(C_T=0.6)), ("C_T x 2", APW._replace(C_T=2.4)),
          ("C_T x 3", APW._replace(C_T=3.6)), ("C_R x 0.5", APW._replace(C_R=0.5 * math.pi)),
          ("A, B x 0.5", APW._replace(A=0.7, B=0.5)),
          ("mu1 = 0, mu2 x 0.25", APW._replace(mu1=0.0, mu2=0.05)),
          # a torque that drives rotation as autorotating plates show: net linear term
          # pro-rotation, so a plate spinning in a stream settles at ω a/U = 0.15/0.2
          ("mu1 = -0.15 (autorotation)", APW._replace(mu1=-0.15)),
          ("rotational lift at the centre of pressure", APW._replace(cop=True)))


def lever_sweep(istars=(0.2, 0.35, 0.5, 0.8, 1.5), levers=LEVERS, t_end=300.0):
    """[(label, [regime at each I*])] for the coefficient variants in `levers`."""
    return [(label, [regime(i, c, t_end=t_end)[0] for i in istars]) for label, c in levers]


if __name__ == "__main__":
    for row in transition():
        print("I* = %.2f: %s (net %.1f turns, pitch peak-to-peak %.0f°)" % row)
    for label, regs in lever_sweep():
        print("%s: %s" % (label, " ".join(regs)))
