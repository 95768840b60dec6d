#include "integrate/stops.h"

#include <cmath>

namespace lrigid {

bool touches_ground(const Model& m, const BodyType& type, const BodyState& s) {
  const Mat3 R = s.q.toRotationMatrix();
  double reach = 0;
  for (int a = 0; a < 3; ++a) reach += std::abs(R(2, a)) * type.half_extents[a];
  return s.x.z() - reach <= m.ground_z;
}

namespace {

const char* const kLeftTheGrid = "left the grid";

// where one more step would take the body: its world velocity R v, plus the turbulent velocity
// u' for the body turbulence model (which carries the body directly; for the seen model u' is
// the fluid's and acts through the forces)
Vec3 predicted_position(const Model& m, const BodyType& type, const BodyState& b) {
  Vec3 velocity = b.q * b.v;
  if (type.effects.has(Effect::Turbulence) && m.turbulence_model == TurbulenceModel::Body)
    velocity += b.u_seen;
  return b.x + m.dt * velocity;
}

// where a body that could not be sampled went: where one more step would take it
std::string exit_reason(const Model& m, const BodyType& type, const BodyState& b) {
  // colliding walls keep bodies out of the solids: a body still on the fluid's side of every
  // wall (positive wall distance) left through the grid's open boundary, whatever one more
  // step with its velocity predicts (a batched step's turbulence or acceleration can carry it
  // past the edge when its velocity alone does not)
  double d;
  Vec3 grad;
  if (m.walls_collide() && m.field.wall_distance(b.x, 0.0, &d, &grad) && d > 0)
    return kLeftTheGrid;
  const Vec3 next = predicted_position(m, type, b);
  if (m.field.in_box(next) && m.field.in_box(b.x))
    return "hit a solid: no valid grid point around it (a wall, a building, an obstacle)";
  return kLeftTheGrid;
}

}  // namespace

bool heads_into_ground(const Model& m, const BodyType& type, const BodyState& b) {
  if (!m.ground_collides()) return false;
  BodyState next = b;
  next.x = predicted_position(m, type, b);
  return touches_ground(m, type, next);
}

BodyStatus stop_body(const Model& m, const BodyType& type, size_t i, double t, StepOutcome out,
                     const std::string& failure, const BodyState& b, State* st) {
  if (out == StepOutcome::Exited && m.has_ground && !m.ground_collides()) {
    // a step that would cross the ground (often also the grid's bottom) lands the body, even
    // when a stage of it sampled below the grid first
    BodyState next = b;
    next.x = predicted_position(m, type, b);
    if (touches_ground(m, type, next)) {
      st->status[i] = BodyStatus::Landed;
      st->t_stop[i] = t + m.dt;
      return BodyStatus::Landed;
    }
  }
  const bool exited = out == StepOutcome::Exited;
  st->status[i] = exited ? BodyStatus::Exited : BodyStatus::Failed;
  st->t_stop[i] = t;
  st->reason[i] = exited ? exit_reason(m, type, b) : failure;
  if (exited && m.outside == OutsideMode::Remove && !st->hidden.empty() &&
      st->reason[i] == kLeftTheGrid)
    st->hidden[i] = 1;
  return st->status[i];
}

}  // namespace lrigid
