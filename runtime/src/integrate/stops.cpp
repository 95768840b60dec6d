#include "integrate/stops.h"

#include <cmath>

namespace lrigid {

bool touches_ground(const Model& m, const BodyType& type, const BodyState& s) {
  const Mat3 R = s.q.toRotationMatrix();
  double reach = 0;
  for (int a = 0; a < 3; ++a) reach += std::abs(R(2, a)) * type.half_extents[a];
  return s.x.z() - reach <= m.ground_z;
}

Vec3 predicted_position(const Model& m, const BodyType& type, const BodyState& b) {
  Vec3 velocity = b.q * b.v;
  if (type.effects.has(Effect::Turbulence) && m.turbulence_model == TurbulenceModel::Body)
    velocity += b.u_seen;
  return b.x + m.dt * velocity;
}

std::string exit_reason(const Model& m, const BodyType& type, const BodyState& b) {
  const Vec3 next = predicted_position(m, type, b);
  if (m.field.in_box(next) && m.field.in_box(b.x))
    return "hit a solid: no valid grid point around it (a wall, a building, an obstacle)";
  return "left the grid";
}

}  // namespace lrigid
