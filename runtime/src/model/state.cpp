#include "model/state.h"

#include <cmath>

#include "effects/basset.h"

#include "util/rng.h"
#include "util/rng_uniform.h"

namespace lrigid {

const char* body_status_name(BodyStatus s) {
  switch (s) {
    case BodyStatus::Moving: return "moving";
    case BodyStatus::Landed: return "landed";
    case BodyStatus::Exited: return "exited";
    case BodyStatus::Failed: return "failed";
  }
  return "?";
}

State initial_state(const Model& model, const Scene& scene) {
  State s;
  const size_t n = model.body_count;
  s.x.resize(n);
  s.q.resize(n);
  s.v.resize(n);
  s.w.resize(n);
  s.u_seen.assign(n, Vec3::Zero());
  s.type.resize(n);
  s.status.assign(n, BodyStatus::Moving);
  s.t_stop.assign(n, 0.0);
  s.reason.assign(n, std::string());
  s.history_offset.assign(n, State::kNoHistory);
  size_t hist = 0;
  for (const BodyType& type : model.types)
    if (type.plan.basset) hist += type.count * type.basset.stride();
  s.history.assign(hist, 0.0);
  hist = 0;
  for (size_t ti = 0; ti < model.types.size(); ++ti) {
    const BodyType& type = model.types[ti];
    const BodySpec& spec = scene.bodies[type.spec];
    for (size_t i = type.first_body; i < type.first_body + type.count; ++i) {
      const uint32_t id = static_cast<uint32_t>(i);
      s.type[i] = static_cast<uint16_t>(ti);
      if (spec.spawn_in_box) {
        double u[4];
        uniforms4(model.seed, id, 1, u);
        for (int a = 0; a < 3; ++a)
          s.x[i][a] = spec.box_lo[a] + u[a] * (spec.box_hi[a] - spec.box_lo[a]);
      } else {
        s.x[i] = spec.position;
      }
      if (spec.random_orientation) {
        // uniform on SO(3): a normalized 4D Gaussian (Shoemake's method is equivalent)
        NormalStream ns(model.seed, id, ~uint64_t(0));
        double z[4];
        ns.normals(z);
        s.q[i] = Quat(z[0], z[1], z[2], z[3]).normalized();
      } else {
        s.q[i] = spec.orientation.normalized();
      }
      const Mat3 Rt = s.q[i].toRotationMatrix().transpose();
      s.v[i] = Rt * spec.velocity;
      s.w[i] = Rt * spec.angular_velocity;
      if (spec.spin_max > 0) {
        // art direction: spin of a uniformly drawn magnitude about a uniformly random axis
        double u[4];
        uniforms4(model.seed, id, 2, u);
        NormalStream ns(model.seed, id, ~uint64_t(2));
        double z[4];
        ns.normals(z);
        const Vec3 axis = Vec3(z[0], z[1], z[2]).normalized();
        s.w[i] += (spec.spin_min + u[0] * (spec.spin_max - spec.spin_min)) * axis;
      }
      // seen model: the fluid's fluctuation starts stationary; body model: the body starts with
      // exactly the scene's velocity (its turbulent velocity starts at 0)
      if (type.effects.has(Effect::Turbulence) &&
          model.turbulence_model == TurbulenceModel::Seen) {
        FluidSample fs;
        if (model.field.sample(s.x[i], 0.0, false, &fs)) {
          NormalStream ns(model.seed, id, ~uint64_t(1));
          double z[4];
          ns.normals(z);
          s.u_seen[i] = model.turbulence_scale * std::sqrt(fs.sigma2) * Vec3(z[0], z[1], z[2]);
        }
      }
      if (type.plan.basset) {
        // the history starts from the relative velocity at t = 0 (no initial-jump term)
        s.history_offset[i] = hist;
        hist += type.basset.stride();
        Vec3 uf = Vec3::Zero();
        FluidSample fs;
        if (type.plan.mean_flow && model.field.sample(s.x[i], 0.0, false, &fs))
          uf += model.mean_flow_scale * fs.U;
        if (type.plan.seen) uf += s.u_seen[i];
        basset_reset(type.basset, uf - s.q[i].toRotationMatrix() * s.v[i], s.history_of(i));
      }
    }
  }
  return s;
}

}  // namespace lrigid
