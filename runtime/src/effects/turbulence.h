// Langevin turbulence from the local k and epsilon (docs/physics/langevin.md; physics-notes §2).
// Ornstein-Uhlenbeck process du = -alpha u dt + beta dW with alpha, beta from
// fluid/turbulence_coefficients.h. Two models:
//   body: the body's velocity relative to the mean flow follows the OU process directly (the seed
//         method); its angular velocity follows one with the same alpha and beta / r_eq
//         (r_eq: radius of the sphere of equal volume), so <w_i^2> = sigma2 / r_eq^2.
//   seen: the fluctuating fluid velocity u' seen by the body follows the OU process and acts on
//         the body through drag and added mass: heavy bodies filter it, light ones follow it.
//         In inhomogeneous turbulence it carries Thomson's (1987) well-mixed drift
//         a_i = 1/2 d_i sigma2 + u'_i v . grad sigma2 / (2 sigma2), which keeps a uniform
//         cloud of tracers uniform (without it tracers gather where k is low). v is the velocity
//         of the path along which u' is sampled, the body's own: for a tracer v = U + u'
//         (Thomson's form); for a body that lags the fluid the term keeps u' / sigma stationary
//         along its path, where U + u' would feed u' back into itself (d u'/dt ~ u'^2, a
//         blow-up in finite time in steep gradients: docs/physics/langevin.md).
#pragma once
#include <cmath>

#include "fluid/field.h"
#include "util/fast_math.h"
#include "util/lane.h"
#include "util/types.h"

namespace lrigid {

// exact OU update over h: u <- decay u + noise_std xi
struct OUStep {
  double decay = 1;      // exp(-alpha h)
  double noise_std = 0;  // beta sqrt((1 - exp(-2 alpha h)) / (2 alpha)), m/s
};

// The exact update's coefficients, written once (ou_exact and the batched steps' loops call it):
// decay = exp(-alpha h), noise = beta sqrt((1 - exp(-2 alpha h)) / (2 alpha)), m/s, with
// 1 - exp(-y) kept precise for small y; the alpha -> 0 limit is beta sqrt(h). alpha in 1/s, beta
// in m/s^1.5, h in s. Math: util/fast_math.h (LaneMath in the batched loops).
template <class Math = LaneMath>
LRIGID_LANE void ou_exact_kernel(double alpha, double beta, double h, double* decay,
                                 double* noise) {
  const double ah = alpha * h;
  const double a_safe = alpha > 0 ? alpha : 1.0;
  *decay = Math::exp(-ah);
  *noise = beta * (ah > 1e-12 ? std::sqrt(Math::one_minus_exp_neg(2.0 * ah) / (2.0 * a_safe))
                              : std::sqrt(h));
}

// The same with the rate alpha b and the amplitude beta sqrt(b) (the crossing trajectories'
// axes), written so that b cancels under the root and one function call serves both: with
// m = 1 - exp(-alpha b h), decay = 1 - m and 1 - exp(-2 alpha b h) = m (2 - m), so
// noise = beta sqrt(m (2 - m) / (2 alpha)); precise for small alpha b h as m is.
template <class Math = LaneMath>
LRIGID_LANE void ou_exact_scaled_kernel(double alpha, double beta, double b, double h,
                                        double* decay, double* noise) {
  const double ah = alpha * b * h;
  const double a_safe = alpha > 0 ? alpha : 1.0;
  const double m = Math::one_minus_exp_neg(ah);
  *decay = 1.0 - m;
  *noise = beta * (ah > 1e-12 ? std::sqrt(m * (2.0 - m) / (2.0 * a_safe)) : std::sqrt(b * h));
}

// Euler-Maruyama's coefficients over h (the euler and rk4 steps): decay = 1 - alpha h,
// noise = beta sqrt(h), m/s. Written once (integrators.cpp and the batched loops call it).
template <typename T>
LRIGID_LANE void ou_euler_kernel(T alpha, T beta, T h, T* decay, T* noise) {
  *decay = T(1) - alpha * h;
  *noise = beta * std::sqrt(h);
}

inline OUStep ou_exact(double alpha, double beta, double h) {
  OUStep s;
  ou_exact_kernel<ScalarMath>(alpha, beta, h, &s.decay, &s.noise_std);
  return s;
}

// One update of the seen fluctuation us (world frame, m/s) over h with Thomson's well-mixed
// drift (well_mixed_drift) along a path of world velocity V: us <- decay us + h a + noise z,
// a = 1/2 grad sigma2 + us (V . grad sigma2) / (2 sigma2) (0 where sigma2 <= 0), z three standard
// normals. wm: 1 with the drift, 0 without (a factor: no branch in the loops across lanes).
// Written once: the scalar step (integrators.cpp) and the batched loops call it.
template <typename T>
LRIGID_LANE void ou_update(T wm, T decay, T noise, T sigma2, const T* V, const T* gs, const T* z,
                           T h, T* us) {
  const T s_safe = sigma2 > T(0) ? sigma2 : T(1);
  const T proj = (V[0] * gs[0] + V[1] * gs[1] + V[2] * gs[2]) / (T(2) * s_safe);
  const T on = sigma2 > T(0) ? wm : T(0);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a)
    us[a] = decay * us[a] + h * (on * (T(0.5) * gs[a] + us[a] * proj)) + noise * z[a];
}

// Crossing trajectories (Csanady 1963): a body that drifts through the turbulence at v_d relative
// to the fluid leaves each eddy before the eddy forgets itself, so the fluid velocity it sees
// decorrelates faster than a tracer's, most across the drift (continuity). The seen model's time
// scale T_L becomes T_L / b along the drift direction and T_L / b' across it, with
//   b = sqrt(1 + beta^2 v_d^2 / sigma2),  b' = sqrt(1 + 4 beta^2 v_d^2 / sigma2),  beta = 0.8,
// as Wang & Stock (1993), Minier & Peirano (2001) and code_saturne's Lagrangian module take it
// (sigma2: the model's per-component variance, 2k/3 with the stationary drift). Each axis keeps
// the variance sigma2 (noise beta_OU sqrt(b)): the fluid velocity at the body's place has the
// fluid's one-point statistics whatever the path. v_d = 0 (tracers) gives b = b' = 1 exactly.
constexpr double kCsanadyBeta = 0.8;  // ratio of Lagrangian to Eulerian integral time scales, -

// b and b' above for a drift speed squared vd2 (m^2/s^2) at the sample's sigma2 (m^2/s^2); 1 and
// 1 where there is no turbulence (sigma2 <= 0: the noise is 0 there anyway)
template <typename T>
LRIGID_LANE void crossing_factors(T vd2, T sigma2, T* along, T* across) {
  const T r = sigma2 > T(0) ? vd2 / (sigma2 > T(0) ? sigma2 : T(1)) : T(0);
  const T b2 = T(kCsanadyBeta * kCsanadyBeta);
  *along = std::sqrt(T(1) + b2 * r);
  *across = std::sqrt(T(1) + T(4) * b2 * r);
}

// The exact OU coefficients over h with the crossing factors (ou_exact_scaled_kernel): decay and
// noise across the drift, decay_a and noise_a along it. vd2 = 0: both pairs are
// ou_exact_kernel's (alpha, beta), to the bit (a branch: the batched loops call it only for a
// type with a drift, batch_lanes.h ou_coefficients).
template <class Math = LaneMath>
LRIGID_LANE void ou_crossing_exact_kernel(double alpha, double beta, double sigma2, double vd2,
                                          double h, double* decay, double* noise,
                                          double* decay_a, double* noise_a) {
  if (!(vd2 > 0)) {  // a tracer: the isotropic pair
    ou_exact_kernel<Math>(alpha, beta, h, decay, noise);
    *decay_a = *decay;
    *noise_a = *noise;
    return;
  }
  double along, across;
  crossing_factors(vd2, sigma2, &along, &across);
  ou_exact_scaled_kernel<Math>(alpha, beta, across, h, decay, noise);
  ou_exact_scaled_kernel<Math>(alpha, beta, along, h, decay_a, noise_a);
}

// Euler-Maruyama's coefficients with the crossing factors (the euler and rk4 steps). Each factor
// is capped at 1 / (alpha h) (but not below 1), so the decay 1 - alpha b h stays >= 0 wherever
// the tracer's does: a step that does not resolve T_L / b takes the time scale h instead.
template <typename T>
LRIGID_LANE void ou_crossing_euler_kernel(T alpha, T beta, T sigma2, T vd2, T h, T* decay,
                                          T* noise, T* decay_a, T* noise_a) {
  T along, across;
  crossing_factors(vd2, sigma2, &along, &across);
  const T ah = alpha * h;
  const T cap = ah > T(1) ? T(1) : (ah > T(0) ? T(1) / ah : along + across);
  along = along < cap ? along : cap;
  across = across < cap ? across : cap;
  // ou_euler_kernel on alpha b and beta sqrt(b), with one root per pair; b = 1: its values
  *decay = T(1) - alpha * across * h;
  *noise = beta * std::sqrt(across * h);
  *decay_a = T(1) - alpha * along * h;
  *noise_a = beta * std::sqrt(along * h);
}

// ou_update with the crossing trajectories: decay and noise (across the drift) act on every
// component as in ou_update, then the component along the unit drift direction d (world; zero
// without a drift) takes decay_a and noise_a instead. With decay_a == decay and noise_a ==
// noise (no drift) this adds 0: the tracer's update to the bit.
template <typename T>
LRIGID_LANE void ou_update_crossing(T wm, T decay, T noise, T decay_a, T noise_a, const T* d,
                                    T sigma2, const T* V, const T* gs, const T* z, T h, T* us) {
  const T ud = dot3(d, us), zd = dot3(d, z);
  ou_update(wm, decay, noise, sigma2, V, gs, z, h, us);
  const T c = (decay_a - decay) * ud + (noise_a - noise) * zd;
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) us[a] += c * d[a];
}

// Thomson's well-mixed drift correction for the seen fluctuation u' (world frame), m/s^2, for u'
// sampled along a path moving at path_velocity (world frame, m/s).
Vec3 well_mixed_drift(const Vec3& u_seen, const Vec3& path_velocity, const FluidSample& s);

}  // namespace lrigid
