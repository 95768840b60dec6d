#include "contact/events.h"

#include <algorithm>
#include <cmath>

namespace lrigid {

namespace {

// how far the body reaches below its centre, m (ground_reach)
double reach_down(const BodyType& type, const Quat& q) {
  const Mat3 R = q.toRotationMatrix();
  const double r[3] = {R(2, 0), R(2, 1), R(2, 2)};
  return ground_reach(is_round(type), r, type.half_extents.data(), type.r_cob.data());
}

// the height of the body's lowest point above the ground, m
double ground_clearance(const Model& m, const BodyType& type, const Vec3& x, const Quat& q) {
  return x.z() - reach_down(type, q) - m.ground_z;
}

const char* const kLeftTheGrid = "left the grid";

// The body's world velocity dx/dt: R v, plus the turbulent velocity u' for the body turbulence
// model (which carries the body directly; for the seen model u' is the fluid's and acts through
// the forces)
Vec3 world_velocity(const Model& m, const BodyType& type, const BodyState& b) {
  Vec3 velocity = b.q * b.v;
  if (type.effects.has(Effect::Turbulence) && m.turbulence_model == TurbulenceModel::Body)
    velocity += b.u_seen;
  return velocity;
}

// where one more step would take the body
Vec3 predicted_position(const Model& m, const BodyType& type, const BodyState& b) {
  return b.x + m.dt * world_velocity(m, type, b);
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

bool touches_ground(const Model& m, const BodyType& type, const BodyState& s) {
  return s.x.z() - reach_down(type, s.q) <= m.ground_z;
}

double locate_touchdown(const Model& m, const BodyType& type, const BodyState& a,
                        const BodyState& b, BodyState* at) {
  *at = b;
  if (ground_clearance(m, type, a.x, a.q) <= 0) return m.dt;
  return locate_event(
      m, type, a, b, m.dt,
      [&](const Vec3& x, const Quat& q) { return ground_clearance(m, type, x, q); }, at);
}

double locate_event(const Model& m, const BodyType& type, const BodyState& a, const BodyState& b,
                    double h, const std::function<double(const Vec3&, const Quat&)>& gap,
                    BodyState* at) {
  *at = b;
  const Vec3 va = h * world_velocity(m, type, a), vb = h * world_velocity(m, type, b);
  // quaternions as 4-vectors on the same hemisphere, with their rates times h
  const Eigen::Vector4d qa = a.q.coeffs();
  Eigen::Vector4d qb = b.q.coeffs();
  const double sign = qa.dot(qb) < 0 ? -1.0 : 1.0;
  qb *= sign;
  const auto rate = [h](const Quat& q, const Vec3& w) {
    return Eigen::Vector4d((q * Quat(0, w.x(), w.y(), w.z())).coeffs() * (0.5 * h));
  };
  const Eigen::Vector4d ra = rate(a.q, a.w), rb = sign * rate(b.q, b.w);
  // the state at fraction u of the step (cubic Hermite basis)
  const auto state = [&](double u, Vec3* x, Quat* q) {
    const double u2 = u * u, u3 = u2 * u;
    const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2,
                 h11 = u3 - u2;
    *x = h00 * a.x + h10 * va + h01 * b.x + h11 * vb;
    Eigen::Vector4d c = h00 * qa + h10 * ra + h01 * qb + h11 * rb;
    *q = Quat(c.normalized());  // Eigen's coefficient order (x, y, z, w) both ways
  };
  const auto clearance = [&](double u) {
    Vec3 x;
    Quat q;
    state(u, &x, &q);
    return gap(x, q);
  };
  // the first sign change on a few sub-intervals (the interpolant may dip below and come back),
  // then regula falsi (Illinois) inside it
  constexpr int kScan = 8;
  double lo = 0, glo = clearance(0), hi = 1, ghi = 0;
  for (int k = 1; k <= kScan; ++k) {
    const double u = double(k) / kScan, g = k == kScan ? std::min(clearance(u), 0.0) : clearance(u);
    if (g <= 0) {
      hi = u, ghi = g;
      break;
    }
    lo = u, glo = g;
  }
  int side = 0;
  for (int it = 0; it < 100 && hi - lo > 1e-14; ++it) {
    const double u = ghi < glo ? lo + (hi - lo) * glo / (glo - ghi) : 0.5 * (lo + hi);
    const double g = clearance(u);
    if (g > 0) {
      lo = u, glo = g;
      if (side == -1) ghi *= 0.5;
      side = -1;
    } else {
      hi = u, ghi = g;
      if (side == 1) glo *= 0.5;
      side = 1;
      if (g == 0) break;
    }
  }
  state(hi, &at->x, &at->q);
  at->v = (1 - hi) * a.v + hi * b.v;
  at->w = (1 - hi) * a.w + hi * b.w;
  at->u_seen = (1 - hi) * a.u_seen + hi * b.u_seen;
  at->history = a.history;
  return hi * h;
}

void record_touchdown(const Model& m, const BodyType& type, size_t i, double t, const BodyState& a,
                      const BodyState& b, State* st) {
  BodyState at;
  st->t_touch[i] = t + locate_touchdown(m, type, a, b, &at);
  st->x_touch[i] = at.x;
}

bool heads_into_ground(const Model& m, const BodyType& type, const BodyState& b) {
  if (!m.ground_collides()) return false;
  BodyState next = b;
  next.x = predicted_position(m, type, b);
  return touches_ground(m, type, next);
}

BodyStatus stop_body(const Model& m, const BodyType& type, size_t i, double t, StepOutcome out,
                     const std::string& failure, BodyState* bp, State* st) {
  const BodyState& b = *bp;
  if (out == StepOutcome::Exited && m.has_ground && !m.ground_collides()) {
    // a step that would cross the ground (often also the grid's bottom) lands the body, even
    // when a stage of it sampled below the grid first: where its straight motion meets the
    // ground (the step itself is not known)
    BodyState next = b;
    next.x = predicted_position(m, type, b);
    if (touches_ground(m, type, next)) {
      next.w.setZero();  // the orientation held, as in the prediction
      BodyState still = b;
      still.w.setZero();
      st->status[i] = BodyStatus::Landed;
      st->t_stop[i] = t + locate_touchdown(m, type, still, next, bp);  // (b is *bp)
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
