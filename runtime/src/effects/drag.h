// Quasi-steady drag on the motion relative to the fluid (docs/physics/drag.md).
// Linear: F = -1/2 rho |u| u [C_D(Re) A_perp + C_s (A_max - A_perp)], applied at the volume
// centroid, with u the centroid's velocity relative to the fluid, A_perp the projected area of
// the body's equivalent ellipsoid normal to u, C_D the Schiller-Naumann law at
// Re = |u| d_perp / nu, d_perp = 2 sqrt(A_perp/pi) (exactly Schiller-Naumann for a sphere), and
// C_s a small edgewise (skin-friction) coefficient for flat bodies.
// Angular: T_a = -(8 pi mu r_m^3 + 1/2 rho C_rot L5_a |w|) w_a: Stokes rotational resistance of
// the sphere of mean radius plus quadratic pressure drag from the body's out-of-roundness
// (L5_a = l_a |l_b^4 - l_c^4|, zero for a sphere; 1/2 rho C_D w^2 a b^4 for a flat plate).
#pragma once
#include <cmath>

#include "effects/wrench.h"
#include "model/drag_out.h"
#include "model/model.h"
#include "util/fast_math.h"
#include "util/lane.h"

namespace lrigid {

constexpr double kDragEdgewise = 0.1;   // C_s
constexpr double kDragRotation = 1.2;   // C_rot (flat-plate normal drag ~1.2)

// Schiller & Naumann (1935): C_D = 24/Re (1 + 0.15 Re^0.687), Re < 1000; 0.44 above.
double schiller_naumann(double re);

// Stiffness of the drag for the linearly implicit step: d(-wrench)/d(xi) approximated as
// diag(c_lin (I + p u^ u^T), diag(c_ang)), c_ang per body axis (N m s). Per axis, not one value
// for all three: a plate's damping about its normal and about its in-plane axes differ by orders
// of magnitude on long strips (docs/physics/integrators.md, "The angular stiffness per axis").
struct DragStiffness {
  double c_lin = 0, p = 0;
  double c_ang[3] = {0, 0, 0};
  Vec3 u_hat = Vec3::Zero();
};

// ---- the kernel, written once: the scalar step (drag_wrench) and the batched step's loops
// (integrate/rigid_batch_step.h) call it ---------------------------------------------------------

// What the drag law needs of a body type and the fluid, built once per body type.
struct DragParams {
  double rho = 0, nu = 0;  // fluid density (kg/m^3) and kinematic viscosity (m^2/s)
  double area_max = 0;     // largest projected area, m^2
  double c_ang0 = 0;       // Stokes rotational drag 8 pi mu r_m^3, N m s
  // 1/2 rho C_rot int r^3 dA per axis, N m s^2; rho C_rot times the largest
  double rot[3] = {0, 0, 0}, rot_max = 0;
  // products of the equivalent ellipsoid's semi-axes l1 l2, l0 l2, l0 l1 (projected area), m^2
  double l12 = 0, l02 = 0, l01 = 0;
};
DragParams drag_params(const BodyType& type, double rho, double nu);

// The projected area of the equivalent ellipsoid across the unit direction uh, m^2, and the
// diameter of the disk of that area, m.
template <typename T>
LRIGID_LANE void ellipsoid_projected_area(const DragParams& k, const T* uh, T* a_perp,
                                          T* d_perp) {
  const T p0 = T(k.l12) * uh[0], p1 = T(k.l02) * uh[1], p2 = T(k.l01) * uh[2];
  *a_perp = T(M_PI) * std::sqrt(p0 * p0 + p1 * p1 + p2 * p2);
  *d_perp = T(2) * std::sqrt(*a_perp * T(1.0 / M_PI));
}

// The drag law on relative velocity u (of the volume centroid) and spin w, both in the body
// frame: Schiller-Naumann on the projected area area(u_hat, &a_perp, &d_perp) (m^2, and the
// diameter of the disk of that area, m) across the flow, the edgewise skin drag and the
// rotational drag. The torque is about the centroid. Math: LaneMath in the batched loops,
// ScalarMath in the scalar step (util/fast_math.h).
template <class Math = LaneMath, typename T, class Area>
LRIGID_LANE DragOut<T> drag_kernel(const DragParams& k, const T* u, const T* w, Area area) {
  DragOut<T> d;
  const T speed = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  const bool moving = speed > T(0);
  const T inv = T(1) / (moving ? speed : T(1));
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) d.u_hat[a] = moving ? u[a] * inv : T(0);
  T a_perp, d_perp;
  area(d.u_hat, &a_perp, &d_perp);
  const T re = speed * d_perp / T(k.nu);
  const T re_safe = moving ? re : T(1);
  // C_D Re = 24 (1 + 0.15 Re^0.687) below Re = 1000, 0.44 above; force ~ speed^(1 + p).
  // Written as a branch so that the scalar step skips the power in the Newton regime; the
  // batched loops (built with -fno-trapping-math) if-convert it into a blend.
  T cd = T(0.44), p = T(1);
  if (!(re >= T(1000))) {
    const T s = T(0.15 * Math::pow(double(re_safe), 0.687));
    cd = T(24) / re_safe * (T(1) + s);
    p = T(0.687) * s / (T(1) + s);
  }
  const T c_moving =
      T(0.5 * k.rho) * speed * (cd * a_perp + T(kDragEdgewise) * (T(k.area_max) - a_perp));
  const T c_lin = moving ? c_moving : T(0);
  d.c_lin = c_lin;
  d.p = moving ? p : T(0);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) d.f[a] = -c_lin * u[a];
  const T w_norm = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) d.tq[a] = -(T(k.c_ang0) + T(k.rot[a]) * w_norm) * w[a];
  const T c_ang = T(k.c_ang0) + T(k.rot_max) * w_norm;
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) d.c_ang[a] = c_ang;
  return d;
}

// drag_kernel with the equivalent ellipsoid's projected area (any body that is not flat)
template <class Math = LaneMath, typename T>
LRIGID_LANE DragOut<T> ellipsoid_drag_kernel(const DragParams& k, const T* u, const T* w) {
  return drag_kernel<Math>(k, u, w, [&k](const T* uh, T* a_perp, T* d_perp) {
    ellipsoid_projected_area(k, uh, a_perp, d_perp);
  });
}

// ---- the scalar step's wrappers (Eigen, the centre of buoyancy anywhere) -----------------------

// u_rel: velocity of the centre of mass relative to the fluid (body frame), w: angular velocity
// relative to the fluid (body frame).
Wrench drag_wrench(const BodyType& type, const Vec3& u_rel, const Vec3& w, double rho, double nu,
                   DragStiffness* stiffness = nullptr);

// Drag of flat bodies (BodyType::flat), after Andersen, Pesavento & Wang (2005), in 3D
// (docs/physics/lift.md): F = -1/2 rho S (A - B cos 2a) |u| u with cos 2a = (|u_t|^2 - u_n^2)/|u|^2
// (a: angle of attack, S: planform area), and the dissipative torque about the in-plane axes
// T = -pi rho c^4 L (mu1(Re) U / c + mu2 |w_p|) w_p per strip of half chord c and span L across
// w_p, summed over the planform's strips (plate_strips, effects/plate.h; U the APW velocity
// scale sqrt(|rho_b/rho_f - 1| g b), b the half thickness). APW fitted
// these at Re ~ 10^3, where viscous stresses are negligible; the viscous part is added as the
// exact Stokes resistance of the equivalent ellipsoid, F_i = -mu k_i u_i and T_i = -mu r_i w_i
// (BodyType::stokes_force, stokes_torque), which dominates as Re falls (Re < ~30). Spin about the
// normal: the Stokes torque plus the generic out-of-roundness drag.
// APW's strip values; a finite plate's B (and so A = (A - B) + B) follows its broadside C_D and
// its mu1, mu2 its aspect ratio (plate_coefficients, effects/plate.h)
constexpr double kPlateDragA = 1.4;   // APW 2005
constexpr double kPlateDragB = 1.0;
constexpr double kPlateTorqueMu1 = 0.2;  // at Re = kPlateTorqueFitRe
constexpr double kPlateTorqueMu2 = 0.2;
// mu1 is the linear, viscous part of APW's torque; they fitted it at Re ~ 10^3. Scaled with the
// laminar boundary-layer law mu1 (Re_fit / Re)^(1/2), Re = |u| w / nu (w: planform width), Re
// held at >= kPlateTorqueReMin (below it the Stokes torque dominates).
constexpr double kPlateTorqueFitRe = 1000.0;
constexpr double kPlateTorqueReMin = 10.0;

// Stokes-flow resistance of an ellipsoid of semi-axes s (Oberbeck 1876, Edwardes 1892, Jeffery
// 1922; Happel & Brenner 1965 section 5-11): along axis i F_i = -mu k_i u_i with
// k_i = 16 pi / (chi + s_i^2 a_i), about axis i T_i = -mu r_i w_i with
// r_i = 16 pi (s_j^2 + s_k^2) / (3 (s_j^2 a_j + s_k^2 a_k)), where
// a_i = int_0^inf dl / ((s_i^2 + l) D(l)), D(l) = sqrt(prod_j (s_j^2 + l)), chi = sum_i s_i^2 a_i.
// k in m, r in m^3 (sphere: 6 pi R and 8 pi R^3; disk of radius R: 16 R broadside, 32/3 R edgewise,
// 32/3 R^3 about a diameter).
void ellipsoid_stokes_resistance(const Vec3& s, Vec3* k, Vec3* r);

Wrench plate_drag_wrench(const BodyType& type, const Vec3& u_rel, const Vec3& w, double rho,
                         double nu, DragStiffness* stiffness = nullptr);

// the scalar step's terms (the registry's row picks one by the body's flatness), on the body
// type's cached kernel parameters (effects/plan.h); the stiffness goes to c.stiffness
struct EffectContext;
Vec6 drag_term(const EffectContext& c);
Vec6 plate_drag_term(const EffectContext& c);

}  // namespace lrigid
