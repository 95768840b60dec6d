#include "contact/pass.h"

#include <algorithm>
#include <cmath>

#include "contact/sleep.h"
#include "contact/solver.h"

namespace lrigid {

namespace {

// The weight of the step's end velocity in its position update: x += h/2 (V0 + V1) for the
// splitting step; the strang step moves x by h/2 times the velocities after its first force half
// step and before its second, the same for forces constant over the step (a body lying on a
// surface); about that for rk4; explicit Euler moves x by h V0 only.
double end_velocity_weight(const Model& m) {
  return m.integrator == Integrator::Euler ? 0.0 : 0.5;
}

// the fastest approach (m/s) of c's touching points, the body moving with (v, w)
double fastest_approach(const Touching& c, const Vec3& v, const Vec3& w) {
  double approach = 0;
  for (int p = 0; p < c.count; ++p) {
    const Vec3 rb(c.r[3 * p], c.r[3 * p + 1], c.r[3 * p + 2]);
    const Vec3 nb(c.n[3 * p], c.n[3 * p + 1], c.n[3 * p + 2]);
    approach = std::max(approach, -(v + w.cross(rb)).dot(nb));
  }
  return approach;
}

}  // namespace

bool contact_pass(const Model& model, const BodyType& type, size_t i, double t_end, BodyState* b,
                  State* st, WallClearance* clearance, const InStepImpact* impact) {
  const double h = model.dt;
  Mat3 R = b->q.toRotationMatrix();
  Touching c;
  // with the speculative points of the next step: a body lying on a surface, whatever its tilt
  // within what a step closes, is held by all of its near points at once
  gather(model, type, *b, R, t_end, 0.0, &c, clearance, 0.0, h);
  if (c.touching == 0) {
    mark_flying(st, i);
    return false;
  }
  // the fastest approach of a touching point: an impact (a contact event) when it is above the
  // resting threshold, or when the body was flying
  const double approach = fastest_approach(c, b->v, b->w);
  if (impact && st->contact[i] == ContactState::Flying && approach > model.rest_speed &&
      impact->take(impact->ctx, b, st)) {
    // the impact was taken where it happened, inside the step (and counted); what the step's
    // end touches now (a body that did not bounce clear) is resolved as any contact
    st->contact[i] = ContactState::Sliding;
    R = b->q.toRotationMatrix();
    c = Touching{};
    gather(model, type, *b, R, t_end, 0.0, &c, nullptr, 0.0, h);
    if (c.touching == 0) {
      mark_flying(st, i);
      return false;
    }
  }
  const Vec3 v0 = b->v, w0 = b->w;
  double dx[3];
  // M^-1 is symmetric: its column-major data is its row-major data
  contact_resolve(*type.contact, type.M_inv.data(), b->v.data(), b->w.data(), c.count, c.r, c.n,
                  c.depth, kContactPasses, dx, type.M.data(), h);
  const double cw = end_velocity_weight(model) * h;
  const Vec3 dv = b->v - v0, dw = b->w - w0;
  // the position update with the velocity after the impulse, then what remains of the deepest
  // penetration
  b->x += cw * (R * dv);
  b->q = rotate_body(b->q, cw * dw);
  // the deepest point's normal (body frame): the surface the body lies on
  Vec3 base_n = Vec3::UnitZ();
  for (int p = 0, deepest = -1; p < c.count; ++p)
    if (deepest < 0 || c.depth[p] > c.depth[deepest])
      deepest = p, base_n = Vec3(c.n[3 * p], c.n[3 * p + 1], c.n[3 * p + 2]);
  double worst = 0;
  Vec3 worst_n = Vec3::Zero();
  for (int p = 0; p < c.count; ++p) {
    const Vec3 rb(c.r[3 * p], c.r[3 * p + 1], c.r[3 * p + 2]);
    const Vec3 nb(c.n[3 * p], c.n[3 * p + 1], c.n[3 * p + 2]);
    const double left = c.depth[p] - cw * (dv + dw.cross(rb)).dot(nb);
    if (left > worst) worst = left, worst_n = nb;
  }
  if (worst > 0) b->x += R * (worst * worst_n);
  // what the body does now: resting when every touching point (nearly) stands still
  const double still = kRestFraction * model.rest_speed;
  bool rests = true;
  for (int p = 0; p < c.count && rests; ++p) {
    const Vec3 rb(c.r[3 * p], c.r[3 * p + 1], c.r[3 * p + 2]);
    rests = (b->v + b->w.cross(rb)).norm() < still;
  }
  rests = rests && b->w.norm() * type.reach < still;
  if (st->contact[i] == ContactState::Flying && approach > model.rest_speed) ++st->impacts[i];
  if (c.ground && std::isnan(st->t_touch[i])) {
    st->t_touch[i] = t_end;
    st->x_touch[i] = b->x;
  }
  st->contact[i] = rests ? ContactState::Resting : ContactState::Sliding;
  st->rest_steps[i] = rests ? st->rest_steps[i] + 1 : 0;
  if (rests && double(st->rest_steps[i]) * h >= model.sleep_time) {
    // it sleeps only where the flow as it is cannot move it: otherwise it stays awake (and is
    // asked again after another sleep_time of rest); a gust watch wakes it when a gust could
    if (!fall_asleep(model, type, i, t_end, R * base_n, b, st)) {
      st->rest_steps[i] = 0;
      return false;
    }
    return true;
  }
  return false;
}

bool speculative_ground_contact(const Model& model, const BodyType& type, BodyState* b) {
  if (!model.ground_collides()) return false;
  const Mat3 R = b->q.toRotationMatrix();
  Touching c;
  gather(model, type, *b, R, 0.0, model.dt, &c);
  if (c.count == 0 || !c.ground) return false;
  double dx[3];
  return contact_resolve(*type.contact, type.M_inv.data(), b->v.data(), b->w.data(), c.count,
                         c.r, c.n, c.depth, kContactPasses, dx, type.M.data()) > 0;
}

}  // namespace lrigid
