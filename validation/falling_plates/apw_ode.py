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

with C_T = 1.2, C_R = π, A = 1.4, B = 1.0, μ1 = μ2 = 0.2. Here I* = ρ_s b/(ρ_f a), the ellipse's
thickness-to-width ratio times the density ratio. Integrated with classical RK4 (dt = 0.01 in
units of a/U) from rest at 10° for 400 time units; the regime is read from the second half.
"""
import math

import numpy as np

C_T, C_R, A, B, MU1, MU2 = 1.2, math.pi, 1.4, 1.0, 0.2, 0.2


def rates(s, istar, mu_scale=1.0):
    u, v, w, th = s
    V = math.hypot(u, v) + 1e-9
    G = (2 / math.pi) * (-C_T * u * v / V + C_R * w)
    fd = (1 / math.pi) * (A - B * (u * u - v * v) / (V * V)) * V
    du = ((istar + 1) * w * v - G * v - math.sin(th) - fd * u) / istar
    dv = (-istar * w * u + G * u - math.cos(th) - fd * v) / (istar + 1)
    dw = (-u * v - mu_scale * (MU1 + MU2 * abs(w)) * w) / (0.25 * (istar + 0.5))
    return np.array([du, dv, dw, w])


def regime(istar, mu_scale=1.0, t_end=400.0, dt=0.01, theta0=math.radians(10.0)):
    """("steady" | "flutter" | "chaotic" | "tumble", net turns and pitch peak-to-peak in degrees
    over the second half)."""
    s = np.array([0.0, 0.0, 0.0, theta0])
    n = int(round(t_end / dt))
    th = np.empty(n)
    for i in range(n):
        k1 = rates(s, istar, mu_scale)
        k2 = rates(s + 0.5 * dt * k1, istar, mu_scale)
        k3 = rates(s + 0.5 * dt * k2, istar, mu_scale)
        k4 = rates(s + dt * k3, istar, mu_scale)
        s = s + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        th[i] = s[3]
    return classify_angle(th[n // 2:])


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


def transition(istars=(0.2, 0.4, 0.6, 0.8, 1.0, 1.2, 1.5, 2.0, 3.0), mu_scale=1.0):
    return [(i,) + regime(i, mu_scale) for i in istars]


if __name__ == "__main__":
    for row in transition():
        print("I* = %.2f: %s (net %.1f turns, pitch peak-to-peak %.0f°)" % row)
