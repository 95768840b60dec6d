// Basset-Boussinesq history force (docs/physics/basset.md; physics-notes §6). For a sphere in
// unsteady Stokes flow (Maxey & Riley 1983), with g = u - v the fluid velocity minus the body's
// (world frame):
//   F_B(t) = C int_0^t g'(tau) / sqrt(t - tau) dtau,
//   C = 6 a^2 rho sqrt(pi nu) = 3/2 d^2 sqrt(pi rho mu)
// with a = r_eq for other shapes. The memory term is evaluated with g' piecewise constant per
// step (dt = h):
//   - the current interval, exactly: 2 C sqrt(h) (g_{n+1} - g_n) / h. It acts like a mass
//     2 C sqrt(h) and goes on the left-hand side (integrate/integrators.cpp); explicit it
//     would be the same instability as an explicit added mass.
//   - a window of the W previous intervals, exactly: weights 2 (sqrt((m+1) h) - sqrt(m h));
//   - the older tail with an exponential sum s^-1/2 ~ sum_i c_i exp(-lambda_i s), valid for
//     (W+1) h <= s <= s_max, each mode updated recursively (van Hinsberg et al., JCP 2011, use the
//     same window + exponential-tail split). The sum is the trapezoidal rule, step du, of
//     s^-1/2 = 2/sqrt(pi) int exp(u - s e^{2u}) du (lambda = e^{2u}, c = 2/sqrt(pi) du e^u),
//     accurate to ~1e-4 relative for du = 0.5, plus the truncation at small lambda (<= 1e-3).
// The initial jump g(0) (a body released with a velocity relative to the fluid) is not counted:
// the history starts at t = 0.
// History of one body (BassetKernel::stride() doubles), vectors of 4 doubles (x, y, z and a pad,
// so that the push works on whole vector registers): g_n, the cached history force of the next
// step per unit C, the window (W vectors, newest first), the tail modes (one vector per mode;
// padded to a multiple of 4 modes of weight 0), and the count of windowed intervals.
#pragma once
#include "effects/context.h"
#include "effects/wrench.h"
#include "model/model.h"

namespace lrigid {

constexpr int kBassetWindow = 8;          // steps kept exactly
constexpr double kBassetModeStep = 0.5;   // du of the exponential sum
constexpr double kBassetTailTolerance = 1e-3;  // relative truncation at s_max
constexpr double kBassetMergeSlow = 0.05;      // modes with lambda s_max below it become one

// Kernel of a body type for step h and memory up to s_max (s).
BassetKernel make_basset_kernel(double coef, double h, int window, double s_max);

// The exponential-sum tail alone at lag s (s^-1/2 for window h < s <= s_max), for tests.
double basset_tail_kernel(const BassetKernel& k, double s);

// History force from the past intervals at the end of the current step, world frame, N.
inline Vec3 basset_history_force(const BassetKernel& k, const double* history) {
  return k.coef * Vec3(history[4], history[5], history[6]);
}

// Body frame wrench of the past history (at the centre of mass), N.
inline Wrench basset_wrench(const BodyType& type, const Mat3& Rt, const double* history) {
  return make_wrench(Rt * basset_history_force(type.basset, history), Vec3::Zero());
}

// the scalar step's term (the registry's row)
// (no history, as for a body evaluated at rest outside its step: no force)
inline Vec6 basset_term(const EffectContext& c) {
  return c.history ? basset_wrench(*c.type, c.Rt, c.history) : Vec6::Zero();
}

// Starts a history with relative velocity g0 (world frame, m/s).
void basset_reset(const BassetKernel& k, const Vec3& g0, double* history);

// Appends the step that ended with relative velocity g (world frame) and refreshes the cache.
void basset_push(const BassetKernel& k, const Vec3& g, double h, double* history);

}  // namespace lrigid
