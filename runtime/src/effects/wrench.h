// A force and a torque about the centre of mass, body frame: (F; T) in N and N m.
#pragma once
#include "util/types.h"

namespace lrigid {

using Wrench = Vec6;

inline Wrench make_wrench(const Vec3& force, const Vec3& torque) {
  Wrench w;
  w << force, torque;
  return w;
}

// Kirchhoff's gyroscopic terms for generalized momentum (P; L) moving with (v; w):
// (w x P; w x L + v x P). Lamb §124; Weissmann & Pinkall 2012.
inline Vec6 kirchhoff_gyro(const Vec3& v, const Vec3& w, const Vec6& momentum) {
  const Vec3 P = momentum.head<3>(), L = momentum.tail<3>();
  Vec6 g;
  g << w.cross(P), w.cross(L) + v.cross(P);
  return g;
}

}  // namespace lrigid
