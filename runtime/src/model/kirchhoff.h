// The free Kirchhoff flow's kernels, written once for the scalar step (integrate/dynamics.cpp,
// T = double) and the batched steps' loops across bodies (integrate/rigid_batch_step.h, double or
// float): the generalized mass M as the kernels see it, the flow's right-hand side, the Newton
// matrix of its implicit midpoint step, and the implicit force step's solve. The drivers (the
// scalar step's early-exit iterations, the lanes' masked ones) stay with their steps.
//
// The flow (dynamics.h kirchhoff_flow): for Y = (P; L) = M xi_r, xi_r = (v - R^T u_f; w),
//   dY/dt = -G(Y),   G(Y) = (w x P; w x L + v x P),   (v; w) = M^-1 Y,
// and one implicit-midpoint step solves Y1 = Y0 - h G((Y0 + Y1)/2), by fixed point first and
// Newton with the matrix I + h/2 dG/dY, where dG/dY = [w^ 0; v^ w^] + [0 -P^; -P^ -L^] M^-1.
#pragma once
#include <cmath>

#include "model/drag_out.h"
#include "util/lane.h"
#include "util/small_lu.h"

namespace lrigid {

// ---- M as the kernels see it --------------------------------------------------------------------

// The Munk couple's share a flat body's separated flow takes back (BodyType::munk_back,
// docs/physics/lift.md "The Munk couple of a finite plate"): with S that 3 x 3 matrix (kg, zero
// for every other body), the moment of the translational momentum P is -v x (P - S v) instead of
// -v x P, the rest of the flow unchanged.
inline constexpr double kNoMunkBack[9] = {};

// A diagonal M (boxes, ellipsoids, spheres with the centre of mass at the centroid): its
// diagonal and the inverse's, kg and kg m^2; S: the diagonal of the Munk share taken back, kg.
struct DiagonalMass {
  double M[6] = {0, 0, 0, 0, 0, 0};
  double Mi[6] = {0, 0, 0, 0, 0, 0};
  double S[3] = {0, 0, 0};
};

// An isotropic M = diag(m, m, m, J, J, J) (uniform spheres): a diagonal M whose free flow is a
// rotation alone (G(Y) = 0) and whose implicit force step has a cheaper closed form
struct IsotropicMass : DiagonalMass {};
inline IsotropicMass isotropic_mass(double m, double J) {
  IsotropicMass r;
  for (int a = 0; a < 3; ++a) {
    r.M[a] = m, r.M[3 + a] = J;
    r.Mi[a] = 1.0 / m, r.Mi[3 + a] = 1.0 / J;
  }
  return r;
}

// A full symmetric M (meshes, bodies with an offset centre of mass): M and M^-1, 36 numbers each
// (symmetric, so row and column major are the same; the scalar step points into BodyType::M and
// M_inv).
struct FullMass {
  const double* M = nullptr;
  const double* Mi = nullptr;
  const double* S = kNoMunkBack;  // the Munk share taken back, 3 x 3 (kg)
};

// x = M^-1 y and x = M y
template <typename T>
LRIGID_LANE void mass_inv_times(const DiagonalMass& m, const T* y, T* x) {
#pragma GCC unroll 6
  for (int a = 0; a < 6; ++a) x[a] = T(m.Mi[a]) * y[a];
}
// x = A y for a symmetric 6 x 6 A
template <typename T>
LRIGID_LANE void symmetric6_times(const double* A, const T* y, T* x) {
#pragma GCC unroll 6
  for (int r = 0; r < 6; ++r) {
    T s = 0;
#pragma GCC unroll 6
    for (int c = 0; c < 6; ++c) s += T(A[r * 6 + c]) * y[c];
    x[r] = s;
  }
}
template <typename T>
LRIGID_LANE void mass_inv_times(const FullMass& m, const T* y, T* x) {
  symmetric6_times(m.Mi, y, x);
}
template <typename T>
LRIGID_LANE void mass_times(const DiagonalMass& m, const T* y, T* x) {
#pragma GCC unroll 6
  for (int a = 0; a < 6; ++a) x[a] = T(m.M[a]) * y[a];
}
template <typename T>
LRIGID_LANE void mass_times(const FullMass& m, const T* y, T* x) {
  symmetric6_times(m.M, y, x);
}

// d^T M^-1 d: twice the kinetic energy of an impulse d (the flow's convergence norm)
template <typename T>
LRIGID_LANE T energy_norm2(const DiagonalMass& m, const T* d) {
  T s = 0;
#pragma GCC unroll 6
  for (int a = 0; a < 6; ++a) s += d[a] * d[a] * T(m.Mi[a]);
  return s;
}
template <typename T>
LRIGID_LANE T energy_norm2(const FullMass& m, const T* d) {
  T x[6];
  mass_inv_times(m, d, x);
  T s = 0;
#pragma GCC unroll 6
  for (int a = 0; a < 6; ++a) s += d[a] * x[a];
  return s;
}

// xi^T M xi: twice the kinetic energy of a velocity xi (the force step's stiffness test)
template <typename T>
LRIGID_LANE T velocity_norm2(const DiagonalMass& m, const T* xi) {
  T s = 0;
#pragma GCC unroll 6
  for (int a = 0; a < 6; ++a) s += xi[a] * xi[a] * T(m.M[a]);
  return s;
}
template <typename T>
LRIGID_LANE T velocity_norm2(const FullMass& m, const T* xi) {
  T x[6];
  mass_times(m, xi, x);
  T s = 0;
#pragma GCC unroll 6
  for (int a = 0; a < 6; ++a) s += xi[a] * x[a];
  return s;
}

// ---- the fluid's impulse ------------------------------------------------------------------------

// K (u; 0): the impulse of the added mass carried along by the fluid moving with u (body frame,
// m/s), K's first three columns (6 components: linear, angular), as the scalar step's
// K_fluid.leftCols<3>() * u (dynamics.cpp velocity_from_impulse). With a diagonal M only K's
// linear diagonal can be non-zero; otherwise (meshes) the 6 x 3 columns, row major. Zero without
// the added-mass effect.
struct DiagonalFluidImpulse {
  double K[3] = {0, 0, 0};
};
struct FullFluidImpulse {
  double K[18] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
};
// the fluid impulse that goes with a kind of M
template <class Mass>
struct FluidImpulseOf {
  using type = FullFluidImpulse;
};
template <>
struct FluidImpulseOf<DiagonalMass> {
  using type = DiagonalFluidImpulse;
};
template <>
struct FluidImpulseOf<IsotropicMass> {
  using type = DiagonalFluidImpulse;
};

template <typename T>
LRIGID_LANE void fluid_impulse(const DiagonalFluidImpulse& k, const T* u, T* p) {
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) {
    p[a] = T(k.K[a]) * u[a];
    p[3 + a] = T(0);
  }
}
template <typename T>
LRIGID_LANE void fluid_impulse(const FullFluidImpulse& k, const T* u, T* p) {
#pragma GCC unroll 6
  for (int r = 0; r < 6; ++r)
    p[r] = T(k.K[r * 3]) * u[0] + T(k.K[r * 3 + 1]) * u[1] + T(k.K[r * 3 + 2]) * u[2];
}

// xi = M^-1 (Pi + K (u; 0)): the velocity (v; w) of the generalized impulse Pi relative to the
// fluid's added-mass impulse (dynamics.h velocity_from_impulse), u the fluid velocity (body frame)
template <typename T, class Mass, class Fluid>
LRIGID_LANE void velocity_of_impulse(const Mass& m, const Fluid& k, const T* Pi, const T* u,
                                     T* xi) {
  T p[6];
  fluid_impulse(k, u, p);
#pragma GCC unroll 6
  for (int a = 0; a < 6; ++a) p[a] += Pi[a];
  mass_inv_times(m, p, xi);
}

// Pi = M xi - K (u; 0), the inverse of velocity_of_impulse (dynamics.h impulse_rates)
template <typename T, class Mass, class Fluid>
LRIGID_LANE void impulse_of_velocity(const Mass& m, const Fluid& k, const T* xi, const T* u,
                                     T* Pi) {
  T p[6];
  fluid_impulse(k, u, p);
  mass_times(m, xi, Pi);
#pragma GCC unroll 6
  for (int a = 0; a < 6; ++a) Pi[a] -= p[a];
}

// ---- the Munk share taken back ------------------------------------------------------------------

// s = S v, the translational momentum that exerts no Munk couple
template <typename T>
LRIGID_LANE void munk_back_momentum(const DiagonalMass& m, const T* v, T* s) {
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) s[a] = T(m.S[a]) * v[a];
}
template <typename T>
LRIGID_LANE void munk_back_momentum(const FullMass& m, const T* v, T* s) {
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a)
    s[a] = T(m.S[3 * a]) * v[0] + T(m.S[3 * a + 1]) * v[1] + T(m.S[3 * a + 2]) * v[2];
}
// Pm = P - S v, the translational momentum whose moment the flow keeps
template <typename T, class Mass>
LRIGID_LANE void munk_kept_momentum(const Mass& m, const T* v, const T* P, T* Pm) {
  T sv[3];
  munk_back_momentum(m, v, sv);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) Pm[a] = P[a] - sv[a];
}

// ---- the free flow --------------------------------------------------------------------------

// g = G(Y) = (w x P; w x L + v x (P - S v)) with (v; w) = M^-1 Y (effects/wrench.h
// kirchhoff_gyro; S: the Munk share taken back, zero but for flat bodies with drag)
template <typename T, class Mass>
LRIGID_LANE void kirchhoff_gyro_kernel(const Mass& m, const T* Y, T* g) {
  T xi[6];
  mass_inv_times(m, Y, xi);
  T a[3], b[3], c[3], Pm[3];
  munk_kept_momentum(m, xi, Y, Pm);
  cross3(xi + 3, Y, a);
  cross3(xi + 3, Y + 3, b);
  cross3(xi, Pm, c);
#pragma GCC unroll 3
  for (int i = 0; i < 3; ++i) {
    g[i] = a[i];
    g[3 + i] = b[i] + c[i];
  }
}

// a^ (r, c): 0 on the diagonal, -a[3 - r - c] above it in cyclic order, + below
template <typename T>
LRIGID_LANE T skew_entry(const T* a, int r, int c) {
  return r == c ? T(0) : ((c - r + 3) % 3 == 1 ? -a[3 - r - c] : a[3 - r - c]);
}
// (v^ S)(r, c)
template <typename T>
LRIGID_LANE T skew_times_S(const DiagonalMass& m, const T* v, int r, int c) {
  return skew_entry(v, r, c) * T(m.S[c]);
}
template <typename T>
LRIGID_LANE T skew_times_S(const FullMass& m, const T* v, int r, int c) {
  return skew_entry(v, r, 0) * T(m.S[c]) + skew_entry(v, r, 1) * T(m.S[3 + c]) +
         skew_entry(v, r, 2) * T(m.S[6 + c]);
}
// A = I + h2 dG/dY at the midpoint impulse ym (h2 = h / 2), row major:
// dG/dY = D + E M^-1 with D = [w^ 0; v^ w^] and E = [0 -P^; -(P - S v)^ - v^ S -L^]: the
// derivative of v x (P - S v) in v is -(P - S v)^ - v^ S, the second term the Munk share's
// (skew_times_S). Diagonal M: E M^-1 scales E's columns.
template <typename T>
LRIGID_LANE void kirchhoff_newton_matrix(const DiagonalMass& m, const T* ym, T h2, T* A) {
  T xi[6], Pm[3];
  mass_inv_times(m, ym, xi);
  const T* v = xi;
  const T* w = xi + 3;
  const T* P = ym;
  const T* L = ym + 3;
  munk_kept_momentum(m, v, P, Pm);
#pragma GCC unroll 3
  for (int r = 0; r < 3; ++r)
#pragma GCC unroll 3
    for (int c = 0; c < 3; ++c) {
      const T one = r == c ? T(1) : T(0);
      A[r * 6 + c] = one + h2 * skew_entry(w, r, c);
      A[r * 6 + 3 + c] = -h2 * skew_entry(P, r, c) * T(m.Mi[3 + c]);
      A[(3 + r) * 6 + c] =
          h2 * (skew_entry(v, r, c) -
                (skew_times_S(m, v, r, c) + skew_entry(Pm, r, c)) * T(m.Mi[c]));
      A[(3 + r) * 6 + 3 + c] =
          one + h2 * (skew_entry(w, r, c) - skew_entry(L, r, c) * T(m.Mi[3 + c]));
    }
}

// Full M: E M^-1 row by row (M^-1 symmetric: row r of E M^-1 is M^-1 times E's row r)
template <typename T>
LRIGID_LANE void kirchhoff_newton_matrix(const FullMass& m, const T* ym, T h2, T* A) {
  T xi[6], Pm[3];
  mass_inv_times(m, ym, xi);
  const T* v = xi;
  const T* w = xi + 3;
  const T* P = ym;
  const T* L = ym + 3;
  munk_kept_momentum(m, v, P, Pm);
#pragma GCC unroll 6
  for (int r = 0; r < 6; ++r) {
    T E[6];
#pragma GCC unroll 3
    for (int c = 0; c < 3; ++c) {
      E[c] = r < 3 ? T(0)
                   : -(skew_times_S(m, v, r - 3, c) + skew_entry(Pm, r - 3, c));
      E[3 + c] = r < 3 ? -skew_entry(P, r, c) : -skew_entry(L, r - 3, c);
    }
    T EMi[6];
    mass_inv_times(m, E, EMi);
#pragma GCC unroll 6
    for (int c = 0; c < 6; ++c) {
      const int rb = r / 3, cb = c / 3, rr = r % 3, cc = c % 3;
      const T D =
          rb == cb ? skew_entry(w, rr, cc) : (rb == 1 && cb == 0 ? skew_entry(v, rr, cc) : T(0));
      A[r * 6 + c] = (r == c ? T(1) : T(0)) + h2 * (D + EMi[c]);
    }
  }
}

// The explicit midpoint predictor Y = Y0 - h G(Y0 - h/2 G(Y0)) (error O(h^3)), the start of the
// iteration
template <typename T, class Mass>
LRIGID_LANE void kirchhoff_predictor(const Mass& m, T h, const T* Y0, T* Y) {
  T g[6], ym[6];
  kirchhoff_gyro_kernel(m, Y0, g);
#pragma GCC unroll 6
  for (int a = 0; a < 6; ++a) ym[a] = Y0[a] - T(0.5) * h * g[a];
  kirchhoff_gyro_kernel(m, ym, g);
#pragma GCC unroll 6
  for (int a = 0; a < 6; ++a) Y[a] = Y0[a] - h * g[a];
}

// One fixed-point iteration of the midpoint equation, next = Y0 - h G((Y0 + Y)/2); returns the
// update's size (next - Y)^T M^-1 (next - Y)
template <typename T, class Mass>
LRIGID_LANE T kirchhoff_fixed_point(const Mass& m, T h, const T* Y0, const T* Y, T* next) {
  T ym[6], g[6], d[6];
#pragma GCC unroll 6
  for (int a = 0; a < 6; ++a) ym[a] = T(0.5) * (Y0[a] + Y[a]);
  kirchhoff_gyro_kernel(m, ym, g);
#pragma GCC unroll 6
  for (int a = 0; a < 6; ++a) {
    next[a] = Y0[a] - h * g[a];
    d[a] = next[a] - Y[a];
  }
  return energy_norm2(m, d);
}

// The Newton step's right-hand side r = -(Y - Y0 + h G((Y0 + Y)/2)), to be solved with the
// factored kirchhoff_newton_matrix at the midpoint (lu_solve)
template <typename T, class Mass>
LRIGID_LANE void kirchhoff_residual(const Mass& m, T h, const T* Y0, const T* Y, T* r) {
  T ym[6], g[6];
#pragma GCC unroll 6
  for (int a = 0; a < 6; ++a) ym[a] = T(0.5) * (Y0[a] + Y[a]);
  kirchhoff_gyro_kernel(m, ym, g);
#pragma GCC unroll 6
  for (int a = 0; a < 6; ++a) r[a] = -(Y[a] - Y0[a] + h * g[a]);
}

// ---- the implicit force step --------------------------------------------------------------------

// The linear block of the implicit force step for a diagonal M, by Sherman-Morrison:
// (D + cp u u^T)^-1 b = Dinv_b - g Dinv_u, D = M + b_B + h c_lin (diagonal), cp = h c_lin p
template <typename T>
LRIGID_LANE T sherman_morrison_linear(const DiagonalMass& m, T basset_mass, const DragOut<T>& d,
                                      T h, const T* b, T* Dinv_b, T* Dinv_u) {
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) {
    const T Dinv = T(1) / (T(m.M[a]) + basset_mass + h * d.c_lin);
    Dinv_b[a] = Dinv * b[a];
    Dinv_u[a] = Dinv * d.u_hat[a];
  }
  const T cp = h * d.c_lin * d.p;
  return cp * dot3(d.u_hat, Dinv_b) / (T(1) + cp * dot3(d.u_hat, Dinv_u));
}

// y = (M + h J + b_B P)^-1 b: the velocity change of the implicit force step (integrators.cpp
// split_deterministic_step) for right-hand side b (6: linear, angular), where J is the drag's
// stiffness d (linear block c_lin (I + p u u^T), angular diag(c_ang): never coupled) and b_B the
// Basset history's current interval as a mass on the linear block (0 without); implicit_impulse
// gives the impulse change M y. Diagonal M: Sherman-Morrison on the linear block, closed form on
// the angular one.
template <typename T>
LRIGID_LANE bool implicit_velocity(const DiagonalMass& m, T basset_mass, const DragOut<T>& d, T h,
                                   const T* b, T* y) {
  T Dinv_b[3], Dinv_u[3];
  const T g = sherman_morrison_linear(m, basset_mass, d, h, b, Dinv_b, Dinv_u);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) {
    y[a] = Dinv_b[a] - g * Dinv_u[a];
    y[3 + a] = b[3 + a] / (T(m.M[3 + a]) + h * d.c_ang[a]);
  }
  return true;
}
// x = M (M + h J + b_B P)^-1 b, the impulse change (written out rather than as M times
// implicit_velocity: GCC 12 then compiled the splitting loop so that a lane's last bit depended
// on the block's width, BatchLanes.ABlockEndsWhereItsBodiesEndSteppedOneByOne)
template <typename T>
LRIGID_LANE bool implicit_impulse(const DiagonalMass& m, T basset_mass, const DragOut<T>& d, T h,
                                  const T* b, T* x) {
  T Dinv_b[3], Dinv_u[3];
  const T g = sherman_morrison_linear(m, basset_mass, d, h, b, Dinv_b, Dinv_u);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) {
    x[a] = T(m.M[a]) * (Dinv_b[a] - g * Dinv_u[a]);
    x[3 + a] = T(m.M[3 + a]) * b[3 + a] / (T(m.M[3 + a]) + h * d.c_ang[a]);
  }
  return true;
}

// Isotropic M: (m + b_B) I + h c_lin (I + p u u^T) is inverted by Sherman-Morrison in closed form
// (one scalar a for all three axes): its inverse applied to b is (b - g u (u . b)) / a
template <typename T>
struct IsotropicSolve {
  T a, g, ub;
};
template <typename T>
LRIGID_LANE IsotropicSolve<T> isotropic_sherman_morrison(const IsotropicMass& m, T basset_mass,
                                                         const DragOut<T>& d, T h, const T* b) {
  const T a = T(m.M[0]) + basset_mass + h * d.c_lin, c = h * d.c_lin * d.p;
  return {a, c / (a + c), dot3(d.u_hat, b)};
}
template <typename T>
LRIGID_LANE bool implicit_velocity(const IsotropicMass& m, T basset_mass, const DragOut<T>& d, T h,
                                   const T* b, T* y) {
  const T J = T(m.M[3]);
  const IsotropicSolve<T> s = isotropic_sherman_morrison(m, basset_mass, d, h, b);
#pragma GCC unroll 3
  for (int i = 0; i < 3; ++i) {
    y[i] = (b[i] - s.g * d.u_hat[i] * s.ub) / s.a;
    y[3 + i] = b[3 + i] / (J + h * d.c_ang[i]);
  }
  return true;
}
// the impulse change M y, written out (as the diagonal M's implicit_impulse)
template <typename T>
LRIGID_LANE bool implicit_impulse(const IsotropicMass& m, T basset_mass, const DragOut<T>& d, T h,
                                  const T* b, T* x) {
  const T mm = T(m.M[0]), J = T(m.M[3]);
  const IsotropicSolve<T> s = isotropic_sherman_morrison(m, basset_mass, d, h, b);
#pragma GCC unroll 3
  for (int i = 0; i < 3; ++i) {
    x[i] = mm * (b[i] - s.g * d.u_hat[i] * s.ub) / s.a;
    x[3 + i] = J * b[3 + i] / (J + h * d.c_ang[i]);
  }
  return true;
}

// Full M: the symmetric positive definite 6 x 6 matrix M + h J + b_B P factored without pivoting
// into A (lu_factor); 0 when a pivot fails (not for a positive definite matrix). Kept for several
// right-hand sides (implicit_solve: the Strang scheme's two ROS2 stages share it).
template <typename T>
LRIGID_LANE int implicit_factor(const FullMass& m, T basset_mass, const DragOut<T>& d, T h, T* A) {
#pragma GCC unroll 36
  for (int e = 0; e < 36; ++e) A[e] = T(m.M[e]);
#pragma GCC unroll 3
  for (int r = 0; r < 3; ++r) {
#pragma GCC unroll 3
    for (int c = 0; c < 3; ++c)
      A[r * 6 + c] += h * d.c_lin * ((r == c ? T(1) : T(0)) + d.p * d.u_hat[r] * d.u_hat[c]);
    A[r * 6 + r] += basset_mass;
    A[(3 + r) * 6 + 3 + r] += h * d.c_ang[r];
  }
  return lu_factor<6>(A);
}
// y = A^-1 b for A from implicit_factor
template <typename T>
LRIGID_LANE void implicit_solve(const T* A, const T* b, T* y) {
#pragma GCC unroll 6
  for (int a = 0; a < 6; ++a) y[a] = b[a];
  lu_solve<6>(A, y);
}
// implicit_velocity for a full M: factor and solve
template <typename T>
LRIGID_LANE bool implicit_velocity(const FullMass& m, T basset_mass, const DragOut<T>& d, T h,
                                   const T* b, T* y) {
  T A[36];
  const int ok = implicit_factor(m, basset_mass, d, h, A);
  implicit_solve(A, b, y);
  return ok != 0;
}

// x = M (M + h J + b_B P)^-1 b: the impulse change of the implicit force step (implicit_velocity)
template <typename T>
LRIGID_LANE bool implicit_impulse(const FullMass& m, T basset_mass, const DragOut<T>& d, T h,
                                  const T* b, T* x) {
  T y[6];
  const bool ok = implicit_velocity(m, basset_mass, d, h, b, y);
  mass_times(m, y, x);
  return ok;
}

// ---- the force step of the Strang scheme --------------------------------------------------------

// The Strang scheme's force step (integrators.cpp strang_force_step, rigid_batch_step.h): Verwer,
// Spee, Blom and Hundsdorfer's (1999) two-stage Rosenbrock-W method ROS2 on the impulse change
// of the forces over h, position and orientation held:
//   (I + g h J M^-1) k1 = F(0),   (I + g h J M^-1) k2 = F(h k1) - 2 k1,
//   dPi = h (3/2 k1 + 1/2 k2),   g = 1 + 1/sqrt(2).
// Second order for any matrix J (a W-method: the drag's stiffness leaves out the lift and the
// drag's cross terms), L-stable where J is the forces' exact stiffness; without drag (J = 0) it
// is Heun's method. With the fluid velocity held, the velocity changes by M^-1 dPi, and the
// stages are taken in the velocity y_i = M^-1 k_i, which needs M once per step and M^-1 never:
//   (M + g h J) y1 = F(0),   (M + g h J) y2 = F(h y1) - 2 M y1,   dxi = h (3/2 y1 + 1/2 y2).
// forces(dxi, first, F) fills the impulse rate F (6: force, torque, body frame) at the velocity
// change dxi (first: the first stage, which also sets the stiffness J); solve(gh, b, y) sets
// y = (M + gh J)^-1 b with the J of the first stage; m_times(y, x) sets x = M y.
constexpr double kRos2Gamma = 1.0 + M_SQRT1_2;
template <typename T, class Forces, class Solve, class MassTimes>
LRIGID_LANE void ros2_velocity(T h, Forces forces, Solve solve, MassTimes m_times, T* dxi) {
  T F[6], y1[6], y2[6], k1[6], x[6];
#pragma GCC unroll 6
  for (int a = 0; a < 6; ++a) x[a] = T(0);
  forces(x, true, F);
  const T gh = T(kRos2Gamma) * h;
  solve(gh, F, y1);
#pragma GCC unroll 6
  for (int a = 0; a < 6; ++a) x[a] = h * y1[a];
  forces(x, false, F);
  m_times(y1, k1);
#pragma GCC unroll 6
  for (int a = 0; a < 6; ++a) F[a] -= T(2) * k1[a];
  solve(gh, F, y2);
#pragma GCC unroll 6
  for (int a = 0; a < 6; ++a) dxi[a] = h * (T(1.5) * y1[a] + T(0.5) * y2[a]);
}

}  // namespace lrigid
