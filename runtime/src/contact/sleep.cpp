#include "contact/sleep.h"

#include <algorithm>
#include <cmath>

#include "contact/points.h"
#include "effects/evaluate.h"
#include "effects/turbulence.h"
#include "util/rng.h"

namespace lrigid {

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
  // crossing trajectories (effects/turbulence.h): u' along the mean flow takes the time scale of
  // the axis of the type's drift nearer to the flow, along the drift or across it (for a flow
  // along the ground and a drift along gravity, across: exact there)
  const BodyType& type = model.types[st->type[i]];
  double along_drift, across_drift;
  crossing_factors(type.drift_speed * type.drift_speed, s.sigma2, &along_drift, &across_drift);
  const double cosd = type.drift_dir.dot(along);
  const double b = 2 * cosd * cosd >= 1 ? along_drift : across_drift;
  s.alpha *= b;
  s.beta *= std::sqrt(b);
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
