#include "integrate/contacts.h"

#include <algorithm>
#include <cmath>

#include "effects/contact.h"
#include "effects/turbulence.h"
#include "integrate/dynamics.h"
#include "util/rng.h"

namespace lrigid {

namespace {

// The touching points of one body: body-frame offsets from the centre of mass, body-frame unit
// normals (from the surface into the fluid) and depths (m, >= 0).
struct Touching {
  double r[3 * kContactMaxPoints];
  double n[3 * kContactMaxPoints];
  double depth[kContactMaxPoints];
  int count = 0;
  bool ground = false;
  void add(const Vec3& rb, const Vec3& nb, double d) {
    if (count == kContactMaxPoints) return;
    for (int a = 0; a < 3; ++a) r[3 * count + a] = rb[a], n[3 * count + a] = nb[a];
    depth[count++] = d;
  }
};

// The shape's points that reach a surface, with the positions `ahead` seconds ahead at the
// points' current velocities (0: where they are).
void gather(const Model& m, const BodyType& type, const BodyState& b, const Mat3& R, double t,
            double ahead, Touching* out, WallClearance* clearance = nullptr) {
  const ContactParams& k = *type.contact;
  const Mat3 Rt = R.transpose();
  // points on the ground need no wall check: the grid's floor is the ground, twice the same
  // constraint would only cost
  uint8_t on_ground[kContactMaxPoints * 4] = {};
  auto point_velocity = [&](const Vec3& rb) { return R * (b.v + b.w.cross(rb)); };
  if (m.ground_collides() && b.x.z() - type.reach <= m.ground_z) {
    const Vec3 ez(0, 0, 1);
    auto ground_depth = [&](const Vec3& rb) {
      const Vec3 p = b.x + R * rb + ahead * point_velocity(rb);
      return m.ground_z - p.z();
    };
    if (k.support) {
      const Vec3 nb = Rt * ez;
      Vec3 rb;
      ellipsoid_support_point(k, nb.data(), rb.data());
      const double d = ground_depth(rb);
      if (d >= 0) out->add(rb, nb, d), out->ground = true;
    } else {
      const Vec3 nb = Rt * ez;
      for (size_t p = 0; p < k.count(); ++p) {
        // a box edge's point between two corners on the ground: on it too, and implied by them
        // (the depth and the normal velocity are linear along the edge)
        const bool edge = 2 * p + 1 < k.edge_ends.size() &&
                          k.edge_ends[2 * p] != ContactParams::kNotOnEdge;
        if (edge && on_ground[k.edge_ends[2 * p]] && on_ground[k.edge_ends[2 * p + 1]]) {
          if (p < sizeof on_ground) on_ground[p] = 1;
          continue;
        }
        const Vec3 rb(k.points[3 * p], k.points[3 * p + 1], k.points[3 * p + 2]);
        const double d = ground_depth(rb);
        if (d >= 0) {
          out->add(rb, nb, d);
          out->ground = true;
          if (p < sizeof on_ground) on_ground[p] = 1;
        }
      }
    }
  }
  if (!m.walls_collide()) return;
  // a body near a colliding ground that is the grid's floor, away from every other wall: the
  // ground above was the only surface it could touch (touching or not)
  if (m.ground_collides() && m.field.only_floor_near(b.x, type.reach, m.ground_z, t)) return;
  if (clearance && clearance->radius >= 0 && (b.x - clearance->x).norm() < clearance->radius)
    return;
  double dc;
  Vec3 gc;
  const bool inside = m.field.wall_distance(b.x, t, &dc, &gc);
  if (clearance) {
    clearance->x = b.x;
    clearance->radius = inside ? (dc - type.reach) / std::sqrt(3.0) : -1;
  }
  if (!inside || dc > type.reach) return;
  // a point touches where the wall distance is <= 0; its normal is the distance's gradient
  auto wall = [&](const Vec3& rb, Vec3* nw) {
    const Vec3 p = b.x + R * rb + ahead * point_velocity(rb);
    double d;
    Vec3 g;
    if (!m.field.wall_distance(p, t, &d, &g) || d > 0) return -1.0;
    const double gn = g.norm();
    if (!(gn > 0)) return -1.0;
    *nw = g / gn;
    return -d;
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
    if (d >= 0) out->add(rb, Rt * nw, d);
  } else {
    for (size_t p = 0; p < k.count(); ++p) {
      if (p < sizeof on_ground && on_ground[p]) continue;
      const Vec3 rb(k.points[3 * p], k.points[3 * p + 1], k.points[3 * p + 2]);
      const double d = wall(rb, &nw);
      if (d >= 0) out->add(rb, Rt * nw, d);
    }
  }
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
    w.step = static_cast<uint64_t>(std::llround(t_end / model.dt));
    w.valid = 1;
  }
  return true;
}

constexpr uint64_t kWatchSalt = 0x9e3779b97f4a7c15ull;  // the watches' stream: another key

}  // namespace

uint64_t watch_sleeper(const Model& model, State* st, size_t i, double t, uint64_t upto) {
  if (i >= st->watch.size() || !st->watch[i].valid) return GustWatch::kNever;
  GustWatch& w = st->watch[i];
  if (w.wake != GustWatch::kNever || !(w.gust < HUGE_VAL) || w.step >= upto) return w.wake;
  FluidSample s;
  if (!sample_fluid(model, st->x[i], t, !model.field.is_uniform(), &s)) return w.wake;
  const double un = s.U.norm();
  const Vec3 along = un > 0 ? Vec3(s.U / un) : Vec3::UnitX();
  const OUStep ou = ou_exact(s.alpha, s.beta, model.dt);
  // the seen model's update (turbulence_update) for a body at rest: its path velocity is 0
  const double wm = model.well_mixed_correction ? 1.0 : 0.0;
  const double rest[3] = {0, 0, 0};
  for (; w.step < upto; ++w.step) {
    double z[3];
    NormalStream(model.seed ^ kWatchSalt, static_cast<uint32_t>(i), w.step).normals(z);
    ou_update(wm, ou.decay, ou.noise_std, s.sigma2, rest, s.grad_sigma2.data(), z, model.dt,
              w.u.data());
    if (w.u.dot(along) >= w.gust) {
      w.wake = ++w.step;
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

bool contact_after_step(const Model& model, const BodyType& type, size_t i, double t_end,
                        BodyState* b, State* st, WallClearance* clearance) {
  const Mat3 R = b->q.toRotationMatrix();
  Touching c;
  gather(model, type, *b, R, t_end, 0.0, &c, clearance);
  if (c.count == 0) {
    mark_flying(st, i);
    return false;
  }
  const Vec3 v0 = b->v, w0 = b->w;
  // the fastest approach of a touching point: an impact (a contact event) when it is above the
  // resting threshold, or when the body was flying
  double approach = 0;
  for (int p = 0; p < c.count; ++p) {
    const Vec3 rb(c.r[3 * p], c.r[3 * p + 1], c.r[3 * p + 2]);
    const Vec3 nb(c.n[3 * p], c.n[3 * p + 1], c.n[3 * p + 2]);
    approach = std::max(approach, -(v0 + w0.cross(rb)).dot(nb));
  }
  double dx[3];
  // M^-1 is symmetric: its column-major data is its row-major data
  contact_resolve(*type.contact, type.M_inv.data(), b->v.data(), b->w.data(), c.count, c.r, c.n,
                  c.depth, kContactPasses, dx, type.M.data());
  const double h = model.dt, cw = end_velocity_weight(model) * h;
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
  const double t = static_cast<double>(first) * model.dt;
  for (size_t i = n0; i < n; ++i) {
    if (st->status[i] != BodyStatus::Sleeping) continue;
    if (changes && model.field.next_frame_time(st->t_stop[i]) <= st->t) {
      wake_sleeper(st, i);  // its flow changed: it keeps the u' it fell asleep with
      continue;
    }
    if (watch_sleeper(model, st, i, t, last) <= first) st->u_seen[i] = wake_sleeper(st, i);
  }
}

}  // namespace lrigid
