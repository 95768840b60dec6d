// The batched step's loops (integrate/rigid_batch.h): the constants of a body type, the lanes,
// the force kernels, the splitting and strang loops (splitting_lanes, strang_lanes), the euler
// and rk4 loops (rigid_batch_explicit.h) and advance<T, Mass>, which drives a block through them.
// Internal to the six files that instantiate it, one for each precision and kind of M
// (rigid_batch_{iso,diag,full}_{double,float}.cpp), which compile side by side. Each holds the
// splitting and strang loops once (the plate force stage is chosen inside them by by_shape) and
// the euler and rk4 loops once per plate switch: 6 instantiations per file for a diagonal or full
// M, 4 for an isotropic one (a sphere is never a plate), 32 in all, each compiled for every
// target of LRIGID_MULTIVERSION. bench/perf/build_time.sh measures what that costs.
//
// The kind of M is a policy of the stages: for an isotropic M the free Kirchhoff flow leaves the
// impulse unchanged (the stages skip its iteration), the lanes keep the world velocity (FrameOf:
// the translation needs no rotation), the drag takes a sphere's projected area and the terms of
// an offset centre of mass and of a plate are not compiled in.
#pragma once
#include <algorithm>
#include <cmath>
#include <type_traits>

#include "effects/drag.h"
#include "effects/lift.h"
#include "effects/plate.h"
#include "effects/wrench.h"
#include "integrate/batch_lanes.h"
#include "integrate/dynamics.h"
#include "model/kirchhoff.h"
#include "integrate/rigid_batch.h"

namespace lrigid {
namespace {  // NOLINT(build/namespaces): internal to rigid_batch_*.cpp

// The kinds of M: a diagonal one (IsotropicMass is one too) and an isotropic one
template <class Mass>
constexpr bool kDiagonal = std::is_base_of_v<DiagonalMass, Mass>;
template <class Mass>
constexpr bool kIsotropic = std::is_same_v<Mass, IsotropicMass>;

// What the step needs of the body type. Mass: M as the kernels of model/kirchhoff.h see it,
// IsotropicMass (uniform spheres), DiagonalMass (boxes, disks, ellipsoids) or FullMass (meshes;
// the step's loops are compiled once for each).
template <class Mass>
struct StepConsts : FieldConsts {
  static constexpr bool isotropic = kIsotropic<Mass>;
  bool plate = false;       // flat: plate drag and lift (with turb, the step's template switches)
  bool strang = false;      // the Strang scheme (not with the Basset history: integrators.h)
  Mass mass;                // M (model/kirchhoff.h)
  typename FluidImpulseOf<Mass>::type K;  // K's first three columns (0 without added mass)
  double drag = 0;          // the drag effect as a factor 1 or 0 (bodies that are not flat)
  // the drag of bodies that are not flat (effects/drag.h) and the plate model (effects/plate.h)
  DragParams law;
  PlateParams plate_model;
  double sphere_area = 0, sphere_diameter = 0;  // an isotropic M's (a sphere's), m^2 and m
  // euler and rk4 (rigid_batch_explicit.h): the scheme; M_body and K as the gyroscopic and
  // added-mass kernels take them (mass_times reads .M; K zero without added mass); the Basset
  // history's (M + b P)^-1, its first three columns in K's layout (fluid_impulse applies them)
  Integrator scheme = Integrator::Splitting;
  Mass body, fluid;
  typename FluidImpulseOf<Mass>::type basset_inv;
};

// a full K without the added-mass effect
constexpr double kNoTensor[36] = {};

template <class Mass>
StepConsts<Mass> make_consts(const Model& model, const BodyType& type) {
  StepConsts<Mass> tc;
  set_field_consts(model, type, &tc);
  const EffectSet& e = type.effects;
  const bool am = e.has(Effect::AddedMass);
  tc.plate = type.flat;
  tc.strang = model.integrator == Integrator::Strang && !tc.basset;
  if constexpr (kIsotropic<Mass>) {
    tc.mass = isotropic_mass(type.M(0, 0), type.M(3, 3));
    for (int a = 0; a < 3; ++a) tc.K.K[a] = am ? type.K_fluid(a, a) : 0.0;
  } else if constexpr (kDiagonal<Mass>) {
    tc.mass = diagonal_mass(type);
    for (int a = 0; a < 3; ++a) tc.K.K[a] = am ? type.K_fluid(a, a) : 0.0;
  } else {
    tc.mass = full_mass(type);  // points into type.M and M_inv
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 3; ++c) tc.K.K[r * 3 + c] = am ? type.K_fluid(r, c) : 0.0;
  }
  tc.drag = e.has(Effect::Drag) ? 1.0 : 0.0;
  {
    const double r = type.ell.x();
    tc.sphere_area = M_PI * r * r;
    tc.sphere_diameter = 2.0 * r;
  }
  // the kernels' parameters, as the scalar step's terms read them (effects/plan.h)
  tc.law = type.plan.params->drag;
  if (type.flat) tc.plate_model = type.plan.params->plate_both;
  tc.scheme = model.integrator;
  const Mat6& inv = type.basset.implicit_inv;
  if constexpr (kDiagonal<Mass>) {
    for (int a = 0; a < 6; ++a) {
      tc.body.M[a] = type.M_body(a, a);
      tc.fluid.M[a] = am ? type.K_fluid(a, a) : 0.0;
    }
    for (int a = 0; a < 3; ++a) tc.fluid.S[a] = type.munk_back(a, a);  // (zero without am)
    for (int a = 0; a < 3; ++a) tc.basset_inv.K[a] = tc.basset ? inv(a, a) : 0.0;
  } else {
    tc.body.M = type.M_body.data();  // symmetric: row or column major alike
    tc.fluid.M = am ? type.K_fluid.data() : kNoTensor;
    tc.fluid.S = type.munk_back.data();  // (zero without added mass)
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 3; ++c) tc.basset_inv.K[r * 3 + c] = tc.basset ? inv(r, c) : 0.0;
  }
  return tc;
}

// The frame a lane keeps its velocity v in and the loops take its translation in: the body
// frame (the scalar step's), or for an isotropic M the world frame: a uniform sphere's forces do
// not depend on its orientation, so its translation needs no rotation. The spin w stays in the
// body frame in both. The frame at orientation q (set): velocities to and from the world frame
// (to_world, of_world), and the spin w in the frame (spin: Magnus takes it with the velocity).
template <typename T>
struct BodyFrame {
  T R[9];  // body -> world
  LRIGID_LANE void set(const T* q) { rotation(q, R); }
  LRIGID_LANE void to_world(const T* a, T* b) const { mul(R, a, b); }
  LRIGID_LANE void of_world(const T* a, T* b) const { mul_t(R, a, b); }
  LRIGID_LANE void spin(const T* w, T* s) const {
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) s[a] = w[a];
  }
  // a body-frame vector (the angular momentum) to and from the world frame
  LRIGID_LANE void body_to_world(const T* a, T* b) const { mul(R, a, b); }
  LRIGID_LANE void body_of_world(const T* a, T* b) const { mul_t(R, a, b); }
};
template <typename T>
struct WorldFrame {
  T q[4];
  LRIGID_LANE void set(const T* qb) {
#pragma GCC unroll 4
    for (int a = 0; a < 4; ++a) q[a] = qb[a];
  }
  LRIGID_LANE void to_world(const T* a, T* b) const {
#pragma GCC unroll 3
    for (int c = 0; c < 3; ++c) b[c] = a[c];
  }
  LRIGID_LANE void of_world(const T* a, T* b) const { to_world(a, b); }
  LRIGID_LANE void spin(const T* w, T* s) const { rotate_by(q, w, s); }
  LRIGID_LANE void body_to_world(const T* a, T* b) const { rotate_by(q, a, b); }
  LRIGID_LANE void body_of_world(const T* a, T* b) const {
    const T c[4] = {q[0], -q[1], -q[2], -q[3]};
    rotate_by(c, a, b);
  }
};
template <typename T, class Mass>
using FrameOf = std::conditional_t<kIsotropic<Mass>, WorldFrame<T>, BodyFrame<T>>;

// The state of a block of bodies, structure of arrays: v in the frame of FrameOf<T, Mass> (the
// body frame, or the world frame for an isotropic M), w in the body frame.
template <typename T, class Mass>
struct Lanes : Samples<T> {
  static constexpr bool kWorld = kIsotropic<Mass>;
  alignas(64) T v[3][kBatch];
  alignas(64) T w[3][kBatch];
  alignas(64) T q[4][kBatch];  // (w, x, y, z)
  alignas(64) T us[3][kBatch];

  void load(int j, const BodyState& b) {
    const Vec3 vf = kWorld ? Vec3(b.q * b.v) : b.v;
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      this->x[a][j] = T(b.x[a]);
      v[a][j] = T(vf[a]);
      w[a][j] = T(b.w[a]);
      us[a][j] = T(b.u_seen[a]);
    }
    q[0][j] = T(b.q.w()), q[1][j] = T(b.q.x()), q[2][j] = T(b.q.y()), q[3][j] = T(b.q.z());
  }
  void store(int j, BodyState* b) const {
    b->x = Vec3(double(this->x[0][j]), double(this->x[1][j]), double(this->x[2][j]));
    b->q = Quat(double(q[0][j]), double(q[1][j]), double(q[2][j]), double(q[3][j]));
    b->v = Vec3(double(v[0][j]), double(v[1][j]), double(v[2][j]));
    if (kWorld) b->v = b->q.toRotationMatrix().transpose() * b->v;
    b->w = Vec3(double(w[0][j]), double(w[1][j]), double(w[2][j]));
    b->u_seen = Vec3(double(us[0][j]), double(us[1][j]), double(us[2][j]));
  }
  void rest(int j) {
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) v[a][j] = w[a][j] = T(0);
  }
  T (*velocity())[kBatch] { return v; }  // the velocity a lane keeps (end_step)
};

// The forces of a body that is not flat: the drag (effects/drag.h, the equivalent ellipsoid's
// projected area across u) times the drag effect's factor (0 without it)
template <typename T, class C>
LRIGID_LANE DragOut<T> ellipsoid_forces(const C& tc, const T* u, const T* w) {
  DragOut<T> drag = ellipsoid_drag_kernel(tc.law, u, w);
  const T dr = T(tc.drag);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) {
    drag.f[a] *= dr;
    drag.tq[a] *= dr;
  }
  drag.c_lin *= dr;
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) drag.c_ang[a] *= dr;
  return drag;
}

// The centre of mass may be off the volume centroid (BodyType::r_cob): the fluid's
// forces act at the centroid (effects/wrench.h centroid_velocity_kernel, add_offset_torque_kernel,
// the scalar terms' kernels), on the type's r_cob in the lane's precision.
template <typename T, class C>
LRIGID_LANE void centroid_velocity(const C& tc, const T* u, const T* w, T* uc) {
  const T r[3] = {T(tc.r_cob[0]), T(tc.r_cob[1]), T(tc.r_cob[2])};
  centroid_velocity_kernel(r, u, w, uc);
}
template <typename T, class C>
LRIGID_LANE void add_offset_torque(const C& tc, const T* f, T* tq) {
  const T r[3] = {T(tc.r_cob[0]), T(tc.r_cob[1]), T(tc.r_cob[2])};
  add_offset_torque_kernel(r, f, tq);
}

// A lane's drag (and, for plates, lift: effects/plate.h) on relative velocity u and spin w, at
// the volume centroid, with the drag's torque about the centre of mass (the lift's, explicit:
// explicit_torque). A uniform body has r_cob = 0, which leaves u and the torque unchanged to the
// bit (u + w x 0 = u), so one loop serves bodies with and without an offset centre of mass.
template <typename T, bool Plate, class C>
LRIGID_LANE DragOut<T> body_forces(const C& tc, const T* u, const T* w, T* lift) {
  if constexpr (C::isotropic) {
    // a uniform sphere: the centroid is the centre of mass, the projected area the same across
    // every direction
    const T a_perp = T(tc.sphere_area), d_perp = T(tc.sphere_diameter);
    DragOut<T> d = drag_kernel(tc.law, u, w, [&](const T*, T* a, T* diameter) {
      *a = a_perp;
      *diameter = d_perp;
    });
    const T dr = T(tc.drag);
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      d.f[a] *= dr;
      d.tq[a] *= dr;
      d.c_ang[a] *= dr;
    }
    d.c_lin *= dr;
    return d;
  }
  T uc[3];
  centroid_velocity(tc, u, w, uc);
  DragOut<T> drag;
  if constexpr (Plate)
    plate_kernel(tc.plate_model, uc, w, &drag, lift);
  else
    drag = ellipsoid_forces(tc, uc, w);
  add_offset_torque(tc, drag.f, drag.tq);
  return drag;
}

// The Magnus force on a lane with relative velocity u and spin w (both in the lanes' frame,
// FrameOf), at the centroid
template <typename T, class C>
LRIGID_LANE void lane_magnus(const C& tc, const T* u, const T* w, T* f) {
  if constexpr (C::isotropic) return magnus_kernel(T(tc.magnus), w, u, f);
  T uc[3];
  centroid_velocity(tc, u, w, uc);
  magnus_kernel(T(tc.magnus), w, uc, f);
}

// The torque about the centre of mass of the explicit forces that act at the centroid
// (effects/buoyancy.h, lift.cpp, magnus.h): r_cob x (buoyancy + lift + Magnus), the buoyancy
// rotated to the body by the frame fr (BodyFrame); zero for a uniform body
template <typename T, class C, class Frame>
LRIGID_LANE void explicit_torque(const C& tc, const Frame& fr, const T* lift, const T* fx,
                                 T* tq) {
  if constexpr (C::isotropic) {
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) tq[a] = T(0);
    return;
  }
  const T Fw[3] = {T(tc.F_buoy[0]), T(tc.F_buoy[1]), T(tc.F_buoy[2])};
  T f[3];
  fr.of_world(Fw, f);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) {
    f[a] += lift[a] + fx[a];
    tq[a] = T(0);
  }
  add_offset_torque(tc, f, tq);
}

// The forces stage's sum on one lane, written once for every scheme (the batched counterpart of
// the scalar step's EffectPlan): in the frame fr (FrameOf: the body frame, or the world frame
// for an isotropic M), relative velocity vr in that frame and spin w (body frame), with Fb the
// weight and buoyancy (and the Basset history force) in that frame. The torques are in the body
// frame. Returns the drag (and the plate's dissipative torque) with its stiffness, which the
// splitting and strang steps take implicitly; fe = (force; torque) of the explicit rest: Fb, the
// plate's lift, Magnus, and their torque about an offset centre of mass. Each term is its
// effect's kernel (effects/); an effect off contributes its factor 0.
template <typename T, bool Plate, class Mass, class Frame>
LRIGID_LANE DragOut<T> lane_forces(const StepConsts<Mass>& tc, const Frame& fr, const T* Fb,
                                   const T* vr, const T* w, T* fe) {
  T lift[3] = {0, 0, 0}, fx[3], tx[3], ws[3];
  const DragOut<T> d = body_forces<T, Plate>(tc, vr, w, lift);
  fr.spin(w, ws);  // Magnus: the spin in vr's frame
  lane_magnus(tc, vr, ws, fx);
  explicit_torque(tc, fr, lift, fx, tx);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) {
    fe[a] = Fb[a] + lift[a] + fx[a];
    fe[3 + a] = tx[a];
  }
  return d;
}

// The Strang scheme's force step over hs on a lane's velocities v (in the frame fr) and w (body
// frame), in place, and the fluid velocity u_f (world) with its material derivative acc (world,
// the gu factor applied here): ROS2 (model/kirchhoff.h ros2_velocity), as integrators.cpp
// strang_force_step (for an isotropic M the world and body frames give the same step). Not with
// the Basset history (tc.strang).
template <typename T, bool Plate, class Mass>
LRIGID_LANE void strang_force_lane(const StepConsts<Mass>& tc, const FrameOf<T, Mass>& fr,
                                   const T* u_f, const T* acc, T hs, T* v, T* w) {
  const T F[3] = {T(tc.F[0]), T(tc.F[1]), T(tc.F[2])};
  const T a_f[3] = {T(tc.gu) * acc[0], T(tc.gu) * acc[1], T(tc.gu) * acc[2]};
  T ufb[3], ab[3], Fb[3];
  fr.of_world(u_f, ufb);
  fr.of_world(a_f, ab);
  fr.of_world(F, Fb);
  // the fluid's acceleration drags the added mass along: K (R^T a; 0), a force and (meshes) a
  // torque
  T drag_along[6];
  fluid_impulse(tc.K, ab, drag_along);
  const T xi0[6] = {v[0], v[1], v[2], w[0], w[1], w[2]};
  DragOut<T> J{};
  auto forces = [&](const T* dxi, bool first, T* f) LRIGID_LANE_LAMBDA {
    T vr[3], wn[3], fe[6];
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      vr[a] = xi0[a] + dxi[a] - ufb[a];
      wn[a] = xi0[3 + a] + dxi[3 + a];
    }
    const DragOut<T> d = lane_forces<T, Plate>(tc, fr, Fb, vr, wn, fe);
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      f[a] = fe[a] + drag_along[a] + d.f[a];
      f[3 + a] = fe[3 + a] + drag_along[3 + a] + d.tq[a];
    }
    if (first) J = d;
  };
  // (a full M: the matrix of ROS2's two stages factored once, at the first)
  [[maybe_unused]] T lu[std::is_same_v<Mass, FullMass> ? 36 : 1];
  [[maybe_unused]] bool factored = false;
  auto solve = [&](T gh, const T* b, T* y) LRIGID_LANE_LAMBDA {
    if constexpr (std::is_same_v<Mass, FullMass>) {
      if (!factored) implicit_factor(tc.mass, T(0), J, gh, lu);
      factored = true;
      implicit_solve(lu, b, y);
    } else {
      implicit_velocity(tc.mass, T(0), J, gh, b, y);
    }
  };
  auto m_times = [&](const T* y, T* x) LRIGID_LANE_LAMBDA { mass_times(tc.mass, y, x); };
  T dxi[6];
  ros2_velocity(hs, forces, solve, m_times, dxi);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) {
    v[a] = xi0[a] + dxi[a];
    w[a] = xi0[3 + a] + dxi[3 + a];
  }
}

// The end of the free Kirchhoff flow of lane j from the converged iterate: the orientation
// q <- q cay(h w_mid) (q: the lane's at the start), the frame there, and v (in that frame), w
// relative to the fluid velocity u_f (world) the flow moved in
template <typename T, class Mass>
LRIGID_LANE void flow_end(const StepConsts<Mass>& tc, const T* q0, const T* y0, const T* y,
                          const T* u_f, T* q, FrameOf<T, Mass>* fr, T* ufb, T* v, T* w) {
  const T hh = T(0.5 * tc.h);
  T ym[6], xi[6], a[3];
#pragma GCC unroll 6
  for (int k = 0; k < 6; ++k) ym[k] = T(0.5) * (y0[k] + y[k]);
  if constexpr (kDiagonal<Mass>) {
    // (h/2 M^-1 first: the diagonal path's rounding, which its tests compare against)
#pragma GCC unroll 3
    for (int k = 0; k < 3; ++k) a[k] = hh * T(tc.mass.Mi[3 + k]) * ym[3 + k];
  } else {
    T xm[6];
    mass_inv_times(tc.mass, ym, xm);  // (the linear rows unused: the compiler drops them)
#pragma GCC unroll 3
    for (int k = 0; k < 3; ++k) a[k] = hh * xm[3 + k];
  }
  cayley_rotate(q0, a, q);
  fr->set(q);
  fr->of_world(u_f, ufb);
  mass_inv_times(tc.mass, y, xi);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) {
    v[a] = xi[a] + ufb[a];
    w[a] = xi[3 + a];
  }
}

// flow_end on lane j of the block's arrays: its start orientation q0 (4 x kBatch), the
// iteration's start impulse Y0 and converged iterate Y (6 x kBatch) and the fluid velocity uf
// (3 x kBatch) the flow moved in (the splitting and the strang steps' end of the flow)
template <typename T, class Mass>
LRIGID_LANE void lane_flow_end(const StepConsts<Mass>& tc, const T (*q0)[kBatch],
                               const T (*Y0)[kBatch], const T (*Y)[kBatch],
                               const T (*uf)[kBatch], int j, T* q, FrameOf<T, Mass>* fr, T* ufb,
                               T* v, T* w) {
  T y0[6], y[6];
#pragma GCC unroll 6
  for (int a = 0; a < 6; ++a) {
    y0[a] = Y0[a][j];
    y[a] = Y[a][j];
  }
  const T q0j[4] = {q0[0][j], q0[1][j], q0[2][j], q0[3][j]};
  const T u_f[3] = {uf[0][j], uf[1][j], uf[2][j]};
  flow_end(tc, q0j, y0, y, u_f, q, fr, ufb, v, w);
}

// The force step's norms, d^T M^-1 d of an impulse change d and xi^T M xi of a velocity xi
// (model/kirchhoff.h energy_norm2, velocity_norm2), for a diagonal M summed in linear and
// angular pairs: the diagonal path's stiffness and convergence tests take their decisions, and
// its results their rounding, from these sums
template <typename T, class Mass>
LRIGID_LANE T lane_energy_norm2(const Mass& m, const T* d) {
  if constexpr (kDiagonal<Mass>) {
    T s = 0;
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a)
      s += d[a] * d[a] * T(m.Mi[a]) + d[3 + a] * d[3 + a] * T(m.Mi[3 + a]);
    return s;
  } else {
    return energy_norm2(m, d);
  }
}
template <typename T, class Mass>
LRIGID_LANE T lane_velocity_norm2(const Mass& m, const T* xi) {
  if constexpr (kDiagonal<Mass>) {
    T s = 0;
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a)
      s += T(m.M[a]) * xi[a] * xi[a] + T(m.M[3 + a]) * xi[3 + a] * xi[3 + a];
    return s;
  } else {
    return velocity_norm2(m, xi);
  }
}

// the scalar step's Kirchhoff tolerance (integrate/dynamics.h); float converges to its own
// round-off
template <typename T>
constexpr double kLaneKirchhoffTol = std::is_same_v<T, float> ? 1e-5 : kKirchhoffTol;
constexpr int kLaneKirchhoffNewton = kKirchhoffMaxNewton / 2;
// the stiff-drag Newton runs over only its lanes when at most kBatch / kSparseNewton of a block's
// lanes need it, and vectorised over the whole block (masked) when more do
constexpr int kSparseNewton = 4;

// The splitting and strang steps' state within a step, across a block: the free Kirchhoff
// flow's start impulse Y0 and iterate Y (relative to the fluid), its tolerance tol2 and last
// update norm per lane, the lanes still iterating (active), the fluid velocity uf (world) the
// flow moves in, and the world velocity V0 at the start of the step.
template <typename T>
struct FlowBlock {
  alignas(64) T Y0[6][kBatch], Y[6][kBatch], tol2[kBatch], last[kBatch];
  alignas(64) T uf[3][kBatch], V0[3][kBatch];
  int active[kBatch];
};

// Calls f with std::bool_constant<plate> (with_switch), and with false alone for an isotropic M
// (a sphere is never flat): the plate's kernels are not compiled into its loops
template <class Mass, class F>
LRIGID_LANE void by_shape(bool plate, F f) {
  if constexpr (kIsotropic<Mass>)
    f(std::false_type{});
  else
    with_switch(plate, f);
}

// The stages of the splitting and strang steps (integrators.h), each a loop (or a few) across the
// block's live lanes, inlined into each scheme's loop function below. "in => out" names what a
// stage reads and writes of the block (lanes: the state at the start of the step and the samples;
// flow: FlowBlock; next: NewState).

// Stage 1, the turbulence: lanes (state, sample), z1 => next.us (the seen fluctuation after the
// first exact OU half step along the start's world velocity), flow.uf (the fluid velocity,
// world: the mean flow and that fluctuation), next.scalar = 0.
template <typename T, class Mass>
LRIGID_LANE void stage_turbulence_start(const StepConsts<Mass>& tc, const Lanes<T, Mass>* lanes,
                                        const T (*z1)[kBatch], FlowBlock<T>* flow,
                                        NewState<T>* next) {
  const int nw = lanes->width;
  const T hh = T(0.5 * tc.h), wm = T(tc.wm), tu = T(tc.tu);
  const T cd[3] = {T(tc.cd[0]), T(tc.cd[1]), T(tc.cd[2])};
LRIGID_IVDEP
  for (int j = 0; j < nw; ++j) {
    T us[3] = {lanes->us[0][j], lanes->us[1][j], lanes->us[2][j]};
    const T q[4] = {lanes->q[0][j], lanes->q[1][j], lanes->q[2][j], lanes->q[3][j]};
    const T v[3] = {lanes->v[0][j], lanes->v[1][j], lanes->v[2][j]};
    T V[3];
    FrameOf<T, Mass> fr;
    fr.set(q);
    fr.to_world(v, V);
    lane_ou_half(tu, wm, hh, cd, *lanes, z1, j, V, us);
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      flow->uf[a][j] = T(tc.mf) * lanes->U[a][j] + tu * us[a];
      next->us[a][j] = us[a];
    }
    next->scalar[j] = 0;
  }
}

// Strang's force half step (ROS2 over h/2, strang_force_lane) on every lane, at orientation q and
// body-frame velocities v, w (the start's, or the end of the flow's), in the fluid velocity
// mf U + tu us of the lanes' current sample and next.us => next.vel, next.w and the world
// velocity Vn. The body's shape (Plate) chooses the force kernels: the recipes
// call it through by_shape, outside the loop. A function of its own, compiled for each
// instruction set as the schemes' loop functions are (each clone calls its own instruction set's
// clone): strang takes it twice a step, and inlined twice it was most of strang's machine code
// and of its compile time.
template <typename T, bool Plate, class Mass>
LRIGID_MULTIVERSION void strang_force_lanes(const StepConsts<Mass>& tc, const Lanes<T, Mass>* lanes,
                                            const T (*q)[kBatch], const T (*v)[kBatch],
                                            const T (*w)[kBatch], NewState<T>* next,
                                            T (*Vn)[kBatch]) {
  const int nw = lanes->width;
  const T hh = T(0.5 * tc.h), tu = T(tc.tu);
LRIGID_IVDEP
  for (int j = 0; j < nw; ++j) {
    const T qj[4] = {q[0][j], q[1][j], q[2][j], q[3][j]};
    const T acc[3] = {lanes->acc[0][j], lanes->acc[1][j], lanes->acc[2][j]};
    T u_f[3], vj[3] = {v[0][j], v[1][j], v[2][j]}, wj[3] = {w[0][j], w[1][j], w[2][j]};
    FrameOf<T, Mass> fr;
    fr.set(qj);
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) u_f[a] = T(tc.mf) * lanes->U[a][j] + tu * next->us[a][j];
    strang_force_lane<T, Plate>(tc, fr, u_f, acc, hh, vj, wj);
    T Vend[3];
    fr.to_world(vj, Vend);
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      next->vel[a][j] = vj[a];
      next->w[a][j] = wj[a];
      Vn[a][j] = Vend[a];
    }
  }
}

// The start of the free Kirchhoff flow: at the start's orientation, body-frame velocities v, w
// (splitting: the start's; strang: after the first force half step) and the fluid velocity
// flow.uf => flow (V0, the world velocity; uf, corrected by mid h/2 grad U V0, the fluid velocity
// at the flow's midpoint for strang, mid = 1; Y0 and the explicit midpoint predictor Y of the
// motion relative to the fluid, tol2, active).
template <typename T, class Mass>
LRIGID_LANE void stage_flow_begin(const StepConsts<Mass>& tc, const Lanes<T, Mass>* lanes,
                                  const T (*v)[kBatch], const T (*w)[kBatch], T mid,
                                  FlowBlock<T>* flow) {
  const int nw = lanes->width;
  const T h = T(tc.h), hh = T(0.5 * tc.h), gm = mid * T(tc.gu) * hh;
LRIGID_IVDEP
  for (int j = 0; j < nw; ++j) {
    const T q[4] = {lanes->q[0][j], lanes->q[1][j], lanes->q[2][j], lanes->q[3][j]};
    const T vj[3] = {v[0][j], v[1][j], v[2][j]}, wj[3] = {w[0][j], w[1][j], w[2][j]};
    T V[3], u_f[3], ufb[3];
    FrameOf<T, Mass> fr;
    fr.set(q);
    fr.to_world(vj, V);
#pragma GCC unroll 3
    for (int p = 0; p < 3; ++p)
      u_f[p] = flow->uf[p][j] + gm * (lanes->gU[p * 3][j] * V[0] + lanes->gU[p * 3 + 1][j] * V[1] +
                                      lanes->gU[p * 3 + 2][j] * V[2]);
    fr.of_world(u_f, ufb);
    // the implicit midpoint rule's start (dynamics.cpp kirchhoff_midpoint)
    T y0[6], y[6];
    const T xr[6] = {vj[0] - ufb[0], vj[1] - ufb[1], vj[2] - ufb[2], wj[0], wj[1], wj[2]};
    mass_times(tc.mass, xr, y0);
    // an isotropic M: G = 0, the flow leaves Y unchanged (a rotation alone)
    if constexpr (kIsotropic<Mass>) {
#pragma GCC unroll 6
      for (int a = 0; a < 6; ++a) y[a] = y0[a];
    } else {
      kirchhoff_predictor(tc.mass, h, y0, y);
    }
    const T norm0 = energy_norm2(tc.mass, y0);
#pragma GCC unroll 6
    for (int a = 0; a < 6; ++a) {
      flow->Y0[a][j] = y0[a];
      flow->Y[a][j] = y[a];
    }
    flow->tol2[j] = T(kLaneKirchhoffTol<T> * kLaneKirchhoffTol<T>) * norm0;
    flow->last[j] = T(0);
    flow->active[j] = kIsotropic<Mass> ? 0 : 1;
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      flow->uf[a][j] = u_f[a];
      flow->V0[a][j] = V[a];
    }
  }
}

// Stage 2, the free Kirchhoff flow (gyroscopic and Munk terms) by the implicit midpoint rule:
// flow (Y0, Y) => flow.Y converged, flow.active and next.scalar for the lanes left to the scalar
// step. The fixed-point iteration per lane under a convergence mask, then Newton for the lanes
// whose fixed point stopped.
template <typename T, class Mass>
LRIGID_LANE void stage_kirchhoff_flow(const StepConsts<Mass>& tc, Lanes<T, Mass>* lanes,
                                      FlowBlock<T>* flow, NewState<T>* next) {
  const int nw = lanes->width;
  const T h = T(tc.h), hh = T(0.5 * tc.h);
  (void)h, (void)hh;
  if constexpr (kIsotropic<Mass>) return;  // nothing to iterate (stage_flow_begin)
  // the fixed-point iteration Y <- Y0 - h gyro((Y0 + Y)/2); lanes drop out as they converge;
  // a lane that contracts slowly or diverges goes to the scalar step (its Newton iteration)
  for (int it = 0; it < kKirchhoffMaxFixedPoint; ++it) {
    int any = 0;
LRIGID_IVDEP
    for (int j = 0; j < nw; ++j) {
      T y0[6], y[6], y_next[6];
#pragma GCC unroll 6
      for (int a = 0; a < 6; ++a) {
        y0[a] = flow->Y0[a][j];
        y[a] = flow->Y[a][j];
      }
      const T step2 = kirchhoff_fixed_point(tc.mass, h, y0, y, y_next);
      int fin = 1;
#pragma GCC unroll 6
      for (int a = 0; a < 6; ++a) fin &= int(std::isfinite(y_next[a]));
      const int act = flow->active[j];
      const int keep = act & fin;
#pragma GCC unroll 6
      for (int a = 0; a < 6; ++a) flow->Y[a][j] = keep ? y_next[a] : flow->Y[a][j];
      const int conv = int(step2 <= flow->tol2[j]);
      const int slow = int(it > 0) & int(step2 > T(kKirchhoffSlowContraction) * flow->last[j]);
      next->scalar[j] |= act & ((1 - fin) | ((1 - conv) & slow));
      const int more = keep & (1 - conv) & (1 - slow);
      flow->last[j] = act ? step2 : flow->last[j];
      flow->active[j] = more;
      any |= more;
    }
    if (!any) break;
  }
  // lanes whose fixed point stopped (slow contraction, divergence, or no convergence): Newton
  // from where it stopped, as kirchhoff_midpoint does (simplified: the Jacobian kept while each
  // step contracts by kKirchhoffRefactor). A lane that has not converged within half the scalar
  // step's iterations goes to the scalar step: where Newton struggles, rounding alone (these
  // loops factor without pivoting) could decide between converging and the scalar step's
  // substeps, and the results must be the scalar step's.
  {
    alignas(64) T lu[36][kBatch], last_step[kBatch];
    int newton[kBatch], refactor[kBatch];
    int any_newton = 0;
    for (int j = 0; j < nw; ++j) {
      newton[j] = next->scalar[j] | flow->active[j];
      any_newton |= newton[j];
    }
    // most blocks have no lane here: they skip the start and the counting (one pass over the
    // flags above)
    if (any_newton) {
LRIGID_IVDEP
      for (int j = 0; j < nw; ++j) {
        const int nt = newton[j];
        refactor[j] = 1;
        last_step[j] = T(0);
        // the start: where the fixed point stopped, or Y0 if that is not finite or far off
        T y0[6], dy[6];
        int fin = 1;
#pragma GCC unroll 6
        for (int a = 0; a < 6; ++a) {
          y0[a] = flow->Y0[a][j];
          dy[a] = flow->Y[a][j] - y0[a];
          fin &= int(std::isfinite(flow->Y[a][j]));
        }
        const T dist = energy_norm2(tc.mass, dy), norm0 = energy_norm2(tc.mass, y0);
        const int reset = nt & ((1 - fin) | int(dist > T(4) * norm0));
#pragma GCC unroll 6
        for (int a = 0; a < 6; ++a) flow->Y[a][j] = reset ? flow->Y0[a][j] : flow->Y[a][j];
      }
      for (int j = 0; j < nw; ++j)
        lanes->newton += uint64_t(newton[j] != 0) & uint64_t(lanes->live[j]);
      for (int e = 0; e < 36; ++e)
        for (int j = 0; j < nw; ++j) lu[e][j] = T(0);
    }
    for (int it = 0; any_newton && it < kLaneKirchhoffNewton; ++it) {
      // a new factorization at the current iterate for the lanes that need one (all of them in
      // the first iteration), the kept one for the others
      int any_ref = 0;
      for (int j = 0; j < nw; ++j) any_ref |= newton[j] & refactor[j];
      if (any_ref) {
LRIGID_IVDEP
        for (int j = 0; j < nw; ++j) {
          T ym[6], A[36];
#pragma GCC unroll 6
          for (int a = 0; a < 6; ++a) ym[a] = T(0.5) * (flow->Y0[a][j] + flow->Y[a][j]);
          kirchhoff_newton_matrix(tc.mass, ym, hh, A);
          const int ok = lu_factor<6>(A);
          const int ref = newton[j] & refactor[j];
#pragma GCC unroll 36
          for (int e = 0; e < 36; ++e) lu[e][j] = ref ? A[e] : lu[e][j];
          // a singular matrix: the lane goes to the scalar step
          newton[j] = ref & (1 - ok) ? 0 : newton[j];
        }
      }
      int any = 0;
LRIGID_IVDEP
      for (int j = 0; j < nw; ++j) {
        const int act = newton[j];
        T y0[6], y[6], r[6], A[36];
#pragma GCC unroll 6
        for (int a = 0; a < 6; ++a) {
          y0[a] = flow->Y0[a][j];
          y[a] = flow->Y[a][j];
        }
        kirchhoff_residual(tc.mass, h, y0, y, r);
#pragma GCC unroll 36
        for (int e = 0; e < 36; ++e) A[e] = lu[e][j];
        lu_solve<6>(A, r);
        const T step2 = energy_norm2(tc.mass, r);
        int fin = 1;
#pragma GCC unroll 6
        for (int a = 0; a < 6; ++a) {
          y[a] += r[a];
          fin &= int(std::isfinite(y[a]));
        }
        const int good = act & fin;
#pragma GCC unroll 6
        for (int a = 0; a < 6; ++a) flow->Y[a][j] = good ? y[a] : flow->Y[a][j];
        const int conv = good & int(step2 <= flow->tol2[j]);
        // converged: the loops take the lane again; failed: it stays with the scalar step
        next->scalar[j] = conv ? 0 : next->scalar[j];
        flow->active[j] = conv ? 0 : flow->active[j];
        const int more = good & (1 - conv);
        refactor[j] =
            int(it > 0) & int(step2 > T(kKirchhoffRefactor * kKirchhoffRefactor) * last_step[j]);
        last_step[j] = step2;
        newton[j] = more;
        any |= more;
      }
      if (!any) break;
    }
    // lanes still in Newton after kLaneKirchhoffNewton iterations go to the scalar step
  }
}

// Stage 3 of splitting, the forces at the new orientation with the drag implicit:
// (M + h J + b_B P) M^-1 dPi = h G + b_B h a_fluid, one linearly implicit step, then Newton for
// the lanes whose drag is stiff. flow (Y0, Y, uf), lanes (sample, Basset force) => next.q, the
// body-frame velocities next.vel, next.w.
template <typename T, bool Plate, class Mass>
LRIGID_LANE void stage_forces_implicit(const StepConsts<Mass>& tc, Lanes<T, Mass>* lanes,
                                       FlowBlock<T>* flow, NewState<T>* next) {
  const int nw = lanes->width;
  const T h = T(tc.h), hh = T(0.5 * tc.h);
  (void)h, (void)hh;
  // what Newton needs: the impulse P (linear, relative to the fluid's added-mass impulse) and lanes
  // before the forces, their changes dP and dL, h times the forces other than drag G (and their
  // torque about an offset centre of mass: zero for a uniform body), the fluid velocity (body
  // frame) at the end, and the norm of the relative velocity
  alignas(64) T Pl[6][kBatch], dPL[6][kBatch], G[6][kBatch], ufe[3][kBatch],
      ufs[3][kBatch];
  alignas(64) T norm_r[kBatch];
  int stiff[kBatch];
  int any_stiff = 0;
LRIGID_IVDEP
  for (int j = 0; j < nw; ++j) {
    // q <- q cay(h w_mid)
    T q[4], ufb[3], v[3], w[3], vr[3];
    FrameOf<T, Mass> fr;
    lane_flow_end(tc, lanes->q, flow->Y0, flow->Y, flow->uf, j, q, &fr, ufb, v, w);
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) vr[a] = v[a] - ufb[a];
    // the Basset history force (world; zero without the history) joins the weight; the current
    // interval's b_B h a_fluid (body frame) joins the explicit forces
    T F[3], acc[3], Fb[3], u_end[3], ufb_end[3], ab[3], fe[6];
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      F[a] = T(tc.F[a]) + lanes->fb[a][j];
      acc[a] = T(tc.gu) * lanes->acc[a][j];
    }
    fr.of_world(acc, ab);
    fr.of_world(F, Fb);
    const DragOut<T> drag = lane_forces<T, Plate>(tc, fr, Fb, vr, w, fe);
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) u_end[a] = flow->uf[a][j] + h * T(tc.gu) * lanes->acc[a][j];
    fr.of_world(u_end, ufb_end);
    T Gj[6], rhs[6], dPL_j[6];
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      Gj[a] = h * fe[a] + T(tc.basset_mass) * h * ab[a];
      Gj[3 + a] = h * fe[3 + a];
      rhs[a] = Gj[a] + h * drag.f[a];
      rhs[3 + a] = Gj[3 + a] + h * drag.tq[a];
    }
    implicit_impulse(tc.mass, T(tc.basset_mass), drag, h, rhs, dPL_j);
    // the impulse Pi before the forces (relative to the fluid's added-mass impulse) and the
    // velocity after them, xi = M^-1 (Pi + dPi + K (u_f end; 0))
    const T xi[6] = {v[0], v[1], v[2], w[0], w[1], w[2]};
    T Pi[6], Pn[6], xin[6];
    impulse_of_velocity(tc.mass, tc.K, xi, ufb, Pi);
#pragma GCC unroll 6
    for (int a = 0; a < 6; ++a) {
      Pn[a] = Pi[a] + dPL_j[a];
      Pl[a][j] = Pi[a];
      dPL[a][j] = dPL_j[a];
    }
    velocity_of_impulse(tc.mass, tc.K, Pn, ufb_end, xin);
    const T xr[6] = {vr[0], vr[1], vr[2], w[0], w[1], w[2]};
    const T e_new = lane_energy_norm2(tc.mass, dPL_j), e_r = lane_velocity_norm2(tc.mass, xr);
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      next->vel[a][j] = xin[a];
      next->w[a][j] = xin[3 + a];
      G[a][j] = Gj[a];
      G[3 + a][j] = Gj[3 + a];
      ufe[a][j] = ufb_end[a];
      ufs[a][j] = ufb[a];
    }
    // drag that changes the relative velocity by more than kStiffChange: Newton, as the scalar
    // step (lanes the scalar step takes anyway need none)
    const int st = int(tc.drag != 0) & int(e_new > T(kStiffChange * kStiffChange) * e_r) &
                   (1 - (next->scalar[j] | flow->active[j]));
    stiff[j] = st;
    any_stiff |= st;
    norm_r[j] = e_r;
    next->scalar[j] |= flow->active[j];
#pragma GCC unroll 4
    for (int a = 0; a < 4; ++a) next->q[a][j] = q[a];
  }
  // stiff drag: Newton on R(dPi) = dPi - h (G_other + F_drag(xi(dPi))) - b_B (h a - dv), lanes
  // drop out as they converge (integrators.cpp split_deterministic_step). One Newton update of
  // lane j, written once for both loops below; returns whether j goes on.
  auto newton_lane = [&](int j) LRIGID_LANE_LAMBDA {
    const int act = stiff[j];
    T vr[3], w[3], lift[3];
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      vr[a] = next->vel[a][j] - ufs[a][j];
      w[a] = next->w[a][j];
    }
    const DragOut<T> drag = body_forces<T, Plate>(tc, vr, w, lift);
    // the Newton step -M (M + h J + b_B P)^-1 res, J the drag's stiffness here
    // (the Basset term: b_B times the linear velocity change M^-1 dPi)
    T res[6], x[6], dPi[6], ddv[6], Pn[6], xin[6];
#pragma GCC unroll 6
    for (int a = 0; a < 6; ++a) dPi[a] = dPL[a][j];
    mass_inv_times(tc.mass, dPi, ddv);
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      T b_dv = T(tc.basset_mass) * ddv[a];
      if constexpr (kDiagonal<Mass>)
        b_dv = T(tc.basset_mass) * T(tc.mass.Mi[a]) * dPi[a];  // (the diagonal step's rounding)
      res[a] = dPi[a] - G[a][j] - h * drag.f[a] + b_dv;
      res[3 + a] = dPi[3 + a] - h * drag.tq[a] - G[3 + a][j];
    }
    implicit_impulse(tc.mass, T(tc.basset_mass), drag, h, res, x);
#pragma GCC unroll 6
    for (int a = 0; a < 6; ++a) {
      dPi[a] -= x[a];
      Pn[a] = Pl[a][j] + dPi[a];
    }
    const T ufe_j[3] = {ufe[0][j], ufe[1][j], ufe[2][j]};
    velocity_of_impulse(tc.mass, tc.K, Pn, ufe_j, xin);
    const T conv = lane_energy_norm2(tc.mass, x);
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      dPL[a][j] = act ? dPi[a] : dPL[a][j];
      dPL[3 + a][j] = act ? dPi[3 + a] : dPL[3 + a][j];
      next->vel[a][j] = act ? xin[a] : next->vel[a][j];
      next->w[a][j] = act ? xin[3 + a] : next->w[a][j];
    }
    const int more = act & int(conv > T(kDragTol * kDragTol) * norm_r[j]);
    stiff[j] = more;
    return more;
  };
  if (tc.drag != 0 && any_stiff) {
    int idx[kBatch], m = 0;
    for (int j = 0; j < nw; ++j) {
      lanes->newton += uint64_t(stiff[j] != 0) & uint64_t(lanes->live[j]);
      idx[m] = j;
      m += stiff[j];
    }
    for (int it = 0; it < kDragMaxNewton && m > 0; ++it) {
      if (m * kSparseNewton > nw) {
        // many stiff lanes: every lane, vectorised, the others masked
        int any = 0;
LRIGID_IVDEP
        for (int j = 0; j < nw; ++j) any |= newton_lane(j);
        if (!any) break;
        m = 0;
        for (int j = 0; j < nw; ++j) {
          idx[m] = j;
          m += stiff[j];
        }
      } else {
        // a few: only those (a lane that needs Newton is rare and usually alone in its block;
        // the masked loop cost all kBatch lanes per iteration, 93 % of them idle on
        // scenes/art_flow_scales.json)
        int k = 0;
        for (int i = 0; i < m; ++i) {
          const int j = idx[i];
          idx[k] = j;
          k += newton_lane(j);
        }
        m = k;
      }
    }
  }
}

// Stage 4 of splitting, the positions by the trapezoidal rule on the world velocity:
// lanes.x, flow.V0, next (q, vel) => next.x and Vn, the world velocity at the end.
template <typename T, class Mass>
LRIGID_LANE void stage_positions(const StepConsts<Mass>& tc, const Lanes<T, Mass>* lanes,
                                 FlowBlock<T>* flow, NewState<T>* next, T (*Vn)[kBatch]) {
  const int nw = lanes->width;
  const T h = T(tc.h), hh = T(0.5 * tc.h);
  (void)h, (void)hh;
  // 4. x by the trapezoidal rule on the world velocity
LRIGID_IVDEP
  for (int j = 0; j < nw; ++j) {
    const T q[4] = {next->q[0][j], next->q[1][j], next->q[2][j], next->q[3][j]};
    const T v[3] = {next->vel[0][j], next->vel[1][j], next->vel[2][j]};
    T Vend[3];
    FrameOf<T, Mass> fr;
    fr.set(q);
    fr.to_world(v, Vend);
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      next->x[a][j] = lanes->x[a][j] + hh * (flow->V0[a][j] + Vend[a]);
      Vn[a][j] = Vend[a];
    }
  }
}

// Stage 3 of strang, the end of the flow: flow => next.q, next.vel, next.w, next.x by the
// trapezoidal rule over the flow; the field sampled at next.x (inside0: each lane's inside flag
// before). The second force half step (strang_force_lanes) follows on that sample.
template <typename T, class Mass>
LRIGID_LANE void stage_strang_flow_end(const StepConsts<Mass>& tc, Lanes<T, Mass>* lanes,
                                       FlowBlock<T>* flow, NewState<T>* next, T* inside0) {
  const int nw = lanes->width;
  const T hh = T(0.5 * tc.h);
LRIGID_IVDEP
  for (int j = 0; j < nw; ++j) {
    T q[4], ufb[3], v[3], w[3], Vend[3];
    FrameOf<T, Mass> fr;
    lane_flow_end(tc, lanes->q, flow->Y0, flow->Y, flow->uf, j, q, &fr, ufb, v, w);
    fr.to_world(v, Vend);
    next->scalar[j] |= flow->active[j];
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      next->x[a][j] = lanes->x[a][j] + hh * (flow->V0[a][j] + Vend[a]);
      next->vel[a][j] = v[a];
      next->w[a][j] = w[a];
    }
#pragma GCC unroll 4
    for (int a = 0; a < 4; ++a) next->q[a][j] = q[a];
  }
  for (int j = 0; j < nw; ++j) inside0[j] = tc.sample ? lanes->inside[j] : T(1);
  if (tc.sample) sample_lanes(tc, next->x, lanes, 0, nw);
}

// The splitting step (integrators.h): the first OU half step, the free Kirchhoff flow, the
// forces with the drag implicit, the positions, the second OU half step at the new positions
// (end_step). Lanes that are not kOk keep their state at the start of the step; landed: the lane
// is on or below the ground after the step. The body's shape chooses the force stage's kernels
// (with_switch, outside the loops).
template <typename T, class Mass>
LRIGID_MULTIVERSION void splitting_lanes(const StepConsts<Mass>& tc, Lanes<T, Mass>* lanes,
                                         uint64_t step, int* outcome, int* landed) {
  alignas(64) T z1[3][kBatch], z2[3][kBatch], Vn[3][kBatch];
  lane_normals(tc, *lanes, step, z1, z2);
  FlowBlock<T> flow;
  NewState<T> next;  // committed by end_step for the lanes whose step succeeded
  stage_turbulence_start(tc, lanes, z1, &flow, &next);
  stage_flow_begin(tc, lanes, lanes->v, lanes->w, T(0), &flow);
  stage_kirchhoff_flow(tc, lanes, &flow, &next);
  by_shape<Mass>(tc.plate, [&](auto plate) LRIGID_LANE_LAMBDA {
    stage_forces_implicit<T, decltype(plate)::value>(tc, lanes, &flow, &next);
  });
  stage_positions(tc, lanes, &flow, &next, Vn);
  end_step<T>(tc, z2, Vn, &next, lanes, outcome, landed);
}

// The strang step (integrators.h): the first OU half step and force half step, the free
// Kirchhoff flow, the positions, the second force half step and OU half step at the new
// positions.
template <typename T, class Mass>
LRIGID_MULTIVERSION void strang_lanes(const StepConsts<Mass>& tc, Lanes<T, Mass>* lanes, uint64_t step,
                                      int* outcome, int* landed) {
  alignas(64) T z1[3][kBatch], z2[3][kBatch], Vn[3][kBatch], inside0[kBatch];
  lane_normals(tc, *lanes, step, z1, z2);
  FlowBlock<T> flow;
  NewState<T> next;
  stage_turbulence_start(tc, lanes, z1, &flow, &next);
  by_shape<Mass>(tc.plate, [&](auto plate) LRIGID_LANE_LAMBDA {
    strang_force_lanes<T, decltype(plate)::value>(tc, lanes, lanes->q, lanes->v, lanes->w, &next,
                                                  Vn);
  });
  stage_flow_begin(tc, lanes, next.vel, next.w, T(1), &flow);
  stage_kirchhoff_flow(tc, lanes, &flow, &next);
  stage_strang_flow_end(tc, lanes, &flow, &next, inside0);
  by_shape<Mass>(tc.plate, [&](auto plate) LRIGID_LANE_LAMBDA {
    strang_force_lanes<T, decltype(plate)::value>(tc, lanes, next.q, next.vel, next.w, &next, Vn);
  });
  end_step<T>(tc, z2, Vn, &next, lanes, outcome, landed, inside0);
}

}  // namespace
}  // namespace lrigid
#include "integrate/rigid_batch_explicit.h"  // euler and rk4
namespace lrigid {
namespace {  // NOLINT(build/namespaces)

template <typename T, class Mass>
BlockStats advance(const Model& model, const BodyType& type, State* state, const uint32_t* body,
                   int count, uint64_t first, uint64_t last, StretchSweep* sweep) {
  const StepConsts<Mass> tc = make_consts<Mass>(model, type);
  const bool unsteady = tc.grid && model.field.frame_count() > 1;
  auto step = [&](auto plate, Lanes<T, Mass>* lanes, uint64_t s, int* outcome, int* landed) {
    constexpr bool P = decltype(plate)::value && !kIsotropic<Mass>;
    if (tc.scheme == Integrator::Euler) return euler_lanes<T, P>(tc, lanes, s, outcome, landed);
    if (tc.scheme == Integrator::RK4)
      return rk4_lanes<T, P>(tc, rk4_frames(model, unsteady, s), lanes, s, outcome, landed);
    if (tc.strang)
      strang_lanes<T>(tc, lanes, s, outcome, landed);
    else
      splitting_lanes<T>(tc, lanes, s, outcome, landed);
  };
  return drive_block<T, Lanes<T, Mass>>(model, type, tc, tc.plate, state, body, count, first, last,
                                        step, sweep);
}

}  // namespace
}  // namespace lrigid
