// The euler and rk4 schemes (integrate/integrators.h) on the batched sphere step: internal to
// sphere_batch.cpp, which includes this file after its StepConsts, Lanes and sphere_drag (the
// lanes, the consts and the drag kernel of the splitting and strang loops are these loops' too).
//
// The physics is the scalar step's, term for term, on the same random numbers (integrators.cpp
// impulse_step and rk4, the Euler-Maruyama update of the seen fluctuation from the start of the
// step), with the same kernels: gravity and buoyancy, the sphere drag (effects/drag.h), Magnus,
// the Basset history, the added mass's wrench (effects/added_mass.h, velocity form for rk4), the
// rigid body's gyroscopic terms (effects/wrench.h), the exponential map and dexp^-1
// (util/lane.h), the implicit solve (model/kirchhoff.h), the OU update
// (effects/turbulence.h). The moments that vanish for an isotropic M (w x J w, v x m_b v and
// the added mass's v_r x m_a v_r) are left out: on the scalar step they are a torque of rounding
// noise, which turns a small sphere released without spin (J ~ r^5) by ~1e-9 rad/s. The frames:
// euler's step is the scalar one's world-frame impulse update, which for an isotropic M needs
// no body frame; rk4 runs its stages in the body frame as the
// scalar step does (stages in the world frame would be another fourth-order scheme, not the
// same numbers), from the lanes' world velocity. Neither scheme iterates: no lane is handed to
// the scalar step but an rk4 lane whose stage leaves the fluid (the scalar step then exits it
// where it would have).
#pragma once
#include "effects/added_mass.h"
#include "effects/turbulence.h"
#include "effects/wrench.h"
#include "integrate/batch_explicit.h"
#include "integrate/batch_lanes.h"
#include "util/fast_math.h"
#include "util/lane.h"

namespace lrigid {
namespace {  // NOLINT(build/namespaces): internal to sphere_batch.cpp

// A sphere lane's fluid velocity (world): the mean flow and the seen fluctuation us; its
// material derivative (world, the gu factor applied: 0 without gradients); the weight and
// buoyancy with the Basset history force (world)
template <typename T>
LRIGID_LANE void sphere_fluid(const StepConsts& tc, const Lanes<T>* lanes, int j, const T* us,
                              T* u_f, T* acc, T* Fw) {
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) {
    u_f[a] = T(tc.mf) * lanes->U[a][j] + T(tc.tu) * us[a];
    acc[a] = T(tc.gu) * lanes->acc[a][j];
    Fw[a] = T(tc.F[a]) + lanes->fb[a][j];  // (the history force: 0 without it)
  }
}

// The forces on a sphere in one frame (world or body): sphere_force_sum with the spin w in that
// frame for both kernels; f the force, tq the torque (the drag's and the explicit rest's), both
// in that frame (the sphere's drag and Magnus turn with the frame)
template <typename T>
LRIGID_LANE void sphere_forces(const StepConsts& tc, const T* F, const T* vr, const T* w, T* f,
                               T* tq) {
  T fe[6];
  const DragOut<T> d = sphere_force_sum(tc, F, vr, w, w, fe);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) {
    f[a] = fe[a] + d.f[a];
    tq[a] = fe[3 + a] + d.tq[a];
  }
}

// euler (integrators.cpp impulse_step): one explicit step of the world-frame impulse, the forces
// and rotation from the start of the step, the Basset history's current interval implicit; then
// the seen fluctuation by Euler-Maruyama. For an isotropic M the world impulse is
// (m V - m_a u_f; R J w): V1 = V0 + (h F + m_a h a_f) / m, the spin carried to q exp(h w).
template <typename T>
LRIGID_MULTIVERSION void euler_lanes(const StepConsts& tc, Lanes<T>* lanes, uint64_t step,
                                     int* outcome, int* landed) {
  const int nw = lanes->width;
  const T h = T(tc.h);
  alignas(64) T z[3][kBatch];
  [[maybe_unused]] alignas(64) T unused[3][kBatch];
  lane_normals<T, true>(tc, *lanes, step, z, unused);
  NewState<T> next;
  LRIGID_IVDEP
  for (int j = 0; j < nw; ++j) {
    T us[3] = {lanes->us[0][j], lanes->us[1][j], lanes->us[2][j]};
    const T q[4] = {lanes->q[0][j], lanes->q[1][j], lanes->q[2][j], lanes->q[3][j]};
    const T V0[3] = {lanes->V[0][j], lanes->V[1][j], lanes->V[2][j]};
    const T w[3] = {lanes->w[0][j], lanes->w[1][j], lanes->w[2][j]};
    T u_f[3], acc[3], Fw[3], vr[3], wW[3], f[3], tq[3];
    sphere_fluid(tc, lanes, j, us, u_f, acc, Fw);
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) vr[a] = V0[a] - u_f[a];
    rotate_by(q, w, wW);
    sphere_forces(tc, Fw, vr, wW, f, tq);
    // the impulse change h (F; T) (world), with the Basset history's current interval
    // 2 C sqrt(h) (du_f - dv) / h on the left-hand side (b h a_f on the right)
    T b[6], dPi[6];
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      b[a] = h * f[a] + T(tc.basset_mass) * h * acc[a];
      b[3 + a] = h * tq[a];
    }
    const DragOut<T> none{};
    implicit_impulse(tc.mass, T(tc.basset_mass), none, h, b, dPi);
    // V from the new impulse m V0 - m_a u_f + dP and the fluid velocity at the end of the step
    // u_f + h a_f; the world angular momentum R J w + dL in the new body frame q exp(h w)
    const T theta[3] = {h * w[0], h * w[1], h * w[2]};
    T q1[4], R1[9], Lw[3], w1[3];
    exp_rotate<LaneMath>(q, theta, q1);
    rotation(q1, R1);
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) Lw[a] = T(tc.J) * wW[a] + dPi[3 + a];
    mul_t(R1, Lw, w1);
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      const T P = T(tc.m) * V0[a] - T(tc.ma) * u_f[a] + dPi[a];
      next.vel[a][j] = (P + T(tc.ma) * (u_f[a] + h * acc[a])) / T(tc.m);
      next.w[a][j] = w1[a] / T(tc.J);
      next.x[a][j] = lanes->x[a][j] + h * V0[a];
    }
    ou_euler_lane(tc, lanes, j, V0, z, us);
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) next.us[a][j] = us[a];
#pragma GCC unroll 4
    for (int a = 0; a < 4; ++a) next.q[a][j] = q1[a];
    next.scalar[j] = 0;
  }
  end_step<T, false>(tc, z, next.vel, &next, lanes, outcome, landed);
}

// rk4's stage I (0 to 3) on every lane, in the body frame as integrators.cpp rk4: the rates at
// the stage's state on the lanes' samples there (velocity form: the added mass's Kirchhoff terms
// and drag-along, the rigid gyroscopic terms), added to the sums, and the next stage's state
// (c = 1/2, 1/2, 1); stage 0 also takes the start's body-frame velocity and updates the seen
// fluctuation (into next->us) from the start's sample
template <typename T, int I>
LRIGID_LANE void rk4_stage(const StepConsts& tc, const Lanes<T>* lanes, const T (*z)[kBatch],
                           Rk4Block<T>* k, NewState<T>* next) {
  const int nw = lanes->width;
  const T h = T(tc.h);
  LRIGID_IVDEP
  for (int j = 0; j < nw; ++j) {
    const T us0[3] = {lanes->us[0][j], lanes->us[1][j], lanes->us[2][j]};
    const T q0[4] = {lanes->q[0][j], lanes->q[1][j], lanes->q[2][j], lanes->q[3][j]};
    T q[4], theta[3], v[3], w[3], R[9];
    if constexpr (I == 0) {
      const T V0[3] = {lanes->V[0][j], lanes->V[1][j], lanes->V[2][j]};
      rotation(q0, R);
      mul_t(R, V0, v);
#pragma GCC unroll 3
      for (int a = 0; a < 3; ++a) {
        theta[a] = T(0);
        w[a] = lanes->w[a][j];
        k->v0[a][j] = v[a];
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
      rotation(q, R);
    }
    T u_f[3], acc[3], Fw[3], ufb[3], ab[3], Fb[3], vr[3], f[3], tq[3];
    sphere_fluid(tc, lanes, j, us0, u_f, acc, Fw);
    mul_t(R, u_f, ufb);
    mul_t(R, acc, ab);
    mul_t(R, Fw, Fb);
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) vr[a] = v[a] - ufb[a];
    sphere_forces(tc, Fb, vr, w, f, tq);
    // the added mass: K (a~; 0) - (w x P_f; w x L_f + v_r x P_f), a~ = R^T Du/Dt - w x u_f
    T wu[3], fa[3], am[6];
    cross3(w, ufb, wu);
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) fa[a] = ab[a] - wu[a];
    added_mass_kernel<false>(tc.fluid, vr, w, fa, am);
    // the rigid body's own gyroscopic terms (about the centre of mass)
    T Pb[3], Lb[3], g[6], kx[3], kth[3], kxi[6];
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      Pb[a] = T(tc.body.M[a]) * v[a];
      Lb[a] = T(tc.body.M[3 + a]) * w[a];
    }
    kirchhoff_gyro_kernel(v, w, Pb, Lb, g);
    // the moments of both (w x L, v x P_b, v_r x P_f) vanish for an isotropic M and are left
    // out: computed, they are a torque of rounding noise that a small sphere's tiny J turns into
    // a spurious spin (5e-10 rad/s after 1 s for a 0.25 mm bead on the scalar step)
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      kxi[a] = T(tc.diag.Mi[a]) * (f[a] + am[a] - g[a]);
      kxi[3 + a] = T(tc.diag.Mi[3 + a]) * tq[a];
    }
    mul(R, v, kx);
    dexpinv(theta, w, kth);
    const bool in = !tc.sample | (lanes->inside[j] != T(0));
    const T x0[3] = {lanes->x[0][j], lanes->x[1][j], lanes->x[2][j]};
    const T v0[3] = {k->v0[0][j], k->v0[1][j], k->v0[2][j]};
    const T w0[3] = {lanes->w[0][j], lanes->w[1][j], lanes->w[2][j]};
    rk4_sum_lane<I>(k, j, in, h, x0, v0, w0, kx, kth, kxi);
    if constexpr (I == 0) {
      // the path velocity of the seen fluctuation's drift: the start's world velocity
      const T V0[3] = {lanes->V[0][j], lanes->V[1][j], lanes->V[2][j]};
      T us[3] = {us0[0], us0[1], us0[2]};
      ou_euler_lane(tc, lanes, j, V0, z, us);
#pragma GCC unroll 3
      for (int a = 0; a < 3; ++a) next->us[a][j] = us[a];
    }
  }
}

// rk4 (integrators.cpp rk4): classic Runge-Kutta in the velocity form, RKMK4 on SO(3) (the
// rotation q exp(theta), theta through dexp^-1), the field sampled at each stage (time
// t + c h); the Basset history's current interval as an implicit correction after the step
// (for an isotropic M: V1 + (M + b P)^-1 b (V0 - V1), in the world frame); the seen fluctuation
// by Euler-Maruyama from the start of the step.
template <typename T>
LRIGID_MULTIVERSION void rk4_lanes(const StepConsts& tc, const Rk4Frames& frames,
                                   Lanes<T>* lanes, uint64_t step, int* outcome, int* landed) {
  const int nw = lanes->width;
  const T h = T(tc.h);
  alignas(64) T z[3][kBatch];
  [[maybe_unused]] alignas(64) T unused[3][kBatch];
  lane_normals<T, true>(tc, *lanes, step, z, unused);
  Rk4Block<T> k;
  NewState<T> next;
  rk4_stages(tc, frames, lanes, &k, [&](auto stage) LRIGID_LANE_LAMBDA {
    rk4_stage<T, decltype(stage)::value>(tc, lanes, z, &k, &next);
  });
  const T h6 = h / T(6);
  LRIGID_IVDEP
  for (int j = 0; j < nw; ++j) {
    const T q0[4] = {lanes->q[0][j], lanes->q[1][j], lanes->q[2][j], lanes->q[3][j]};
    T theta[3], q1[4], R0[9], R1[9], dv[3], v1[3], dR[9], a0[3], a1[3], V1[3];
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      theta[a] = h6 * k.Sth[a][j];
      dv[a] = h6 * k.Sxi[a][j];
      v1[a] = k.v0[a][j] + dv[a];
    }
    exp_rotate<LaneMath>(q0, theta, q1);
    rotation(q0, R0);
    rotation(q1, R1);
    // V1 = R1 v1 as V0 + R0 dv + (R1 - R0) v1 (R0 v0 = V0): the start's world velocity is not
    // taken through R0 and back, which in single precision scaled it by |q|^4 every step
#pragma GCC unroll 9
    for (int e = 0; e < 9; ++e) dR[e] = R1[e] - R0[e];
    mul(R0, dv, a0);
    mul(dR, v1, a1);
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) V1[a] = lanes->V[a][j] + a0[a] + a1[a];
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      // the Basset history's current interval (0 without it)
      V1[a] += T(tc.basset_inv) * (T(tc.basset_mass) * (lanes->V[a][j] - V1[a]));
      next.x[a][j] = lanes->x[a][j] + h6 * k.Sx[a][j];
      next.vel[a][j] = V1[a];
      next.w[a][j] = lanes->w[a][j] + h6 * k.Sxi[3 + a][j];
    }
#pragma GCC unroll 4
    for (int a = 0; a < 4; ++a) next.q[a][j] = q1[a];
    next.scalar[j] = k.ok[j] != T(0) ? 0 : 1;
  }
  end_step<T, false>(tc, z, next.vel, &next, lanes, outcome, landed);
}

}  // namespace
}  // namespace lrigid
