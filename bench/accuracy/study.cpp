#include "study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>

#include "compile/compile_model.h"
#include "effects/registry.h"
#include "io/added_mass_cache.h"
#include "util/error.h"

namespace lrigid::accuracy {

const char* effect_mode_name(EffectMode m) {
  switch (m) {
    case EffectMode::Scene: return "scene";
    case EffectMode::Full: return "full";
    case EffectMode::Auto: return "auto";
    case EffectMode::Minimal: return "minimal";
  }
  return "?";
}

Integrator integrator_from_name(const std::string& name) {
  Integrator i;
  if (lrigid::integrator_from_name(name, &i)) return i;
  throw Error(ExitCode::Usage, "unknown integrator '" + name + "' (" + kIntegratorNames + ")");
}

void scale_bodies(Scene* scene, int n) {
  long total = 0;
  for (const auto& b : scene->bodies) total += b.count;
  if (total <= 0) return;
  for (auto& b : scene->bodies)
    b.count = std::max(1, static_cast<int>(std::lround(double(b.count) * n / double(total))));
}

RunResult run(const Scene& scene_in, const FluidField& field, const RunSpec& spec, double every) {
  const auto t0 = std::chrono::steady_clock::now();
  Scene scene = scene_in;
  scene.integrator = spec.integrator;
  scene.dt = spec.dt;
  scene.precision = spec.precision;
  switch (spec.effects) {
    case EffectMode::Scene: break;
    case EffectMode::Auto: scene.effects_auto = true; break;
    case EffectMode::Full:
      scene.effects_auto = false;
      scene.effects = EffectSet{};
      for (const auto& e : all_effects()) scene.effects.add(e.effect);
      break;
    case EffectMode::Minimal:
      // what every body needs to move at all: weight, buoyancy, drag in the mean flow (and the
      // turbulence, so that the statistics can be compared with the other sets)
      scene.effects_auto = false;
      scene.effects = EffectSet{};
      for (Effect e : {Effect::Gravity, Effect::Buoyancy, Effect::Drag, Effect::MeanFlow,
                       Effect::Turbulence})
        scene.effects.add(e);
      break;
  }
  // the study measures where bodies land against a reference run: the seed's landing (a body
  // stops where it first touches the ground, ground.contact "stop"), not contacts, whose
  // bounces and slides would spread the landing points over the ground
  scene.ground_contact = ContactMode::Stop;
  scene.walls_contact = ContactMode::Stop;
  scene.outside = OutsideMode::Stop;
  Model model = compile_model(scene, field, [](const Shape& s, double rho, int panels) {
    return cached_added_mass(s, rho, panels);
  });
  model.noise_substeps = spec.substeps;
  if (!spec.turbulence)
    for (auto& t : model.types) t.effects.remove(Effect::Turbulence);
  State state = initial_state(model, scene);
  RunResult r;
  RunOptions opt;
  opt.every = every;
  opt.threads = spec.threads;
  opt.on_output = [&r](const State& s) {
    r.times.push_back(s.t);
    r.x.push_back(s.x);
  };
  const std::clock_t c0 = std::clock();
  r.stats = simulate(model, &state, opt);
  r.cpu_seconds = double(std::clock() - c0) / CLOCKS_PER_SEC;
  r.status = state.status;
  r.wall_total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

namespace {

// common checks: same output times and bodies; counts bodies that failed in one run only
bool comparable(const RunResult& a, const RunResult& ref, Metric* m) {
  if (a.times.size() != ref.times.size() || a.x.empty() || a.x[0].size() != ref.x[0].size()) {
    m->note = "output times or bodies differ";
    return false;
  }
  for (size_t j = 0; j < a.times.size(); ++j)
    if (std::abs(a.times[j] - ref.times[j]) > 1e-9) {
      m->note = "output times differ";
      return false;
    }
  size_t failed = 0;
  for (size_t i = 0; i < a.status.size(); ++i)
    failed += (a.status[i] == BodyStatus::Failed) != (ref.status[i] == BodyStatus::Failed);
  if (failed > 0) {
    m->note = std::to_string(failed) + " bodies failed";
    return false;
  }
  return true;
}

// RMS displacement of the reference bodies from their start at output j, m
double scale(const RunResult& ref, size_t j) {
  double s = 0;
  for (size_t i = 0; i < ref.x[j].size(); ++i) s += (ref.x[j][i] - ref.x[0][i]).squaredNorm();
  return std::sqrt(s / double(ref.x[j].size()));
}

struct Moments {
  Vec3 mean = Vec3::Zero();
  double var = 0;  // total variance (trace of the covariance), m^2
};

Moments moments(const std::vector<Vec3>& x, const std::vector<size_t>& idx, bool horizontal) {
  Moments m;
  for (size_t i : idx) {
    Vec3 p = x[i];
    if (horizontal) p.z() = 0;
    m.mean += p;
  }
  m.mean /= double(idx.size());
  for (size_t i : idx) {
    Vec3 p = x[i];
    if (horizontal) p.z() = 0;
    m.var += (p - m.mean).squaredNorm();
  }
  m.var /= double(idx.size() - 1);
  return m;
}

Metric mean_error(const std::vector<Vec3>& a, const std::vector<Vec3>& r,
                  const std::vector<size_t>& idx, double L, bool horizontal) {
  Metric m;
  const Moments ma = moments(a, idx, horizontal), mr = moments(r, idx, horizontal);
  const Vec3 dm = ma.mean - mr.mean;
  // paired differences: the standard error of the mean difference per component
  Vec3 var = Vec3::Zero();
  for (size_t i : idx) {
    Vec3 d = a[i] - r[i];
    if (horizontal) d.z() = 0;
    var += (d - dm).cwiseAbs2();
  }
  var /= double(idx.size() - 1);
  m.value = dm.norm() / L;
  m.se = std::sqrt(var.sum() / double(idx.size())) / L;
  m.valid = L > 0;
  return m;
}

Metric variance_error(const std::vector<Vec3>& a, const std::vector<Vec3>& r,
                      const std::vector<size_t>& idx, bool horizontal) {
  Metric m;
  const Moments ma = moments(a, idx, horizontal), mr = moments(r, idx, horizontal);
  std::vector<double> d;
  d.reserve(idx.size());
  double dmean = 0;
  for (size_t i : idx) {
    Vec3 pa = a[i] - ma.mean, pr = r[i] - mr.mean;
    if (horizontal) pa.z() = pr.z() = 0;
    d.push_back(pa.squaredNorm() - pr.squaredNorm());
    dmean += d.back();
  }
  dmean /= double(d.size());
  double v = 0;
  for (double x : d) v += (x - dmean) * (x - dmean);
  v /= double(d.size() - 1);
  m.value = std::abs(ma.var - mr.var) / mr.var;
  m.se = std::sqrt(v / double(d.size())) / mr.var;
  m.valid = mr.var > 0;
  return m;
}

std::vector<size_t> all_bodies(const RunResult& r) {
  std::vector<size_t> idx;
  for (size_t i = 0; i < r.status.size(); ++i)
    if (r.status[i] != BodyStatus::Failed) idx.push_back(i);
  return idx;
}

std::vector<size_t> landed_in_both(const RunResult& a, const RunResult& r) {
  std::vector<size_t> idx;
  for (size_t i = 0; i < r.status.size(); ++i)
    if (a.status[i] == BodyStatus::Landed && r.status[i] == BodyStatus::Landed) idx.push_back(i);
  return idx;
}

}  // namespace

Metric pathwise_error(const RunResult& a, const RunResult& ref, size_t last) {
  Metric m;
  if (!comparable(a, ref, &m)) return m;
  const std::vector<size_t> idx = all_bodies(ref);
  double worst = 0;
  for (size_t j = 1; j < ref.times.size() && j <= last; ++j) {
    const double L = scale(ref, j);
    if (L <= 0) continue;
    double s = 0;
    for (size_t i : idx) s += (a.x[j][i] - ref.x[j][i]).squaredNorm();
    worst = std::max(worst, std::sqrt(s / double(idx.size())) / L);
  }
  m.value = worst;
  m.valid = std::isfinite(worst);
  return m;
}

Metric weak_mean_error(const RunResult& a, const RunResult& ref) {
  Metric m;
  if (!comparable(a, ref, &m)) return m;
  const size_t j = ref.times.size() - 1;
  return mean_error(a.x[j], ref.x[j], all_bodies(ref), scale(ref, j), false);
}

Metric weak_variance_error(const RunResult& a, const RunResult& ref) {
  Metric m;
  if (!comparable(a, ref, &m)) return m;
  const size_t j = ref.times.size() - 1;
  return variance_error(a.x[j], ref.x[j], all_bodies(ref), false);
}

namespace {

// a metric of the final positions of the bodies that landed in both runs (at least 30)
template <class Fn>
Metric landing_metric(const RunResult& a, const RunResult& ref, Fn metric) {
  Metric m;
  if (!comparable(a, ref, &m)) return m;
  const auto idx = landed_in_both(a, ref);
  if (idx.size() < 30) {
    m.note = std::to_string(idx.size()) + " bodies landed in both runs";
    return m;
  }
  m = metric(ref.times.size() - 1, idx);
  m.note = std::to_string(idx.size()) + " landed in both";
  return m;
}

}  // namespace

Metric landing_mean_error(const RunResult& a, const RunResult& ref) {
  return landing_metric(a, ref, [&](size_t j, const auto& idx) {
    return mean_error(a.x[j], ref.x[j], idx, scale(ref, j), true);
  });
}

Metric landing_variance_error(const RunResult& a, const RunResult& ref) {
  return landing_metric(a, ref, [&](size_t j, const auto& idx) {
    return variance_error(a.x[j], ref.x[j], idx, true);
  });
}

}  // namespace lrigid::accuracy
