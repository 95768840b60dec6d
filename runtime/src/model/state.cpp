#include "model/state.h"

#include <cmath>

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
  for (size_t ti = 0; ti < model.types.size(); ++ti) {
    const BodyType& type = model.types[ti];
    const BodySpec& spec = scene.bodies[ti];
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
      if (type.effects.has(Effect::Turbulence) &&
          model.turbulence_model == TurbulenceModel::Seen) {
        FluidSample fs;
        if (model.field.sample(s.x[i], 0.0, false, &fs)) {
          NormalStream ns(model.seed, id, ~uint64_t(1));
          double z[4];
          ns.normals(z);
          s.u_seen[i] = std::sqrt(fs.sigma2) * Vec3(z[0], z[1], z[2]);
        }
      }
    }
  }
  return s;
}

}  // namespace lrigid
