#include "integrate/contacts.h"

#include <algorithm>
#include <cmath>

#include "effects/contact.h"
#include "effects/turbulence.h"
#include "integrate/dynamics.h"
#include "integrate/stops.h"
#include "util/rng.h"

namespace lrigid {

namespace {

// The touching points of one body: body-frame offsets from the centre of mass, body-frame unit
// normals (from the surface into the fluid) and depths (m; >= 0 for a point that touches, < 0
// for a speculative point: minus its gap to the surface, which it closes within the next step).
struct Touching {
  double r[3 * kContactMaxPoints];
  double n[3 * kContactMaxPoints];
  double depth[kContactMaxPoints];
  int count = 0;
  int touching = 0;     // of them, the points that touch (depth >= 0)
  bool ground = false;  // a touching point is on the ground
  void add(const Vec3& rb, const Vec3& nb, double d) {
    if (count == kContactMaxPoints) return;
    for (int a = 0; a < 3; ++a) r[3 * count + a] = rb[a], n[3 * count + a] = nb[a];
    touching += d >= 0;
    depth[count++] = d;
  }
};

// The shape's points that reach a surface, with the positions `ahead` seconds ahead at the
// points' current velocities (0: where they are). slack >= 0: points up to slack (m) off the
// surface count too, with depth 0 (an impact located inside a step: the points that touch there).
// spec > 0 (s): the points off the surface that approach it slower than Model::rest_speed and
// reach it within spec at their velocity count too, as speculative points (depth: minus the
// gap): a body lying on a surface tilted by less than what one step closes then has its other
// edge in the contact problem too (docs/contacts.md "Speculative points").
void gather(const Model& m, const BodyType& type, const BodyState& b, const Mat3& R, double t,
            double ahead, Touching* out, WallClearance* clearance = nullptr, double slack = 0,
            double spec = 0) {
  const ContactParams& k = *type.contact;
  const Mat3 Rt = R.transpose();
  // how far off a surface a speculative point can be: spec times the slowest approach of an
  // impact (faster points are impacts, taken where they happen)
  const double reach_spec = spec > 0 ? spec * m.rest_speed : 0.0;
  // a point at depth d < 0 (off the surface) approaching it at `approach` m/s: speculative
  auto speculative = [&](double d, double approach) {
    return d < 0 && approach <= m.rest_speed && d + spec * approach >= 0;
  };
  // points on the ground need no wall check: the grid's floor is the ground, twice the same
  // constraint would only cost
  uint8_t on_ground[kContactMaxPoints * 4] = {};
  // (-> Vec3: an Eigen expression returned by a lambda would refer to the cross product's
  // temporary after it is gone, and ground_depth read that stack garbage, times 0 when not ahead:
  // a NaN there dropped a touching point at random)
  auto point_velocity = [&](const Vec3& rb) -> Vec3 { return R * (b.v + b.w.cross(rb)); };
  if (m.ground_collides() && b.x.z() - type.reach <= m.ground_z + slack + reach_spec) {
    const Vec3 ez(0, 0, 1);
    // only the point's height: the last row of R (and its velocity only when looking ahead)
    const Vec3 rz = R.row(2).transpose();
    auto ground_depth = [&](const Vec3& rb) {
      double z = b.x.z() + rz.dot(rb);
      if (ahead != 0) z += ahead * rz.dot(b.v + b.w.cross(rb));
      return m.ground_z - z;
    };
    if (k.support) {
      const Vec3 nb = Rt * ez;
      Vec3 rb;
      ellipsoid_support_point(k, nb.data(), rb.data());
      const double d = ground_depth(rb);
      if (d >= -slack)
        out->add(rb, nb, std::max(d, 0.0)), out->ground = true;
      else if (spec > 0 && speculative(d, -point_velocity(rb).z()))
        out->add(rb, nb, d);
    } else {
      const Vec3 nb = Rt * ez;
      for (size_t p = 0; p < k.count(); ++p) {
        // a box edge's point between two corners on the ground: on it too, and implied by them
        // (the depth and the normal velocity are linear along the edge)
        if (k.on_edge(p) && on_ground[k.edge_ends[2 * p]] && on_ground[k.edge_ends[2 * p + 1]]) {
          if (p < sizeof on_ground) on_ground[p] = 1;
          continue;
        }
        const Vec3 rb(k.points[3 * p], k.points[3 * p + 1], k.points[3 * p + 2]);
        const double d = ground_depth(rb);
        if (d >= -slack) {
          out->add(rb, nb, std::max(d, 0.0));
          out->ground = true;
          if (p < sizeof on_ground) on_ground[p] = 1;
        } else if (spec > 0 && speculative(d, -point_velocity(rb).z())) {
          // (an edge's point between a touching and a speculative corner, or two speculative
          // ones, is implied by them as well: the gap too is linear along the edge)
          out->add(rb, nb, d);
          if (p < sizeof on_ground) on_ground[p] = 1;
        }
      }
    }
  }
  if (!m.walls_collide()) return;
  // a body near a colliding ground that is the grid's floor, away from every other wall: the
  // ground above was the only surface it could touch (touching or not)
  if (m.ground_collides() &&
      m.field.only_floor_near(b.x, type.reach + slack + reach_spec, m.ground_z, t))
    return;
  if (clearance && clearance->radius >= 0 && (b.x - clearance->x).norm() < clearance->radius)
    return;
  double dc;
  Vec3 gc;
  const bool inside = m.field.wall_distance(b.x, t, &dc, &gc);
  if (clearance) {
    clearance->x = b.x;
    clearance->radius = inside ? (dc - type.reach - reach_spec) / std::sqrt(3.0) : -1;
  }
  if (!inside || dc > type.reach + slack + reach_spec) return;
  // a point touches where the wall distance is <= 0; its normal is the distance's gradient
  auto wall = [&](const Vec3& rb, Vec3* nw) {
    Vec3 p = b.x + R * rb;
    if (ahead != 0) p += ahead * point_velocity(rb);
    double d;
    Vec3 g;
    if (!m.field.wall_distance(p, t, &d, &g) || d > slack + reach_spec) return -HUGE_VAL;
    const double gn = g.norm();
    if (!(gn > 0)) return -HUGE_VAL;
    *nw = g / gn;
    return -d;
  };
  // a wall's point at depth d (< -slack: off the wall), normal nw (world): speculative?
  auto wall_speculative = [&](const Vec3& rb, double d, const Vec3& nw) {
    return spec > 0 && d > -HUGE_VAL && speculative(d, -point_velocity(rb).dot(nw));
  };
  Vec3 nw;
  if (k.support) {
    // the support point against the wall's normal at the centre
    const double gn = gc.norm();
    if (!(gn > 0)) return;
    // the grid's floor under a body already on the ground: the same constraint
    if (out->ground && gc.z() > 0.99 * gn) return;
    const Vec3 nb = Rt * (gc / gn);
    Vec3 rb;
    ellipsoid_support_point(k, nb.data(), rb.data());
    const double d = wall(rb, &nw);
    if (d >= -slack)
      out->add(rb, Rt * nw, std::max(d, 0.0));
    else if (wall_speculative(rb, d, nw))
      out->add(rb, Rt * nw, d);
  } else {
    for (size_t p = 0; p < k.count(); ++p) {
      if (p < sizeof on_ground && on_ground[p]) continue;
      const Vec3 rb(k.points[3 * p], k.points[3 * p + 1], k.points[3 * p + 2]);
      const double d = wall(rb, &nw);
      if (d >= -slack)
        out->add(rb, Rt * nw, std::max(d, 0.0));
      else if (wall_speculative(rb, d, nw))
        out->add(rb, Rt * nw, d);
    }
  }
}

// The smallest signed distance (m; > 0: apart) of the shape's contact points (a box's corners),
// the body at x with rotation R at time t, to the colliding surfaces: the ground plane's height
// and the wall distance. Far from the walls (the centre's wall distance beyond the body's reach)
// the walls count with that distance less the reach, a bound that keeps the function continuous
// enough for a root finder.
double surface_gap(const Model& m, const BodyType& type, const Vec3& x, const Mat3& R, double t) {
  const ContactParams& k = *type.contact;
  const Mat3 Rt = R.transpose();
  double gap = HUGE_VAL;
  auto point = [&](size_t p) {
    return Vec3(k.points[3 * p], k.points[3 * p + 1], k.points[3 * p + 2]);
  };
  // a box edge's inner points lie between its corners: on the ground never lower than both; on
  // a wall they matter only where a solid's corner pokes between two of them, which the
  // contact at the located time still finds (it is deeper there): corners only, a fifth of the
  // wall queries of a leaf
  if (m.ground_collides()) {
    if (k.support) {
      const Vec3 nb = Rt * Vec3::UnitZ();
      Vec3 rb;
      ellipsoid_support_point(k, nb.data(), rb.data());
      gap = (x + R * rb).z() - m.ground_z;
    } else {
      for (size_t p = 0; p < k.count(); ++p)
        if (!k.on_edge(p)) gap = std::min(gap, (x + R * point(p)).z() - m.ground_z);
    }
  }
  if (!m.walls_collide()) return gap;
  // near a colliding ground that is the grid's floor, away from every other wall: the ground
  // was the only surface (as in gather)
  if (m.ground_collides() && m.field.only_floor_near(x, type.reach, m.ground_z, t)) return gap;
  double dc;
  Vec3 gc;
  if (!m.field.wall_distance(x, t, &dc, &gc)) return gap;
  if (dc > type.reach) return std::min(gap, dc - type.reach);
  auto wall_at = [&](const Vec3& rb) {
    double d;
    Vec3 g;
    return m.field.wall_distance(x + R * rb, t, &d, &g) ? d : HUGE_VAL;
  };
  if (k.support) {
    const double gn = gc.norm();
    if (!(gn > 0)) return gap;
    const Vec3 nb = Rt * (gc / gn);
    Vec3 rb;
    ellipsoid_support_point(k, nb.data(), rb.data());
    return std::min(gap, wall_at(rb));
  }
  for (size_t p = 0; p < k.count(); ++p)
    if (!k.on_edge(p)) gap = std::min(gap, wall_at(point(p)));
  return gap;
}

// The weight of the step's end velocity in its position update: x += h/2 (V0 + V1) for the
// splitting step; the strang step moves x by h/2 times the velocities after its first force half
// step and before its second, the same for forces constant over the step (a body lying on a
// surface); about that for rk4; explicit Euler moves x by h V0 only.
double end_velocity_weight(const Model& m) {
  return m.integrator == Integrator::Euler ? 0.0 : 0.5;
}

}  // namespace

bool flow_can_move(const Model& model, const BodyType& type, const BodyState& b, const Vec3& n,
                   double t, double gust) {
  Kinematics k;
  k.x = b.x;
  k.R = b.q.toRotationMatrix();
  k.v.setZero();
  k.w.setZero();
  k.u_seen.setZero();
  k.history = b.history;  // the Basset history's force as it stands (none without the effect)
  // the mean flow at the body (the sample effect_wrench takes is the same)
  FluidSample s;
  if (type.plan.sample_field && !sample_fluid(model, b.x, t, false, &s)) return false;
  const double un = s.U.norm();
  const Vec3 along = un > 0 ? Vec3(s.U / un) : Vec3::UnitX();
  k.u_seen = gust * along;
  Vec6 f;
  FluidSample used;
  if (effect_wrench(model, type, k, t, &f, &used) != EvalResult::Ok) return false;
  const Vec3 F = k.R * f.head<3>();
  const double press = -F.dot(n);  // what holds the body on the surface, N
  const double slide = (F + press * n).norm();
  const ContactParams& c = *type.contact;
  if (!(press > 0) || slide > c.friction * press) return true;
  // a sphere or an ellipsoid with rolling resistance rolls (or twists) when the wrench's torque
  // about its touching point exceeds what the resistance holds,
  // mu_r |r| press: a sphere under a tangential force F_t at its centre when F_t > mu_r press
  if (c.support && c.rolling_resistance > 0) {
    const Vec3 nb = k.R.transpose() * n;
    Vec3 rb;
    ellipsoid_support_point(c, nb.data(), rb.data());
    const Vec3 tau = f.tail<3>() - rb.cross(Vec3(f.head<3>()));
    if (tau.norm() > c.rolling_resistance * rb.norm() * press) return true;
  }
  return false;
}

double wake_gust(const Model& model, const BodyType& type, const BodyState& b, const Vec3& n,
                 double t, double sigma) {
  if (flow_can_move(model, type, b, n, t, 0.0)) return 0.0;
  const double top = kMaxGustSigmas * sigma;
  if (!(top > 0) || !flow_can_move(model, type, b, n, t, top)) return HUGE_VAL;
  double lo = 0, hi = top;
  while (hi - lo > 1e-4 * top) {
    const double mid = 0.5 * (lo + hi);
    (flow_can_move(model, type, b, n, t, mid) ? hi : lo) = mid;
  }
  return hi;
}

bool keeps_gust_watch(const Model& model, const BodyType& type) {
  return type.effects.has(Effect::Turbulence) && model.turbulence_model == TurbulenceModel::Seen &&
         type.plan.sample_field;
}

namespace {

// The standard deviation of one component of the turbulence at x (m/s); 0 outside the grid
double turbulence_sigma(const Model& model, const Vec3& x, double t) {
  FluidSample s;
  if (!sample_fluid(model, x, t, false, &s)) return 0;
  return std::sqrt(std::max(0.0, s.sigma2));
}

// Body i, resting in b on a surface of world normal n after the step that ends at t_end, falls
// asleep unless the flow moves it as it is (returns false: it stays awake). Where the type keeps
// a gust watch, the watch starts from the u' the body sees now.
bool fall_asleep(const Model& model, const BodyType& type, size_t i, double t_end,
                 const Vec3& n, BodyState* b, State* st) {
  const double sigma =
      type.effects.has(Effect::Turbulence) ? turbulence_sigma(model, b->x, t_end) : 0.0;
  double gust = HUGE_VAL;
  if (keeps_gust_watch(model, type)) {
    gust = wake_gust(model, type, *b, n, t_end, sigma);
    if (!(gust > 0)) return false;
  } else if (flow_can_move(model, type, *b, n, t_end, kGustSigmas * sigma)) {
    return false;
  }
  st->status[i] = BodyStatus::Sleeping;
  st->t_stop[i] = t_end;
  b->v.setZero();
  b->w.setZero();
  if (i < st->watch.size()) {
    GustWatch& w = st->watch[i];
    w = GustWatch{};
    w.u = b->u_seen;
    w.gust = gust;
    w.start = w.step = static_cast<uint64_t>(std::llround(t_end / model.dt));
    w.valid = 1;
  }
  return true;
}

constexpr uint64_t kWatchSalt = 0x9e3779b97f4a7c15ull;  // the watches' stream: another key
constexpr uint64_t kWatchAcrossSalt = 0xc2b2ae3d27d4eb4full;  // their draws at the wake

}  // namespace

namespace {

// An OU process of per-step decay a < 1 (its coefficient over one step of h) taken S steps at
// once: the exact sum of S updates x <- a x + c + b z is x <- aS x + D c + bS z with aS = a^S,
// D = (1 - a^S) / (1 - a) and bS the noise of the exact update over S h (ou_exact: its variance
// is the S steps' b^2 (1 - a^2S) / (1 - a^2)).
struct OUStride {
  double decay, drift, noise;
};
OUStride ou_stride(const FluidSample& s, double h, const OUStep& one, uint64_t S) {
  if (S == 1) return {one.decay, 1.0, one.noise_std};
  const OUStep all = ou_exact(s.alpha, s.beta, double(S) * h);
  const double drift = one.decay < 1 ? (1 - all.decay) / (1 - one.decay) : double(S);
  return {all.decay, drift, all.noise_std};
}

}  // namespace

uint64_t watch_sleeper(const Model& model, State* st, size_t i, uint64_t upto) {
  if (i >= st->watch.size() || !st->watch[i].valid) return GustWatch::kNever;
  GustWatch& w = st->watch[i];
  if (w.wake != GustWatch::kNever || !(w.gust < HUGE_VAL) || w.step >= upto) return w.wake;
  // the flow where and when the body fell asleep (whenever the watch is asked: its steps do not
  // depend on when)
  FluidSample s;
  if (!sample_fluid(model, st->x[i], double(w.start) * model.dt, !model.field.is_uniform(), &s))
    return w.wake;
  const double un = s.U.norm();
  const Vec3 along = un > 0 ? Vec3(s.U / un) : Vec3::UnitX();
  const double h = model.dt;
  const OUStep one = ou_exact(s.alpha, s.beta, h);
  // the seen model's update (ou_update) for a body at rest, whose path velocity is 0, is
  // u' <- decay u' + c + noise z, each component apart: c, its drift per step (Thomson's), is
  // the update of u' = 0 without decay or noise
  const double wm = model.well_mixed_correction ? 1.0 : 0.0;
  const double rest[3] = {0, 0, 0};
  auto update = [&](double decay, double noise, double over, const double* z, Vec3* u) {
    ou_update(wm, decay, noise, s.sigma2, rest, s.grad_sigma2.data(), z, over, u->data());
  };
  Vec3 c = Vec3::Zero();
  update(0.0, 0.0, h, rest, &c);
  const double ca = c.dot(along);
  // first asked: u' along the mean flow when the body fell asleep
  if (w.step == w.start) w.ua = w.u.dot(along);
  // the draws: one normal per step it starts from, four steps to a Philox block
  uint64_t block = GustWatch::kNever;
  double z4[4];
  while (w.step < upto) {
    // S steps at once where the gust is out of reach within them: the noise's part of the
    // path after k steps is a^k M_k, M a sum of independent symmetric terms of variance at most
    // S b^2 a^-2S by step S, so (Levy's inequality) it reaches `room` with a probability below
    // 2 Phi(-kWatchStrideSigmas) = 6e-14
    // (the mean part of the path stays between ua and the process's mean)
    uint64_t S = 1;
    const double room =
        one.decay < 1 ? w.gust - std::max(w.ua, ca / (1 - one.decay)) : 0.0;
    if (room > 0) {
      const double q = room / (kWatchStrideSigmas * one.noise_std);
      S = q * q < double(kWatchMaxStride) ? std::max<uint64_t>(1, uint64_t(q * q))
                                          : kWatchMaxStride;
      while (S > 1 && kWatchStrideSigmas * one.noise_std * std::sqrt(double(S)) >
                          room * std::pow(one.decay, double(S)))
        S /= 2;
    }
    if (w.step / 4 != block) {
      block = w.step / 4;
      NormalStream(model.seed ^ kWatchSalt, static_cast<uint32_t>(i), block).normals(z4);
    }
    const OUStride o = ou_stride(s, h, one, S);
    w.ua = o.decay * w.ua + o.drift * ca + o.noise * z4[w.step % 4];
    w.step += S;
    if (w.ua >= w.gust) {
      // the wake: u' across the mean flow, independent of ua, drawn at once over the whole
      // sleep from where it was when the body fell asleep
      const OUStride all = ou_stride(s, h, one, w.step - w.start);
      double z[3];
      NormalStream(model.seed ^ kWatchAcrossSalt, static_cast<uint32_t>(i), w.step).normals(z);
      Vec3 u = w.u;
      update(all.decay, all.noise, all.drift * h, z, &u);
      u += (w.ua - u.dot(along)) * along;
      w.u = u;
      w.wake = w.step;
      break;
    }
  }
  return w.wake;
}

Vec3 wake_sleeper(State* st, size_t i) {
  st->status[i] = BodyStatus::Moving;
  st->rest_steps[i] = 0;
  st->t_stop[i] = 0;
  if (i >= st->watch.size()) return st->u_seen[i];
  GustWatch& w = st->watch[i];
  w.valid = 0;
  return w.u;
}

namespace {

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

bool contact_after_step(const Model& model, const BodyType& type, size_t i, double t_end,
                        BodyState* b, State* st, WallClearance* clearance,
                        const BodyState* start) {
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
  if (start && st->contact[i] == ContactState::Flying && approach > model.rest_speed &&
      impact_inside_step(model, type, i, t_end - model.dt, *start, b, st)) {
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

void wake_bodies(const Model& model, State* st, size_t n0, size_t n, uint64_t first,
                 uint64_t last) {
  const bool changes = model.field.frame_count() >= 2 || model.field.is_streamed();
  for (size_t i = n0; i < n; ++i) {
    if (st->status[i] != BodyStatus::Sleeping) continue;
    if (changes && model.field.next_frame_time(st->t_stop[i]) <= st->t) {
      wake_sleeper(st, i);  // its flow changed: it keeps the u' it fell asleep with
      continue;
    }
    if (watch_sleeper(model, st, i, last) <= first) st->u_seen[i] = wake_sleeper(st, i);
  }
}

}  // namespace lrigid
