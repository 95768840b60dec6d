#include "integrate/impacts.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "contact/events.h"
#include "contact/solver.h"

namespace lrigid {

bool can_split_at_impact(const Model& model, const BodyType& type) {
  return !type.plan.basset &&
         !(type.effects.has(Effect::Turbulence) &&
           model.turbulence_model == TurbulenceModel::Body);
}

namespace {

// The step from a (at time t) taken again with the impact's impulses at t + tau: the points
// within a nanometre of a surface there (what touched first) get contact_resolve's impulses.
// Counts the impact and a first ground touchdown. False (a and st untouched) when the step
// fails or nothing touches at t + tau.
bool split_at_impact(const Model& model, const BodyType& type, size_t i, double t, double tau,
                     BodyState* a, State* st) {
  bool hit = false, ground = false;
  Vec3 x_hit = a->x;
  const SplitAt impulse = [&](double t_hit, BodyState* s) {
    const Mat3 R = s->q.toRotationMatrix();
    Touching c;
    const double slack = std::max(0.0, surface_gap(model, type, s->x, R, t_hit)) + 1e-9;
    gather(model, type, *s, R, t_hit, 0.0, &c, nullptr, slack);
    if (c.count == 0) return;
    double dx[3];
    contact_resolve(*type.contact, type.M_inv.data(), s->v.data(), s->w.data(), c.count, c.r,
                    c.n, c.depth, kContactPasses, dx, type.M.data());
    hit = true;
    ground = c.ground;
    x_hit = s->x;
  };
  BodyState s = *a;
  std::string reason;
  const uint64_t step = static_cast<uint64_t>(std::llround(t / model.dt));
  if (step_body_split(model, type, static_cast<uint32_t>(i), step, t, tau, impulse, &s,
                      &reason) != StepOutcome::Ok ||
      !hit)
    return false;
  ++st->impacts[i];
  if (ground && std::isnan(st->t_touch[i])) {
    st->t_touch[i] = t + tau;
    st->x_touch[i] = x_hit;
  }
  *a = s;
  return true;
}

}  // namespace

bool impact_inside_step(const Model& model, const BodyType& type, size_t i, double t,
                        const BodyState& a, BodyState* b, State* st) {
  if (!can_split_at_impact(model, type)) return false;
  const double h = model.dt, t_end = t + h;
  auto gap = [&](const Vec3& x, const Quat& q) {
    return surface_gap(model, type, x, q.toRotationMatrix(), t_end);
  };
  if (!(gap(a.x, a.q) > 0)) return false;  // it touched at the start: no event inside
  BodyState at;
  const double tau = locate_event(model, type, a, *b, h, gap, &at);
  if (!(tau > 0) || !(tau < h * (1 - 1e-9))) return false;
  BodyState s = a;
  s.history = b->history;
  if (!split_at_impact(model, type, i, t, tau, &s, st)) return false;
  *b = s;
  return true;
}

bool impact_through_floor(const Model& model, const BodyType& type, size_t i, double t,
                          BodyState* a, State* st) {
  if (!model.ground_collides() || !can_split_at_impact(model, type)) return false;
  const double h = model.dt, t_end = t + h;
  // the gap after the deterministic part to t + u h; NaN where that part left the fluid
  // (through the floor: below, the search bisects)
  auto gap = [&](double u) {
    BodyState s = *a;
    if (deterministic_substep(model, type, t, u * h, &s) != StepOutcome::Ok) return double(NAN);
    return surface_gap(model, type, s.x, s.q.toRotationMatrix(), t_end);
  };
  double lo = 0, glo = surface_gap(model, type, a->x, a->q.toRotationMatrix(), t_end);
  if (!(glo > 0)) return false;
  double hi = 1, ghi = gap(1.0);
  if (ghi > 0) return false;  // the deterministic part alone does not reach a surface
  // Illinois regula falsi where both ends have a gap, bisection while the upper end left
  int side = 0;
  for (int it = 0; it < 80 && hi - lo > 1e-12; ++it) {
    const bool falsi = !std::isnan(ghi);
    const double u = falsi ? lo + (hi - lo) * glo / (glo - ghi) : 0.5 * (lo + hi);
    const double g = gap(u);
    if (g > 0) {
      lo = u, glo = g;
      if (side == -1 && falsi) ghi *= 0.5;
      side = -1;
    } else {
      hi = u, ghi = g;  // g <= 0 or NaN
      if (side == 1) glo *= 0.5;
      side = 1;
      if (g == 0) break;
    }
  }
  if (!(hi < 1 - 1e-9)) return false;
  return split_at_impact(model, type, i, t, hi * h, a, st);
}

namespace {

// What contact_after_step hands the contact pass: impact_inside_step on the step from start.
struct StepStart {
  const Model* model;
  const BodyType* type;
  size_t i;
  double t;  // the step's start time
  const BodyState* start;
};
bool take_impact(const void* ctx, BodyState* b, State* st) {
  const StepStart& s = *static_cast<const StepStart*>(ctx);
  return impact_inside_step(*s.model, *s.type, s.i, s.t, *s.start, b, st);
}

}  // namespace

bool contact_after_step(const Model& model, const BodyType& type, size_t i, double t_end,
                        BodyState* b, State* st, WallClearance* clearance,
                        const BodyState* start) {
  if (!start) return contact_pass(model, type, i, t_end, b, st, clearance);
  const StepStart at{&model, &type, i, t_end - model.dt, start};
  const InStepImpact impact{take_impact, &at};
  return contact_pass(model, type, i, t_end, b, st, clearance, &impact);
}

}  // namespace lrigid
