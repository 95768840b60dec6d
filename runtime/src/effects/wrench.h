// A force and a torque about the centre of mass, body frame: (F; T) in N and N m.
#pragma once
#include "util/lane.h"
#include "util/types.h"

namespace lrigid {

using Wrench = Vec6;

inline Wrench make_wrench(const Vec3& force, const Vec3& torque) {
  Wrench w;
  w << force, torque;
  return w;
}

// Kirchhoff's gyroscopic terms for generalized momentum (P; L) moving with (v; w):
// (w x P; w x L + v x P). Lamb §124; Weissmann & Pinkall 2012. The kernel, written once (the
// scalar step's kirchhoff_gyro and the batched loops call it).
template <typename T>
LRIGID_LANE void kirchhoff_gyro_kernel(const T* v, const T* w, const T* P, const T* L, T* g) {
  T b[3], c[3];
  cross3(w, P, g);
  cross3(w, L, b);
  cross3(v, P, c);
#pragma GCC unroll 3
  for (int i = 0; i < 3; ++i) g[3 + i] = b[i] + c[i];
}

// A body whose centre of mass is off its volume centroid (BodyType::r_cob = r, the centroid from
// the centre of mass, body frame, m): the fluid's forces and the buoyancy act at the centroid,
// which moves at u + w x r relative to the fluid, and a force f there turns the body about its
// centre of mass by r x f. The kernels, written once (the scalar terms: effects/drag.cpp,
// lift.cpp, magnus.h, buoyancy.h; the batched loops: integrate/rigid_batch_step.h).
template <typename T>
LRIGID_LANE void centroid_velocity_kernel(const T* r, const T* u, const T* w, T* uc) {
  T wr[3];
  cross3(w, r, wr);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) uc[a] = u[a] + wr[a];
}
template <typename T>
LRIGID_LANE void add_offset_torque_kernel(const T* r, const T* f, T* tq) {
  T rf[3];
  cross3(r, f, rf);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) tq[a] += rf[a];
}

// the centroid's velocity relative to the fluid, u the centre of mass's, w the spin
inline Vec3 centroid_velocity(const Vec3& r, const Vec3& u, const Vec3& w) {
  Vec3 uc;
  centroid_velocity_kernel(r.data(), u.data(), w.data(), uc.data());
  return uc;
}

// a force f at the centroid with a torque about it: the wrench about the centre of mass
inline Wrench wrench_at_centroid(const Vec3& r, const Vec3& f, Vec3 torque = Vec3::Zero()) {
  add_offset_torque_kernel(r.data(), f.data(), torque.data());
  return make_wrench(f, torque);
}

inline Vec6 kirchhoff_gyro(const Vec3& v, const Vec3& w, const Vec6& momentum) {
  Vec6 g;
  kirchhoff_gyro_kernel(v.data(), w.data(), momentum.data(), momentum.data() + 3, g.data());
  return g;
}

}  // namespace lrigid
