// The euler and rk4 schemes (integrate/integrators.h) on the batched step: internal to
// rigid_batch_step.h, which includes this file after its StepConsts, Lanes and body_forces (the
// lanes, the consts and the force kernels of the splitting and strang loops are these loops' too).
//
// The physics is the scalar step's, term for term, on the same random numbers (integrators.cpp
// impulse_step and rk4, the Euler-Maruyama update of the seen fluctuation from the start of the
// step), with the same kernels: gravity and buoyancy, the plate's drag, torque and lift or the
// ellipsoid drag (body_forces), Magnus, the Basset history, the added mass's wrench
// (effects/added_mass.h, impulse form for euler, velocity form for rk4), the Kirchhoff gyroscopic
// terms (effects/wrench.h), the exponential map and dexp^-1 (util/lane.h), the implicit solve
// (model/kirchhoff.h), the OU update (effects/turbulence.h). Like the splitting loops, they
// are compiled for each kind of M (model/kirchhoff.h IsotropicMass, DiagonalMass, FullMass): the
// impulse and velocity conversions (impulse_of_velocity, velocity_of_impulse), M^-1
// (mass_inv_times) and the products with M_body and K (mass_times) are the kernels' for each.
// euler takes the forces in the lanes' frame (FrameOf: the world frame for an isotropic M);
// rk4 runs its stages in the body frame for every M, as the scalar step does. For an isotropic M
// the moments that vanish (w x L, v x P_b, the added mass's v_r x P_f) are left out: on the
// scalar step they are a torque of rounding noise, which turns a small sphere released without
// spin (J ~ r^5) by ~1e-9 rad/s.
// Neither scheme iterates: no lane is handed to the scalar step but an rk4 lane whose stage leaves
// the fluid (the scalar step then exits it where it would have).
#pragma once
#include "effects/added_mass.h"
#include "effects/turbulence.h"
#include "fluid/field.h"
#include "integrate/batch_explicit.h"
#include "integrate/batch_lanes.h"
#include "util/fast_math.h"
#include "util/lane.h"

namespace lrigid {
namespace {  // NOLINT(build/namespaces): internal to rigid_batch_step.h

// The effects' wrench on a lane's body, f = (force; torque), in the frame fr (the force) and the
// body frame (the torque), at velocity v (in fr) and spin w (body frame), the fluid velocity ufb
// (in fr), the weight and buoyancy (plus the Basset history force) Fw (world) and the fluid's
// material derivative acc (world, the gu factor applied). ImpulseForm: euler's (the added mass's
// -v_r x P_f alone), else rk4's velocity form (the added mass's Kirchhoff terms and the
// drag-along K a~; rk4 passes the body frame). As effects/evaluate.cpp context_from_sample and
// the plan's terms. For an isotropic M the added mass's moment v_r x P_f vanishes and is left
// out: computed, it is a torque of rounding noise, which a small sphere's tiny J (~r^5) turns
// into a spurious spin.
template <typename T, bool Plate, bool ImpulseForm, class Mass, class Frame>
LRIGID_LANE void lane_wrench(const StepConsts<Mass>& tc, const Frame& fr, const T* Fw,
                             const T* ufb, const T* acc, const T* v, const T* w, T* f) {
  T vr[3], Fb[3], fe[6], fa[3] = {0, 0, 0}, am[6];
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) vr[a] = v[a] - ufb[a];
  fr.of_world(Fw, Fb);
  const DragOut<T> d = lane_forces<T, Plate>(tc, fr, Fb, vr, w, fe);
  if constexpr (!ImpulseForm) {
    // a~ = R^T Du/Dt - w x u_f (effects/added_mass.h)
    T ab[3], wu[3];
    fr.of_world(acc, ab);
    cross3(w, ufb, wu);
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) fa[a] = ab[a] - wu[a];
  }
  added_mass_kernel<ImpulseForm>(tc.fluid, vr, w, fa, am);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) {
    f[a] = fe[a] + d.f[a] + am[a];
    f[3 + a] = fe[3 + a] + d.tq[a] + (kIsotropic<Mass> ? T(0) : am[3 + a]);
  }
}

// A lane's fluid velocity (world): the mean flow and the seen fluctuation us; its material
// derivative (world, 0 without gradients); the weight and buoyancy with the Basset history force
// (zero without the history)
template <typename T, class C, class L>
LRIGID_LANE void lane_fluid(const C& tc, const L* lanes, int j, const T* us, T* u_f, T* acc,
                            T* Fw) {
  const T tu = T(tc.tu);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) {
    u_f[a] = T(tc.mf) * lanes->U[a][j] + tu * us[a];
    acc[a] = T(tc.gu) * lanes->acc[a][j];
    Fw[a] = T(tc.F[a]) + lanes->fb[a][j];
  }
}

// euler (integrators.cpp impulse_step): one explicit step of the world-frame impulse, the forces,
// Munk moment and rotation from the start of the step, the Basset history's current interval
// implicit; then the seen fluctuation by Euler-Maruyama.
template <typename T, bool Plate, class Mass>
LRIGID_MULTIVERSION void euler_lanes(const StepConsts<Mass>& tc, Lanes<T, Mass>* lanes, uint64_t step,
                                     int* outcome, int* landed) {
  const int nw = lanes->width;
  const T h = T(tc.h);
  alignas(64) T z[3][kBatch], Vn[3][kBatch];
  [[maybe_unused]] alignas(64) T unused[3][kBatch];
  const T bf = T(tc.basset ? 1 : 0);
  lane_normals<T, true>(tc, *lanes, step, z, unused);
  NewState<T> next;
  LRIGID_IVDEP
  for (int j = 0; j < nw; ++j) {
    T us[3] = {lanes->us[0][j], lanes->us[1][j], lanes->us[2][j]};
    const T q[4] = {lanes->q[0][j], lanes->q[1][j], lanes->q[2][j], lanes->q[3][j]};
    const T v[3] = {lanes->v[0][j], lanes->v[1][j], lanes->v[2][j]};
    const T w[3] = {lanes->w[0][j], lanes->w[1][j], lanes->w[2][j]};
    T V0[3], u_f[3], acc[3], Fw[3], ufb[3], rate[6];
    FrameOf<T, Mass> fr;
    fr.set(q);
    fr.to_world(v, V0);
    lane_fluid(tc, lanes, j, us, u_f, acc, Fw);
    fr.of_world(u_f, ufb);
    lane_wrench<T, Plate, true>(tc, fr, Fw, ufb, acc, v, w, rate);
    // the impulse Pi = M xi - K (u_f; 0) and its change h rate
    const T xi[6] = {v[0], v[1], v[2], w[0], w[1], w[2]};
    T Pi[6], dPi[6];
    impulse_of_velocity(tc.mass, tc.K, xi, ufb, Pi);
#pragma GCC unroll 6
    for (int a = 0; a < 6; ++a) dPi[a] = h * rate[a];
    {
      // the Basset history's current interval, 2 C sqrt(h) (du_f - dv) / h, implicitly (bf = 0
      // without it: dPi kept, exactly)
      const T b = T(tc.basset_mass);
      T ha[3], hab[3], x[6];
#pragma GCC unroll 3
      for (int a = 0; a < 3; ++a) ha[a] = h * acc[a];
      fr.of_world(ha, hab);
#pragma GCC unroll 3
      for (int a = 0; a < 3; ++a) dPi[a] += b * hab[a];
      const DragOut<T> none{};
      implicit_impulse(tc.mass, b, none, h, dPi, x);
#pragma GCC unroll 6
      for (int a = 0; a < 6; ++a) dPi[a] = x[a] * bf + dPi[a] * (T(1) - bf);
    }
    // the world-frame impulse is carried to the new orientation q exp(h w)
    T P[3], L[3], Pw[3], Lw[3], ufn[3];
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      P[a] = Pi[a] + dPi[a];
      L[a] = Pi[3 + a] + dPi[3 + a];
      ufn[a] = u_f[a] + h * acc[a];
    }
    fr.to_world(P, Pw);
    fr.body_to_world(L, Lw);
    const T theta[3] = {h * w[0], h * w[1], h * w[2]};
    // and the velocity there, xi = M^-1 (Pi + K (u_f; 0))
    T q1[4], Pn[6], ufb1[3], xi1[6], V1[3];
    exp_rotate<LaneMath>(q, theta, q1);
    FrameOf<T, Mass> fr1;
    fr1.set(q1);
    fr1.of_world(Pw, Pn);
    fr1.body_of_world(Lw, Pn + 3);
    fr1.of_world(ufn, ufb1);
    velocity_of_impulse(tc.mass, tc.K, Pn, ufb1, xi1);
    const T* v1 = xi1;
    const T* w1 = xi1 + 3;
    fr1.to_world(v1, V1);
    ou_euler_lane(tc, lanes, j, V0, z, us);
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      next.x[a][j] = lanes->x[a][j] + h * V0[a];
      next.vel[a][j] = v1[a];
      next.w[a][j] = w1[a];
      next.us[a][j] = us[a];
      Vn[a][j] = V1[a];
    }
#pragma GCC unroll 4
    for (int a = 0; a < 4; ++a) next.q[a][j] = q1[a];
    next.scalar[j] = 0;
  }
  end_step<T, false>(tc, z, Vn, &next, lanes, outcome, landed);
}

// rk4's stage I (0 to 3) on every lane, in the body frame as integrators.cpp rk4 (stages in the
// world frame would be another fourth-order scheme, not the same numbers): the rates at the
// stage's state on the lanes' samples there, added to the sums, and the next stage's state
// (c = 1/2, 1/2, 1); stage 0 also updates the seen fluctuation (into next->us) from the start's
// sample, and for lanes that keep the world velocity (an isotropic M) takes the start's
// body-frame velocity (into k->v0). First: I is 0.
template <typename T, bool Plate, bool First, class Mass>
LRIGID_LANE void rk4_stage(const StepConsts<Mass>& tc, const Lanes<T, Mass>* lanes,
                           const T (*z)[kBatch], Rk4Block<T>* k, NewState<T>* next, int I) {
  constexpr bool world = Lanes<T, Mass>::kWorld;
  const int nw = lanes->width;
  const T h = T(tc.h);
  LRIGID_IVDEP
  for (int j = 0; j < nw; ++j) {
    const T us0[3] = {lanes->us[0][j], lanes->us[1][j], lanes->us[2][j]};
    const T q0[4] = {lanes->q[0][j], lanes->q[1][j], lanes->q[2][j], lanes->q[3][j]};
    const T vl[3] = {lanes->v[0][j], lanes->v[1][j], lanes->v[2][j]};
    T q[4], theta[3], v[3], w[3];
    BodyFrame<T> fr;
    if constexpr (First) {
      fr.set(q0);
      if constexpr (world) {
        fr.of_world(vl, v);
      } else {
#pragma GCC unroll 3
        for (int a = 0; a < 3; ++a) v[a] = vl[a];
      }
#pragma GCC unroll 3
      for (int a = 0; a < 3; ++a) {
        theta[a] = T(0);
        w[a] = lanes->w[a][j];
        if constexpr (world) k->v0[a][j] = v[a];
      }
#pragma GCC unroll 4
      for (int a = 0; a < 4; ++a) q[a] = q0[a];
    } else {
#pragma GCC unroll 3
      for (int a = 0; a < 3; ++a) {
        theta[a] = k->th[a][j];
        v[a] = k->vs[a][j];
        w[a] = k->ws[a][j];
      }
      exp_rotate<LaneMath>(q0, theta, q);
      fr.set(q);
    }
    T u_f[3], acc[3], Fw[3], ufb[3], f[6];
    lane_fluid(tc, lanes, j, us0, u_f, acc, Fw);
    fr.of_world(u_f, ufb);
    lane_wrench<T, Plate, false>(tc, fr, Fw, ufb, acc, v, w, f);
    // the rigid body's own gyroscopic terms (about the centre of mass), xi' = M^-1 (f - g); for
    // an isotropic M their moment w x L + v x P vanishes and is left out (lane_wrench)
    const T xi[6] = {v[0], v[1], v[2], w[0], w[1], w[2]};
    T PL[6], g[6], kx[3], kth[3], kxi[6];
    mass_times(tc.body, xi, PL);
    kirchhoff_gyro_kernel(v, w, PL, PL + 3, g);
#pragma GCC unroll 6
    for (int a = 0; a < 6; ++a) f[a] -= kIsotropic<Mass> && a >= 3 ? T(0) : g[a];
    mass_inv_times(tc.mass, f, kxi);
    fr.to_world(v, kx);
    dexpinv(theta, w, kth);
    const bool in = !tc.sample | (lanes->inside[j] != T(0));
    const T x0[3] = {lanes->x[0][j], lanes->x[1][j], lanes->x[2][j]};
    T v0[3];
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) v0[a] = world ? k->v0[a][j] : vl[a];
    const T w0[3] = {lanes->w[0][j], lanes->w[1][j], lanes->w[2][j]};
    rk4_sum_lane(First ? 0 : I, k, j, in, h, x0, v0, w0, kx, kth, kxi);
    if constexpr (First) {
      // the path velocity of the seen fluctuation's drift: the start's world velocity
      T us[3] = {us0[0], us0[1], us0[2]};
      ou_euler_lane(tc, lanes, j, world ? vl : kx, z, us);
#pragma GCC unroll 3
      for (int a = 0; a < 3; ++a) next->us[a][j] = us[a];
    }
  }
}

// rk4's stages 1 to 3 (I) on every lane: one function for the three, compiled for each
// instruction set as the schemes' loop functions are (inlined three times, they were most of
// rk4's machine code and of its compile time)
template <typename T, bool Plate, class Mass>
LRIGID_MULTIVERSION void rk4_stage_lanes(const StepConsts<Mass>& tc, const Lanes<T, Mass>* lanes,
                                         const T (*z)[kBatch], Rk4Block<T>* k, NewState<T>* next,
                                         int I) {
  rk4_stage<T, Plate, false>(tc, lanes, z, k, next, I);
}

// rk4 (integrators.cpp rk4): classic Runge-Kutta in the velocity form, RKMK4 on SO(3) (the
// rotation q exp(theta), theta through dexp^-1), the field sampled at each stage (time
// t + c h); the Basset history's current interval as an implicit correction after the step; the
// seen fluctuation by Euler-Maruyama from the start of the step.
template <typename T, bool Plate, class Mass>
LRIGID_MULTIVERSION void rk4_lanes(const StepConsts<Mass>& tc, const Rk4Frames& frames,
                                   Lanes<T, Mass>* lanes, uint64_t step, int* outcome,
                                   int* landed) {
  constexpr bool world = Lanes<T, Mass>::kWorld;
  const int nw = lanes->width;
  const T h = T(tc.h);
  alignas(64) T z[3][kBatch], Vn[3][kBatch];
  [[maybe_unused]] alignas(64) T unused[3][kBatch];
  lane_normals<T, true>(tc, *lanes, step, z, unused);
  Rk4Block<T> k;
  NewState<T> next;
  rk4_stages(tc, frames, lanes, &k, [&](auto stage) LRIGID_LANE_LAMBDA {
    constexpr int I = decltype(stage)::value;
    if constexpr (I == 0)
      rk4_stage<T, Plate, true>(tc, lanes, z, &k, &next, 0);
    else
      rk4_stage_lanes<T, Plate>(tc, lanes, z, &k, &next, I);
  });
  const T h6 = h / T(6);
  LRIGID_IVDEP
  for (int j = 0; j < nw; ++j) {
    const T q0[4] = {lanes->q[0][j], lanes->q[1][j], lanes->q[2][j], lanes->q[3][j]};
    T theta[3], dxi[6], q1[4], R1[9], v1[3], w1[3], V1[3];
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) theta[a] = h6 * k.Sth[a][j];
#pragma GCC unroll 6
    for (int a = 0; a < 6; ++a) dxi[a] = h6 * k.Sxi[a][j];
    exp_rotate<LaneMath>(q0, theta, q1);
    rotation(q1, R1);
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      v1[a] = (world ? k.v0[a][j] : lanes->v[a][j]) + dxi[a];
      w1[a] = lanes->w[a][j] + dxi[3 + a];
    }
    if constexpr (world) {
      // the world velocity V1 = R1 v1 as V0 + R0 dv + (R1 - R0) v1 (R0 v0 = V0): the start's is
      // not taken through R0 and back, which in single precision scaled it by |q|^4 every step;
      // then the Basset history's current interval, implicitly (zero without it), in the world
      // frame: V1 + (M + b P)^-1 b (V0 - V1)
      T R0[9], dR[9], a0[3], a1[3], d[3], corr[6];
      rotation(q0, R0);
#pragma GCC unroll 9
      for (int e = 0; e < 9; ++e) dR[e] = R1[e] - R0[e];
      mul(R0, dxi, a0);
      mul(dR, v1, a1);
#pragma GCC unroll 3
      for (int a = 0; a < 3; ++a) {
        V1[a] = lanes->v[a][j] + a0[a] + a1[a];
        d[a] = T(tc.basset_mass) * (lanes->v[a][j] - V1[a]);
      }
      fluid_impulse(tc.basset_inv, d, corr);
#pragma GCC unroll 3
      for (int a = 0; a < 3; ++a) {
        V1[a] += corr[a];
        v1[a] = V1[a];  // the lanes' velocity
      }
    } else {
      // the Basset history's current interval, implicitly (zero without it): (M + b P) xi = M xi* + b P xi_0,
      // xi_0 the start's velocity in the new body frame; the correction (M + b P)^-1 (b (v0 - v);
      // 0) (a full M: the spin too)
      T R0[9], va[3], vw[3], v0[3], d[3], corr[6];
      rotation(q0, R0);
#pragma GCC unroll 3
      for (int a = 0; a < 3; ++a) va[a] = v1[a] - dxi[a];
      mul(R0, va, vw);
      mul_t(R1, vw, v0);
#pragma GCC unroll 3
      for (int a = 0; a < 3; ++a) d[a] = T(tc.basset_mass) * (v0[a] - v1[a]);
      fluid_impulse(tc.basset_inv, d, corr);
#pragma GCC unroll 3
      for (int a = 0; a < 3; ++a) {
        v1[a] += corr[a];
        if constexpr (!kDiagonal<Mass>) w1[a] += corr[3 + a];
      }
      mul(R1, v1, V1);
    }
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      next.x[a][j] = lanes->x[a][j] + h6 * k.Sx[a][j];
      next.vel[a][j] = v1[a];
      next.w[a][j] = w1[a];
      Vn[a][j] = V1[a];
    }
#pragma GCC unroll 4
    for (int a = 0; a < 4; ++a) next.q[a][j] = q1[a];
    next.scalar[j] = k.ok[j] != T(0) ? 0 : 1;
  }
  end_step<T, false>(tc, z, Vn, &next, lanes, outcome, landed);
}

}  // namespace
}  // namespace lrigid
