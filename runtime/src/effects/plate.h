// The plate model of flat bodies (BodyType::flat), written once: Andersen, Pesavento & Wang's
// (2005) drag, dissipative pitching torque and circulation lift in 3D (docs/physics/lift.md;
// the equations and constants are stated in effects/drag.h and effects/lift.h). The scalar
// step's wrappers plate_drag_wrench (effects/drag.cpp) and lift_wrench (effects/lift.cpp) and
// the batched loops of integrate/rigid_batch_step.h all call plate_kernel.
#pragma once
#include <cmath>
#include <type_traits>

#include "effects/drag.h"
#include "effects/lift.h"
#include "util/lane.h"

namespace lrigid {

// x^N for a whole N >= 1, by multiplications (the lift's circulation gate)
template <int N, typename T>
LRIGID_LANE T ipow(T x) {
  static_assert(N >= 1, "ipow takes a positive whole exponent");
  if constexpr (N == 1) {
    return x;
  } else if constexpr (N % 2 == 0) {
    const T h = ipow<N / 2>(x);
    return h * h;
  } else {
    return x * ipow<N - 1>(x);
  }
}

// The share of APW's circulation present at Re = |u| width / nu: x / (1 + x), x = (Re/Re_c)^n
template <typename T>
LRIGID_LANE T circulation_gate(T re) {
  const T x = ipow<kLiftReExponent>(re * T(1.0 / kLiftReCritical));
  return x / (T(1) + x);
}

// The plate's finite-span coefficients (docs/physics/lift.md, "The 3D model"): APW's 2D
// constants, with the drag's normal-force part B scaled so that the broadside drag coefficient
// A + B is the planform's, and the pitch-rate terms C_R, mu1, mu2 scaled by the finite wing's
// share of the 2D lift slope; C_T and A - B are APW's. aspect: the planform's side ratio (long /
// short side of a rectangle, major / minor axis of an ellipse or of a mesh's equivalent
// ellipse), >= 1.
struct PlateCoeffs {
  double aspect = 1;       // planform side ratio
  double cd90 = 0;         // broadside drag coefficient C_D(90 deg) of the planform
  double span_factor = 1;  // (cd90 - (A - B)) / (2 B) of APW's A, B: 1 for an infinite strip
  double span_aspect = 0;  // aspect ratio span^2 / S (a rectangle's side ratio, 4/pi an ellipse's)
  double finite_span = 1;  // plate_finite_span(span_aspect): 1 for an infinite strip
  double A = kPlateDragA, B = kPlateDragB;  // drag (A - B cos 2a)
  double C_T = kLiftTranslational, C_R = kLiftRotational;
  double mu1 = kPlateTorqueMu1;  // linear damping torque (at Re_fit)
  double mu2 = kPlateTorqueMu2;  // quadratic (pressure) damping torque
  double munk = 1;  // the share of its added mass's Munk couple the plate keeps: finite_span
};
// broadside C_D of a flat plate of side ratio `aspect` (rectangle, or ellipse if !box)
double plate_broadside_cd(double aspect, bool box);
// Helmbold's ratio of a finite wing's lift slope to the 2D 2 pi at aspect ratio span^2 / S:
// AR / (2 + sqrt(AR^2 + 4)); 0.236 for a square, 0.291 for a disk, -> 1 for a long strip
double plate_finite_span(double span_aspect);
PlateCoeffs plate_coefficients(const BodyType& type);

// The planform integrals of strip theory about an in-plane axis through the centroid: the plate
// is cut into strips across the axis, each a 2D section of APW's model with its own chord
// (rectangles; ellipses: see below).
// d = (d1, d2): unit direction across the axis in the plate's axes e1, e2; x = d . r the
// distance from the axis. Per unit span APW's rotational lift is 1/2 rho C_R l^2 w u and their
// pitching torque pi rho a^4 (mu1 U / a + mu2 |w|) w (l = 2a the chord), so summed over strips
//   K_R = int l(s)^2 ds              (s along the axis; l S for a strip of chord l)
//   J2  = int x^2 dA,  J3 = int |x|^3 dA   (a strip: 2 a^3 / 3 and a^4 / 2 per unit span)
// and the torque is pi rho (3/2 mu1 U J2 + 2 mu2 |w| J3). Closed forms (docs/physics/lift.md):
// rectangle of half sides c1, c2: x = u + v with u, v uniform on [-p, p], [-q, q],
//   p = c1 |d1|, q = c2 |d2|, P = max, Q = min: J2 = S (p^2 + q^2) / 3,
//   J3 = S (P^3 / 4 + P Q^2 / 2 + Q^4 / (20 P)); l(s) is a trapezoid of height l0 = S / (s1 + s2)
//   over |s| <= s1, falling to 0 at s2 (s2 = c1 |d2| + c2 |d1|, s1 = |c1 |d2| - c2 |d1||), so
//   K_R = 2/3 l0^2 (2 s1 + s2);
// A rectangle about an axis along a side gives l S, 2 c^3 L / 3 and c^4 L / 2 (L: span along
// the axis): APW's strip exactly.
// Ellipses (and a mesh's equivalent ellipse) take the mid-chord form: one strip of
// the chord through the centre l0 = 2 / |(d1 / c1, d2 / c2)| and span S / l0, i.e. K_R = l0 S,
// J2 = l0^2 S / 12, J3 = l0^3 S / 32. Their own strip sums (half width across the axis
// h = |(c1 d1, c2 d2)|: K_R = 8 l0 S / (3 pi), J2 = S h^2 / 4, J3 = 8 S h^3 / (15 pi); a disk:
// 0.85, 0.75, 0.68 times the mid-chord values) are not used: with them the elliptic strips of
// scenes/plate_tumble.json do not tumble (docs/physics/lift.md).
template <typename T>
struct PlateStrips {
  T KR, J2, J3;  // m^3, m^4, m^5
};
// A planform (body/planform.h) takes w times the rectangle's (half sides c1, c2) integrals and
// 1 - w times the ellipse's (semi-axes a1, a2), both of area S.
template <typename T>
LRIGID_LANE void plate_strips(T w, bool rect, bool ell, T c1, T c2, T a1, T a2, T S, T d1, T d2,
                              PlateStrips<T>* o) {
  const T tiny = T(std::is_same_v<T, float> ? 1e-30 : 1e-300);
  const T ad1 = std::abs(d1), ad2 = std::abs(d2);
  // rectangle
  const T p = c1 * ad1, q = c2 * ad2;
  const T P0 = p > q ? p : q, Q = p > q ? q : p;
  const T P = P0 > tiny ? P0 : tiny;
  const T Q2 = Q * Q;
  const T J3_box = S * (P * P * P * T(0.25) + T(0.5) * P * Q2 + Q2 * Q2 / (T(20) * P));
  const T J2_box = S * (p * p + q * q) * T(1.0 / 3.0);
  const T s2 = c1 * ad2 + c2 * ad1, s1 = std::abs(c1 * ad2 - c2 * ad1);
  const T l0 = S / (s1 + s2 > tiny ? s1 + s2 : tiny);
  const T KR_box = T(2.0 / 3.0) * l0 * l0 * (T(2) * s1 + s2);
  // ellipse: the mid-chord strip
  // (a spin along the normal has no mid-chord strip: its length is kept finite, 1e6 times the
  // ellipse's size, so that the rectangle's weight w = 1 still takes the rectangle's exactly)
  const T q1 = d1 / a1, q2 = d2 / a2;
  const T qq = q1 * q1 + q2 * q2, qmin = T(1e-12) / (a1 * a1 + a2 * a2);
  const T l0e = T(2) / std::sqrt(qq > qmin ? qq : qmin);
  const T l0e2S = l0e * l0e * S;
  const T J2_ell = l0e2S * T(1.0 / 12.0), J3_ell = l0e2S * l0e * T(1.0 / 32.0);
  const T KR_ell = l0e * S;
  // w x + (1 - w) y; a rectangle (rect: w = 1) and an ellipse (ell: w = 0) take their own
  // value outright, so that their arithmetic is that of the shape alone
  const T we = T(1) - w;
  T KR = w * KR_box + we * KR_ell, J2 = w * J2_box + we * J2_ell, J3 = w * J3_box + we * J3_ell;
  KR = ell ? KR_ell : KR, J2 = ell ? J2_ell : J2, J3 = ell ? J3_ell : J3;
  o->KR = rect ? KR_box : KR;
  o->J2 = rect ? J2_box : J2;
  o->J3 = rect ? J3_box : J3;
}

// What the plate model needs of a flat body type and the fluid, built once per body type.
struct PlateParams {
  double rho = 0, nu = 0;  // kg/m^3, m^2/s
  // the plate normal n and the in-plane axes e1, e2 as unit vectors of the body frame
  double n[3] = {0, 0, 0}, e1[3] = {0, 0, 0}, e2[3] = {0, 0, 0};
  double S = 0, rect = 0;    // planform area, m^2; the rectangle's weight w (body/planform.h)
  double c1 = 0, c2 = 0;     // the planform's rectangle's half sides along e1, e2, m
  double a1 = 0, a2 = 0;     // the planform's ellipse's semi-axes along e1, e2, m
  double width_over_nu = 0;  // planform width / nu (the Reynolds number per speed), s/m
  double apw_speed = 0;      // APW's velocity scale (0: the speed itself), m/s
  // the Stokes resistance of the plate's equivalent ellipsoid, diagonal in the plate's axes: along
  // (n, e1, e2) in this order
  double sf[3] = {0, 0, 0}, c_visc = 0;  // mu k_i, mu max k_i (Stokes force), N s/m
  double st[3] = {0, 0, 0};              // mu r_i, N m s
  double rot_n = 0;                      // out-of-roundness drag of the spin about n, N m s^2
  double drag = 0, lift = 0;             // the effects as factors 1 or 0
  // the finite-span coefficients (PlateCoeffs)
  double drag_a = kPlateDragA, drag_b = kPlateDragB;
  double lift_t = kLiftTranslational, lift_r = kLiftRotational;
  double mu1 = kPlateTorqueMu1, mu2 = kPlateTorqueMu2;
};
// drag, lift: whether the drag (and torque) and the lift are computed
PlateParams plate_params(const BodyType& type, double rho, double nu, bool drag, bool lift);

// The plate's drag force and torque (times PlateParams::drag) with their stiffness in d, and
// its lift force (times PlateParams::lift; no torque about the centroid) in lift, for relative
// velocity u of the centroid and spin w, body frame.
// Drag, Lift: whether the kernel computes the drag (d) and the lift (lift) at all; the scalar
// step's wrappers ask for one each, the batched loops for both (PlateParams' factors then say
// which the body type has).
template <typename T, bool Drag = true, bool Lift = true>
LRIGID_LANE void plate_kernel(const PlateParams& k, const T* u, const T* w, DragOut<T>* d,
                              T* lift) {
  const T rho = T(k.rho);
  // the coefficients, read before any branch: a load inside a conditional stops the batched
  // loops from vectorizing (GCC cannot prove it safe to do unconditionally; 3x slower on plates)
  const T drag_a = T(k.drag_a), drag_b = T(k.drag_b), mu1_fit = T(k.mu1), mu2 = T(k.mu2);
  const T lift_t_s = T(k.lift_t * k.S), lift_r = T(k.lift_r);
  const T n[3] = {T(k.n[0]), T(k.n[1]), T(k.n[2])};
  const T e1[3] = {T(k.e1[0]), T(k.e1[1]), T(k.e1[2])},
          e2[3] = {T(k.e2[0]), T(k.e2[1]), T(k.e2[2])};
  const T sf_n = T(k.sf[0]), sf_1 = T(k.sf[1]), sf_2 = T(k.sf[2]);
  const T st_n = T(k.st[0]), st_1 = T(k.st[1]), st_2 = T(k.st[2]);
  const T s2 = dot3(u, u);
  const T speed = std::sqrt(s2);
  const bool moving = speed > T(0);
  const T inv = T(1) / (moving ? speed : T(1));
  const T un = dot3(n, u);
  // APW's drag 1/2 rho S (A - B cos 2a) |u| u, cos 2a = (|u_t|^2 - u_n^2) / |u|^2
  const T cos2a = (s2 - T(2) * un * un) * (inv * inv);
  const T c_lin =
      moving ? T(0.5) * rho * T(k.S) * (drag_a - drag_b * cos2a) * speed : T(0);
  // the in-plane part of the spin and the unit direction d across it, in the plate's axes
  const T wn = dot3(n, w);
  T wp[3];
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) wp[a] = w[a] - wn * n[a];
  const T wp_norm = std::sqrt(dot3(wp, wp));
  const bool spinning = wp_norm > T(0);
  T dir[3];
  cross3(n, wp, dir);
  const T winv = T(1) / (spinning ? wp_norm : T(1));
  // not spinning: any direction (the terms below are then multiplied by 0)
  const T d1 = spinning ? dot3(e1, dir) * winv : T(1), d2 = spinning ? dot3(e2, dir) * winv : T(0);
  PlateStrips<T> ps;
  plate_strips(T(k.rect), k.rect >= 1, k.rect <= 0, T(k.c1), T(k.c2), T(k.a1), T(k.a2), T(k.S), d1,
               d2, &ps);
  // APW's pitching torque per unit span pi rho a^4 (mu1 U / a + mu2 |w|) w summed over the
  // strips across the axis: pi rho (3/2 mu1 U J2 + 2 mu2 |w_p| J3) w_p; mu1 scaled as a laminar
  // boundary layer
  const T Uv = k.apw_speed > 0 ? T(k.apw_speed) : speed;
  const T re_w = speed * T(k.width_over_nu);
  const T re = re_w > T(kPlateTorqueReMin) ? re_w : T(kPlateTorqueReMin);
  const T mu1 = mu1_fit * std::sqrt(T(kPlateTorqueFitRe) / re);
  const T lin = T(1.5 * M_PI) * rho * mu1 * Uv * ps.J2, quad = T(2 * M_PI) * rho * mu2 * ps.J3;
  const T pitch = spinning ? lin + quad * wp_norm : T(0);
  const T c_pitch = spinning ? lin + T(2) * quad * wp_norm : T(0);
  // spin about the normal: the Stokes torque plus the out-of-roundness drag
  const T c_n = st_n + T(k.rot_n) * std::abs(wn);
  if constexpr (Drag) {
    const T dr = T(k.drag);
    // the Stokes force and the in-plane Stokes torque in the plate's axes (a turned planform's
    // e1, e2 are not body axes): the velocity's and the spin's components along them
    const T u1 = dot3(e1, u), u2 = dot3(e2, u), w1 = dot3(e1, wp), w2 = dot3(e2, wp);
    const T fs_n = sf_n * un, fs_1 = sf_1 * u1, fs_2 = sf_2 * u2;
    const T ts_1 = st_1 * w1, ts_2 = st_2 * w2;
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      const T stokes_f = fs_n * n[a] + fs_1 * e1[a] + fs_2 * e2[a];
      const T stokes_t = ts_1 * e1[a] + ts_2 * e2[a];
      d->f[a] = dr * (-c_lin * u[a] - stokes_f);
      d->tq[a] = dr * (-pitch * wp[a] - stokes_t - c_n * wn * n[a]);
      d->u_hat[a] = moving ? u[a] * inv : T(0);
    }
    // stiffness: the quadratic part c_lin (I + u^ u^T) and the viscous part c_visc I
    const T c_tot = c_lin + T(k.c_visc);
    d->c_lin = dr * c_tot;
    d->p = c_tot > T(0) ? c_lin / c_tot : T(0);
    // per body axis (the normal is one): in the plane the pitch damping's and that axis's
    // Stokes torque's, about the normal twice c_n (its |w_n| part's derivative). One value for
    // all three (the largest) made the implicit step damp the pitch of a long strip by the
    // Stokes torque of its spin about the normal, 40 times its inertia per step
    // (docs/physics/integrators.md, "The angular stiffness per axis")
    // (the in-plane Stokes torque's stiffness on body axis a: its diagonal entry there)
    const T cn2 = T(2) * c_n;
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      const T nn = n[a] * n[a];  // 1 on the normal's axis, 0 on the others
      const T st_a = st_1 * (e1[a] * e1[a]) + st_2 * (e2[a] * e2[a]);
      d->c_ang[a] = dr * (nn * cn2 + (T(1) - nn) * (c_pitch + st_a));
    }
  }
  if constexpr (Lift) {
    // translational -rho C_T S (u_n / |u|) (|u_t|^2 n - u_n u_t) and rotational
    // 1/2 rho C_R K_R w_p x u (APW's 1/2 rho C_R l^2 per unit span, summed over the strips
    // across the axis: K_R = l S for a strip), both times the circulation gate
    const T gate = T(k.lift) * circulation_gate(re_w);
    T ut[3];
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) ut[a] = u[a] - un * n[a];
    const T ut2 = dot3(ut, ut);
    const T lt = moving ? -rho * gate * lift_t_s * (un * inv) : T(0);
    const T lr = spinning ? T(0.5) * rho * gate * lift_r * ps.KR : T(0);
    T wxu[3];
    cross3(wp, u, wxu);
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) lift[a] = lt * (ut2 * n[a] - un * ut[a]) + lr * wxu[a];
  }
}

}  // namespace lrigid
