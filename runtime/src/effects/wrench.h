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

inline Vec6 kirchhoff_gyro(const Vec3& v, const Vec3& w, const Vec6& momentum) {
  Vec6 g;
  kirchhoff_gyro_kernel(v.data(), w.data(), momentum.data(), momentum.data() + 3, g.data());
  return g;
}

}  // namespace lrigid
