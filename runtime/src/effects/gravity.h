// Gravity: the weight m g acts at the centre of mass (the body frame's origin): no torque.
#pragma once
#include "effects/context.h"
#include "effects/wrench.h"
#include "model/model.h"

namespace lrigid {

// g_body: gravity in the body frame, m/s^2
inline Wrench gravity_wrench(const BodyType& type, const Vec3& g_body) {
  return make_wrench(type.mass * g_body, Vec3::Zero());
}

// the scalar step's term (the registry's row)
inline Vec6 gravity_term(const EffectContext& c) { return gravity_wrench(*c.type, c.g_body); }

}  // namespace lrigid
