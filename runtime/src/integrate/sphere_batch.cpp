#include "integrate/sphere_batch.h"

#include <algorithm>
#include <cmath>

#include "effects/drag.h"
#include "integrate/batch_lanes.h"
#include "integrate/dynamics.h"
#include "model/kirchhoff.h"

namespace lrigid {

bool sphere_batch_eligible(const Model& model, const BodyType& type, std::string* why) {
  auto no = [why](const std::string& reason) {
    if (why) *why = reason;
    return false;
  };
  if (const std::string all = batch_exclusion(model, type, true); !all.empty()) return no(all);
  if (type.shape.type != ShapeType::Sphere) return no("not a sphere");
  if (!uniform_sphere_mass(type)) return no("the centre of mass is off the centroid");
  return true;
}

namespace {

// What the step needs of the sphere type, in the world frame.
struct StepConsts : FieldConsts {
  bool drag = false;            // the drag effect
  double drag_factor = 0;       // the same as a factor 1 or 0
  bool strang = false;          // the Strang scheme (not with the Basset history: integrators.h)
  double m = 0, ma = 0, J = 0;  // M's linear and angular diagonal; K's linear diagonal (0 without)
  IsotropicMass mass;           // M = diag(m, m, m, J, J, J) (model/kirchhoff.h)
  // sphere drag (effects/drag.h drag_kernel, r_cob = 0): the law and the sphere's area
  DragParams law;
  double a_perp = 0, d_perp = 0;
  // euler and rk4 (sphere_batch_explicit.h): the scheme, M (with M^-1), M_body's and K's
  // diagonals, and the Basset history's (M + b P)^-1 on the linear block
  Integrator scheme = Integrator::Splitting;
  DiagonalMass diag, body, fluid;
  double basset_inv = 0;
};

StepConsts make_consts(const Model& model, const BodyType& type) {
  StepConsts tc;
  set_field_consts(model, type, &tc);
  const EffectSet& e = type.effects;
  tc.drag = e.has(Effect::Drag);
  tc.drag_factor = tc.drag ? 1.0 : 0.0;
  tc.strang = model.integrator == Integrator::Strang && !tc.basset;
  tc.m = type.M(0, 0);
  tc.ma = e.has(Effect::AddedMass) ? type.K_fluid(0, 0) : 0.0;
  tc.J = type.M(3, 3);
  tc.mass = IsotropicMass{type.M(0, 0), type.M(3, 3)};
  tc.law = type.plan.params->drag;  // the scalar step's (effects/plan.h)
  const double r = type.ell.x();
  tc.a_perp = M_PI * r * r;
  tc.d_perp = 2.0 * std::sqrt(tc.a_perp / M_PI);
  tc.scheme = model.integrator;
  tc.diag = diagonal_mass(type);
  for (int a = 0; a < 6; ++a) {
    tc.body.M[a] = type.M_body(a, a);
    tc.fluid.M[a] = e.has(Effect::AddedMass) ? type.K_fluid(a, a) : 0.0;
  }
  tc.basset_inv = tc.basset ? type.basset.implicit_inv(0, 0) : 0.0;
  return tc;
}

// The state of a block of spheres and the fluid sample at their positions, structure of arrays.
// The velocity V is the world-frame one (q v).
template <typename T>
struct Lanes : Samples<T> {
  alignas(64) T V[3][kBatch];
  alignas(64) T w[3][kBatch];
  alignas(64) T q[4][kBatch];  // (w, x, y, z)
  alignas(64) T us[3][kBatch];

  void load(int j, const BodyState& b) {
    const Vec3 Vw = b.q * b.v;
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      this->x[a][j] = T(b.x[a]);
      V[a][j] = T(Vw[a]);
      w[a][j] = T(b.w[a]);
      us[a][j] = T(b.u_seen[a]);
    }
    q[0][j] = T(b.q.w()), q[1][j] = T(b.q.x()), q[2][j] = T(b.q.y()), q[3][j] = T(b.q.z());
  }
  void store(int j, BodyState* b) const {
    b->x = Vec3(double(this->x[0][j]), double(this->x[1][j]), double(this->x[2][j]));
    b->q = Quat(double(q[0][j]), double(q[1][j]), double(q[2][j]), double(q[3][j]));
    const Vec3 Vw = Vec3(double(V[0][j]), double(V[1][j]), double(V[2][j]));
    b->v = b->q.toRotationMatrix().transpose() * Vw;
    b->w = Vec3(double(w[0][j]), double(w[1][j]), double(w[2][j]));
    b->u_seen = Vec3(double(us[0][j]), double(us[1][j]), double(us[2][j]));
  }
  void rest(int j) {
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) V[a][j] = w[a][j] = T(0);
  }
  T (*velocity())[kBatch] { return V; }  // the velocity a lane keeps (end_step)
};

// Sphere drag (effects/drag.h drag_kernel, centre of buoyancy at the centre of mass): force
// and torque on relative velocity u and spin w, and the stiffness the implicit step needs; the
// projected area is the same in every direction. Times the drag effect's factor (0 without it).
template <typename T>
LRIGID_LANE DragOut<T> sphere_drag(const StepConsts& tc, const T* u, const T* w) {
  const T a_perp = T(tc.a_perp), d_perp = T(tc.d_perp);
  DragOut<T> d = drag_kernel(tc.law, u, w, [&](const T*, T* a, T* diameter) {
    *a = a_perp;
    *diameter = d_perp;
  });
  const T dr = T(tc.drag_factor);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) {
    d.f[a] *= dr;
    d.tq[a] *= dr;
    d.c_ang[a] *= dr;
  }
  d.c_lin *= dr;
  return d;
}

// The forces stage's sum on a sphere lane, written once for every scheme (the batched
// counterpart of the scalar step's EffectPlan): F the given force (weight, buoyancy, the Basset
// history, the fluid's acceleration on the added mass), relative velocity vr, and the spin in
// the frame of each kernel: w in the frame the caller keeps the spin in (the body frame in the
// splitting, strang and rk4 steps, the world frame in euler), wm in vr's frame (Magnus). Returns
// the drag with its stiffness, which the splitting and strang steps take implicitly; fe =
// (force; torque) of the explicit rest: the force F + Magnus in vr's frame, the torque in w's
// frame (zero: Magnus has no torque about a sphere's centre; every caller adds it to its step,
// for an effect that has one, docs/adding-an-effect.md). An effect off contributes its factor 0.
template <typename T>
LRIGID_LANE DragOut<T> sphere_force_sum(const StepConsts& tc, const T* F, const T* vr,
                                        const T* w, const T* wm, T* fe) {
  const DragOut<T> d = sphere_drag(tc, vr, w);
  T fm[3];
  magnus_kernel(T(tc.magnus), wm, vr, fm);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) {
    fe[a] = F[a] + fm[a];
    fe[3 + a] = T(0);
  }
  return d;
}

// The Strang scheme's force step over hs on a sphere lane's world velocity V and body-frame spin
// w (in place), at orientation q (Magnus: the world spin) and the fluid velocity u_f (world) with
// its material derivative acc (world, the gu factor applied here): ROS2 (model/kirchhoff.h
// ros2_impulse), as integrators.cpp strang_force_step (for an isotropic M the world and body
// frames give the same step). Not with the Basset history (tc.strang).
template <typename T>
LRIGID_LANE void strang_force_lane(const StepConsts& tc, const T* q, const T* u_f, const T* acc,
                                   T hs, T* V, T* w) {
  T Fw[3], P[6];
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) {
    // the fluid's acceleration drags the added mass along
    Fw[a] = T(tc.F[a]) + T(tc.ma) * T(tc.gu) * acc[a];
    P[a] = T(tc.m) * V[a] - T(tc.ma) * u_f[a];
    P[3 + a] = T(tc.J) * w[a];
  }
  DragOut<T> J{};
  auto forces = [&](const T* dPi, bool first, T* f) LRIGID_LANE_LAMBDA {
    T vr[3], ws[3], wW[3], fe[6];
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      vr[a] = (P[a] + dPi[a] + T(tc.ma) * u_f[a]) / T(tc.m) - u_f[a];
      ws[a] = (P[3 + a] + dPi[3 + a]) / T(tc.J);
    }
    rotate_by(q, ws, wW);  // Magnus on the world spin
    const DragOut<T> d = sphere_force_sum(tc, Fw, vr, ws, wW, fe);
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      f[a] = fe[a] + d.f[a];
      f[3 + a] = fe[3 + a] + d.tq[a];
    }
    if (first) J = d;
  };
  auto solve = [&](T gh, const T* b, T* x) LRIGID_LANE_LAMBDA {
    implicit_impulse(tc.mass, T(0), J, gh, b, x);
  };
  T dPi[6];
  ros2_impulse(hs, forces, solve, dPi);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) {
    V[a] = (P[a] + dPi[a] + T(tc.ma) * u_f[a]) / T(tc.m);
    w[a] = (P[3 + a] + dPi[3 + a]) / T(tc.J);
  }
}

// Advances every lane of lanes by one step; lanes that are not kOk keep their state at the start of
// the step. landed: the lane is on or below the ground after the step.
template <typename T, bool Strang>
LRIGID_MULTIVERSION void step_lanes(const StepConsts& tc, Lanes<T>* lanes, uint64_t step,
                                    int* outcome, int* landed) {
  const int nw = lanes->width;
  const T h = T(tc.h), hh = T(0.5 * tc.h), wm = T(tc.wm);
  const bool with_drag = tc.drag;
  const T tu = T(tc.tu);  // the seen fluctuation's factor in the fluid velocity
  alignas(64) T z1[3][kBatch], z2[3][kBatch];
  lane_normals(tc, *lanes, step, z1, z2);
  if constexpr (Strang) {
    // strang: first OU half step, force half step, the free flow (for isotropic M: V unchanged,
    // q <- q cay(h w)) with x by the trapezoidal rule, the field at the new positions, the
    // second force half step there, and the second OU half step (end_step, on that sample)
    NewState<T> next;
    alignas(64) T inside0[kBatch];
LRIGID_IVDEP
    for (int j = 0; j < nw; ++j) {
      T us[3] = {lanes->us[0][j], lanes->us[1][j], lanes->us[2][j]};
      T V[3] = {lanes->V[0][j], lanes->V[1][j], lanes->V[2][j]};
      T w[3] = {lanes->w[0][j], lanes->w[1][j], lanes->w[2][j]};
      lane_ou_half(tu, wm, hh, *lanes, z1, j, V, us);
      const T q0[4] = {lanes->q[0][j], lanes->q[1][j], lanes->q[2][j], lanes->q[3][j]};
      const T acc[3] = {lanes->acc[0][j], lanes->acc[1][j], lanes->acc[2][j]};
      T u_f[3];
#pragma GCC unroll 3
      for (int a = 0; a < 3; ++a) u_f[a] = T(tc.mf) * lanes->U[a][j] + tu * us[a];
      strang_force_lane(tc, q0, u_f, acc, hh, V, w);
      const T a[3] = {hh * w[0], hh * w[1], hh * w[2]};
      T q[4];
      cayley_rotate(q0, a, q);
#pragma GCC unroll 4
      for (int c = 0; c < 4; ++c) next.q[c][j] = q[c];
#pragma GCC unroll 3
      for (int c = 0; c < 3; ++c) {
        next.x[c][j] = lanes->x[c][j] + hh * (V[c] + V[c]);
        next.vel[c][j] = V[c];
        next.w[c][j] = w[c];
        next.us[c][j] = us[c];
      }
      next.scalar[j] = 0;
    }
    for (int j = 0; j < nw; ++j) inside0[j] = tc.sample ? lanes->inside[j] : T(1);
    if (tc.sample) sample_lanes(tc, next.x, lanes, 0, nw);
LRIGID_IVDEP
    for (int j = 0; j < nw; ++j) {
      const T q[4] = {next.q[0][j], next.q[1][j], next.q[2][j], next.q[3][j]};
      const T acc[3] = {lanes->acc[0][j], lanes->acc[1][j], lanes->acc[2][j]};
      T u_f[3], V[3] = {next.vel[0][j], next.vel[1][j], next.vel[2][j]},
                w[3] = {next.w[0][j], next.w[1][j], next.w[2][j]};
#pragma GCC unroll 3
      for (int a = 0; a < 3; ++a)
        u_f[a] = T(tc.mf) * lanes->U[a][j] + tu * next.us[a][j];
      strang_force_lane(tc, q, u_f, acc, hh, V, w);
#pragma GCC unroll 3
      for (int a = 0; a < 3; ++a) {
        next.vel[a][j] = V[a];
        next.w[a][j] = w[a];
      }
    }
    end_step<T>(tc, z2, next.vel, &next, lanes, outcome, landed, inside0);
    return;
  }
  // new state, committed at the end for the lanes whose step succeeded
  NewState<T> next;
  T(&xn)[3][kBatch] = next.x;
  T(&Vn)[3][kBatch] = next.vel;
  T(&wn)[3][kBatch] = next.w;
  T(&qn)[4][kBatch] = next.q;
  T(&usn)[3][kBatch] = next.us;
  for (int j = 0; j < nw; ++j) next.scalar[j] = 0;
  // what the Newton iteration of stiff drag needs
  alignas(64) T uf[3][kBatch], Pi[3][kBatch], dP[3][kBatch], dL[3][kBatch], V0[3][kBatch];
  // h times the forces other than drag, + b_B h a_fluid; h times the torques other than drag
  alignas(64) T G[6][kBatch];
  alignas(64) T norm_r[kBatch];
  int stiff[kBatch];
  int any_stiff = 0;
LRIGID_IVDEP
  for (int j = 0; j < nw; ++j) {
    T us[3] = {lanes->us[0][j], lanes->us[1][j], lanes->us[2][j]};
    const T U[3] = {lanes->U[0][j], lanes->U[1][j], lanes->U[2][j]};
    // 1. first OU half step
    {
      const T V[3] = {lanes->V[0][j], lanes->V[1][j], lanes->V[2][j]};
      lane_ou_half(tu, wm, hh, *lanes, z1, j, V, us);
    }
    // 2. the free Kirchhoff flow: for isotropic M the world velocity is unchanged and
    //    q <- q cay(h w) (integrate/dynamics.cpp kirchhoff_flow)
    T u_f[3], V[3], w[3];
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      u_f[a] = T(tc.mf) * U[a] + tu * us[a];
      V[a] = lanes->V[a][j];
      w[a] = lanes->w[a][j];
    }
    {
      const T q0[4] = {lanes->q[0][j], lanes->q[1][j], lanes->q[2][j], lanes->q[3][j]};
      const T a[3] = {hh * w[0], hh * w[1], hh * w[2]};
      T q[4];
      cayley_rotate(q0, a, q);
#pragma GCC unroll 4
      for (int c = 0; c < 4; ++c) qn[c][j] = q[c];
    }
    // 3. the forces, drag implicit: (M + h J + b_B P) M^-1 dPi = h G + b_B h a_fluid
    T vr[3];
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) vr[a] = V[a] - u_f[a];
    // Magnus on the world spin (the flow rotates q about w, so either orientation gives it);
    // the Basset history force joins the weight, its current interval's b_B h a_fluid the rest
    T Gj[6], Fj[3], wW[3], fe[6];
    const T qj[4] = {qn[0][j], qn[1][j], qn[2][j], qn[3][j]};
    rotate_by(qj, w, wW);
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) Fj[a] = T(tc.F[a]) + lanes->fb[a][j];
    const DragOut<T> drag = sphere_force_sum(tc, Fj, vr, w, wW, fe);
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      Gj[a] = h * fe[a] + T(tc.basset_mass) * h * T(tc.gu) * lanes->acc[a][j];
      Gj[3 + a] = h * fe[3 + a];
    }
    // the implicit step's impulse change (model/kirchhoff.h implicit_impulse; the world and
    // body frames differ by a rotation, under which the isotropic M and the stiffness commute)
    T b[6], P[3], dPL_j[6], Vnew[3], wnew[3], u_end[3];
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      b[a] = Gj[a] + h * drag.f[a];
      b[3 + a] = Gj[3 + a] + h * drag.tq[a];
      P[a] = T(tc.m) * V[a] - T(tc.ma) * u_f[a];
      // the fluid velocity at the end of the step enters through the added mass
      u_end[a] = u_f[a] + h * T(tc.gu) * lanes->acc[a][j];
    }
    implicit_impulse(tc.mass, T(tc.basset_mass), drag, h, b, dPL_j);
    const T* dPj = dPL_j;
    const T* dLj = dPL_j + 3;
    T e_new = 0, e_r = 0;
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      Vnew[a] = (P[a] + dPj[a] + T(tc.ma) * u_end[a]) / T(tc.m);
      wnew[a] = (T(tc.J) * w[a] + dLj[a]) / T(tc.J);
      e_new += dPj[a] * dPj[a] / T(tc.m) + dLj[a] * dLj[a] / T(tc.J);
      e_r += T(tc.m) * vr[a] * vr[a] + T(tc.J) * w[a] * w[a];
    }
    const int s = int(with_drag) & int(e_new > T(kStiffChange * kStiffChange) * e_r);
    stiff[j] = s;
    any_stiff |= s;
    norm_r[j] = e_r;
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      uf[a][j] = u_f[a];
      Pi[a][j] = P[a];
      dP[a][j] = dPj[a];
      dL[a][j] = dLj[a];
      G[a][j] = Gj[a];
      G[3 + a][j] = Gj[3 + a];
      V0[a][j] = V[a];
      Vn[a][j] = Vnew[a];
      wn[a][j] = wnew[a];
      usn[a][j] = us[a];
    }
  }
  // stiff drag: Newton on R(dPi) = dPi - h (G_other + F_drag(xi(dPi))) - b_B (h a - dV), lanes
  // drop out as they converge
  if (with_drag && any_stiff) {
    for (int j = 0; j < nw; ++j)
      lanes->newton += uint64_t(stiff[j] != 0) & uint64_t(lanes->live[j]);
    for (int it = 0; it < kDragMaxNewton; ++it) {
      int any = 0;
LRIGID_IVDEP
      for (int j = 0; j < nw; ++j) {
        // every lane computes, the lanes still iterating keep the result
        const bool act = stiff[j] != 0;
        T vr[3], w[3];
#pragma GCC unroll 3
        for (int a = 0; a < 3; ++a) {
          vr[a] = Vn[a][j] - uf[a][j];
          w[a] = wn[a][j];
        }
        const DragOut<T> drag = sphere_drag(tc, vr, w);
        T res[6], x[6];
#pragma GCC unroll 3
        for (int a = 0; a < 3; ++a) {
          res[a] = dP[a][j] - G[a][j] - h * drag.f[a] + T(tc.basset_mass / tc.m) * dP[a][j];
          res[3 + a] = dL[a][j] - h * drag.tq[a] - G[3 + a][j];
        }
        implicit_impulse(tc.mass, T(tc.basset_mass), drag, h, res, x);
        const T* dd = x;
        T conv = 0;
#pragma GCC unroll 3
        for (int a = 0; a < 3; ++a) {
          const T dl = -x[3 + a];
          const T dPa = dP[a][j] - dd[a], dLa = dL[a][j] + dl;
          const T acc = T(tc.gu) * lanes->acc[a][j];
          const T Va = (Pi[a][j] + dPa + T(tc.ma) * (uf[a][j] + h * acc)) / T(tc.m);
          const T wa = (T(tc.J) * lanes->w[a][j] + dLa) / T(tc.J);
          dP[a][j] = act ? dPa : dP[a][j];
          dL[a][j] = act ? dLa : dL[a][j];
          Vn[a][j] = act ? Va : Vn[a][j];
          wn[a][j] = act ? wa : wn[a][j];
          conv += dd[a] * dd[a] / T(tc.m) + dl * dl / T(tc.J);
        }
        const int more = int(act & (conv > T(kDragTol * kDragTol) * norm_r[j]));
        stiff[j] = more;
        any |= more;
      }
      if (!any) break;
    }
  }
  // 4. x by the trapezoidal rule; 5. the second OU half step at the new position
LRIGID_IVDEP
  for (int j = 0; j < nw; ++j)
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) xn[a][j] = lanes->x[a][j] + hh * (V0[a][j] + Vn[a][j]);
  end_step<T>(tc, z2, Vn, &next, lanes, outcome, landed);
}

}  // namespace
}  // namespace lrigid
#include "integrate/sphere_batch_explicit.h"  // euler and rk4
namespace lrigid {
namespace {

template <typename T>
BlockStats advance(const Model& model, const BodyType& type, State* state, const uint32_t* body,
                   int count, uint64_t first, uint64_t last) {
  const StepConsts tc = make_consts(model, type);
  const bool unsteady = tc.grid && model.field.frame_count() > 1;
  auto step = [&](auto, Lanes<T>* lanes, uint64_t s, int* outcome, int* landed) {
    if (tc.scheme == Integrator::Euler) return euler_lanes<T>(tc, lanes, s, outcome, landed);
    if (tc.scheme == Integrator::RK4)
      return rk4_lanes<T>(tc, rk4_frames(model, unsteady, s), lanes, s, outcome, landed);
    if (tc.strang)
      step_lanes<T, true>(tc, lanes, s, outcome, landed);
    else
      step_lanes<T, false>(tc, lanes, s, outcome, landed);
  };
  // (no template switch: the sphere step has one version per scheme and precision)
  return drive_block<T, Lanes<T>>(model, type, tc, false, state, body, count, first, last, step);
}

}  // namespace

const char* sphere_batch_isa() {
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
  // the same tests the loader's choice among the target_clones versions makes
  if (__builtin_cpu_supports("x86-64-v4")) return "AVX-512";
  if (__builtin_cpu_supports("x86-64-v3")) return "AVX2";
  return "baseline x86-64";
#else
  return "baseline";
#endif
}

BlockStats advance_sphere_block(const Model& model, const BodyType& type, State* state,
                                const uint32_t* body, int count, uint64_t first, uint64_t last) {
  if (model.precision == Precision::Float)
    return advance<float>(model, type, state, body, count, first, last);
  return advance<double>(model, type, state, body, count, first, last);
}

}  // namespace lrigid
