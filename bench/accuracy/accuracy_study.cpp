// accuracy_study: the error-versus-cost study of the schemes (docs/accuracy.md).
//
//   accuracy_study [--quick] [--out DIR] [--scenes a,b] [--sweeps det,stoch,effects]
//                  [--threads N] [--grids NAME:SCENE:FILE1,FILE2,...] [--field SCENE=FILE]
//
// For every standard scene whose field exists it sweeps integrator x dt (turbulence off:
// trajectory error against an rk4 reference at a finer dt; turbulence on: strong error on the
// same Brownian path and weak errors of the mean and variance of positions and landing points,
// against a splitting reference at the Brownian path's resolution), effect sets (full, auto,
// minimal against full) and, with --grids, one scene on several resolutions of the same field
// against the finest. Every reference is checked against the same scheme at twice its step.
// Writes DIR/accuracy.csv (one row per measured point, see docs/accuracy.md for the columns).
// bench/accuracy/make_report.py turns it into the plot, the tolerance table and docs/accuracy.md.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "io/atomic_file.h"
#include <nlohmann/json.hpp>

#include "io/field_loader.h"
#include "io/scene_json.h"
#include "study.h"
#include "util/error.h"

using namespace lrigid;
using namespace lrigid::accuracy;

namespace {

struct Case {
  std::string name;        // scene name (file stem)
  std::string scene_path;
  int bodies_det = 200;    // bodies for the deterministic sweep
  int bodies_stoch = 1000; // bodies for the stochastic sweeps (weak error statistics)
  double duration = 3;     // s
  double every = 0.5;      // s between compared outputs
  double h = 5e-5;         // Brownian path resolution, s
  std::vector<int> ratios; // dt = ratio * h
  double spawn_z_lo = 0, spawn_z_hi = 0;  // m; when hi > lo, every spawn box spans these heights
};

// the spawn boxes of `c` moved to its heights (so that bodies land within the study's duration)
void apply_spawn(const Case& c, Scene* scene) {
  if (!(c.spawn_z_hi > c.spawn_z_lo)) return;
  for (auto& b : scene->bodies)
    if (b.spawn_in_box) {
      b.box_lo.z() = c.spawn_z_lo;
      b.box_hi.z() = c.spawn_z_hi;
    }
}

struct Row {
  std::string scene, sweep, integrator, effects, grid, metric, note;
  double dt = 0;
  uint32_t substeps = 1;
  size_t bodies = 0;
  Metric m;
  double ref_check = 0;
  RunStats stats;
  double wall_total = 0;
  double cpu_seconds = 0;
};

std::vector<Row> g_rows;

void add(const Case& c, const std::string& sweep, const RunSpec& s, const std::string& grid,
         const std::string& metric, const Metric& m, double ref_check, const RunResult& r) {
  Row row;
  row.scene = c.name;
  row.sweep = sweep;
  // the batched steps in single precision count as a scheme of their own
  row.integrator = std::string(integrator_name(s.integrator)) +
                   (s.precision == Precision::Float ? "_float" : "");
  row.effects = effect_mode_name(s.effects);
  row.grid = grid;
  row.metric = metric;
  row.note = m.note;
  row.dt = s.dt;
  row.substeps = s.substeps;
  row.bodies = r.status.size();
  row.m = m;
  row.ref_check = ref_check;
  row.stats = r.stats;
  row.wall_total = r.wall_total;
  row.cpu_seconds = r.cpu_seconds;
  g_rows.push_back(row);
}

std::string csv_text() {
  std::ostringstream o;
  o << "scene,sweep,integrator,dt,substeps,effects,grid,bodies,metric,error,error_se,valid,"
       "ref_check,body_steps,wall_s,ns_per_body_step,wall_total_s,cpu_s,cpu_ns_per_body_step,"
       "failed,note\n";
  for (const Row& r : g_rows) {
    char buf[512];
    const double steps = r.stats.body_steps ? double(r.stats.body_steps) : 1.0;
    const double ns = 1e9 * r.stats.wall_seconds / steps, cpu_ns = 1e9 * r.cpu_seconds / steps;
    std::snprintf(buf, sizeof buf, "%s,%s,%s,%.6g,%u,%s,%s,%zu,%s,%.6e,%.3e,%d,%.3e,%llu,%.4f,%.1f,"
                  "%.4f,%.4f,%.1f,%zu,%s\n",
                  r.scene.c_str(), r.sweep.c_str(), r.integrator.c_str(), r.dt, r.substeps,
                  r.effects.c_str(), r.grid.c_str(), r.bodies, r.metric.c_str(), r.m.value,
                  r.m.se, r.m.valid ? 1 : 0, r.ref_check,
                  static_cast<unsigned long long>(r.stats.body_steps), r.stats.wall_seconds, ns,
                  r.wall_total, r.cpu_seconds, cpu_ns, r.stats.failed, r.note.c_str());
    o << buf;
  }
  return o.str();
}

void write_csv(const std::string& out) {
  ensure_writable_directory(out);
  const std::string text = csv_text();
  write_file_atomically(out + "/accuracy.csv", [&](std::ostream& o) { o << text; });
}

void log(const std::string& s) { std::cerr << "accuracy_study: " << s << std::endl; }

using MetricFn = Metric (*)(const RunResult&, const RunResult&);
struct NamedMetric {
  const char* name;
  MetricFn fn;
};
Metric strong_error(const RunResult& a, const RunResult& ref) { return pathwise_error(a, ref); }
const std::vector<NamedMetric> kStochMetrics = {
    {"strong", strong_error},           {"weak_mean", weak_mean_error},
    {"weak_var", weak_variance_error},  {"landing_mean", landing_mean_error},
    {"landing_var", landing_variance_error}};

// a run of `scheme` at time step dt (s), with or without the turbulence model
RunSpec make_spec(Integrator scheme, double dt, bool turbulence, int threads) {
  RunSpec s;
  s.integrator = scheme;
  s.dt = dt;
  s.turbulence = turbulence;
  s.threads = threads;
  return s;
}

// integrator x dt, turbulence off, against rk4 at h (checked against rk4 at 2h)
void sweep_deterministic(const Case& c, const Scene& base, const FluidField& field, int threads,
                         const std::vector<std::string>& schemes) {
  Scene scene = base;
  scale_bodies(&scene, c.bodies_det);
  const RunSpec ref_spec = make_spec(Integrator::RK4, c.h, false, threads);
  log(c.name + ": deterministic reference (rk4, dt " + std::to_string(ref_spec.dt) + " s)");
  const RunResult ref = run(scene, field, ref_spec, c.every);
  RunSpec chk_spec = ref_spec;
  chk_spec.dt = 2 * c.h;
  const RunResult chk = run(scene, field, chk_spec, c.every);
  const Metric ref_err = pathwise_error(chk, ref), ref_err1 = pathwise_error(chk, ref, 1);
  add(c, "reference_det", chk_spec, "", "trajectory", ref_err, ref_err.value, chk);
  add(c, "reference_det", chk_spec, "", "trajectory_t1", ref_err1, ref_err1.value, chk);
  for (const auto& name : schemes)
    for (int ratio : c.ratios) {
      RunSpec s = ref_spec;
      s.integrator = integrator_from_name(name);
      s.dt = ratio * c.h;
      if (s.integrator == ref_spec.integrator && s.dt == ref_spec.dt) continue;  // the reference
      const RunResult r = run(scene, field, s, c.every);
      const Metric m = pathwise_error(r, ref);
      add(c, "dt_det", s, "", "trajectory", m, ref_err.value, r);
      add(c, "dt_det", s, "", "trajectory_t1", pathwise_error(r, ref, 1), ref_err1.value, r);
      log(c.name + ": " + name + " dt " + std::to_string(s.dt) + " trajectory error " +
          std::to_string(m.value) + (m.valid ? "" : " (" + m.note + ")"));
    }
  // what single precision costs: splitting in float at the same steps, against the reference
  // (dt_det, scheme "splitting_float") and against the double run (sweep "precision")
  if (std::find(schemes.begin(), schemes.end(), "splitting") == schemes.end()) return;
  for (int ratio : c.ratios) {
    RunSpec s = ref_spec;
    s.integrator = Integrator::Splitting;
    s.dt = ratio * c.h;
    const RunResult dbl = run(scene, field, s, c.every);
    s.precision = Precision::Float;
    const RunResult flt = run(scene, field, s, c.every);
    const Metric m = pathwise_error(flt, ref);
    add(c, "dt_det", s, "", "trajectory", m, ref_err.value, flt);
    add(c, "dt_det", s, "", "trajectory_t1", pathwise_error(flt, ref, 1), ref_err1.value, flt);
    add(c, "precision", s, "", "trajectory", pathwise_error(flt, dbl), 0, flt);
    add(c, "precision", s, "", "trajectory_t1", pathwise_error(flt, dbl, 1), 0, flt);
    log(c.name + ": splitting (float) dt " + std::to_string(s.dt) + " trajectory error " +
        std::to_string(m.value) + ", against double " +
        std::to_string(pathwise_error(flt, dbl).value));
  }
}

// integrator x dt on one Brownian path, against splitting at dt = h (checked at 2h)
void sweep_stochastic(const Case& c, const Scene& base, const FluidField& field, int threads,
                      const std::vector<std::string>& schemes) {
  Scene scene = base;
  scale_bodies(&scene, c.bodies_stoch);
  RunSpec ref_spec = make_spec(Integrator::Splitting, c.h, true, threads);
  ref_spec.substeps = 1;
  log(c.name + ": stochastic reference (splitting, dt " + std::to_string(c.h) + " s)");
  const RunResult ref = run(scene, field, ref_spec, c.every);
  RunSpec chk_spec = ref_spec;
  chk_spec.dt = 2 * c.h;
  chk_spec.substeps = 2;
  const RunResult chk = run(scene, field, chk_spec, c.every);
  std::vector<double> checks;
  for (const auto& nm : kStochMetrics) {
    const Metric e = nm.fn(chk, ref);
    checks.push_back(e.valid ? e.value : 0);
    add(c, "reference_stoch", chk_spec, "", nm.name, e, e.value, chk);
  }
  for (const auto& name : schemes)
    for (int ratio : c.ratios) {
      RunSpec s = ref_spec;
      s.integrator = integrator_from_name(name);
      s.dt = ratio * c.h;
      s.substeps = static_cast<uint32_t>(ratio);
      if (s.integrator == ref_spec.integrator && s.dt == ref_spec.dt) continue;  // the reference
      const RunResult r = run(scene, field, s, c.every);
      for (size_t k = 0; k < kStochMetrics.size(); ++k)
        add(c, "dt_stoch", s, "", kStochMetrics[k].name, kStochMetrics[k].fn(r, ref), checks[k],
            r);
      const Metric m = pathwise_error(r, ref);
      log(c.name + ": " + name + " dt " + std::to_string(s.dt) + " strong error " +
          std::to_string(m.value) + (m.valid ? "" : " (" + m.note + ")"));
    }
}

// effect sets at the scene's scheme and dt, against the full set
void sweep_effects(const Case& c, const Scene& base, const FluidField& field, int threads) {
  for (bool turbulence : {false, true}) {
    Scene scene = base;
    scale_bodies(&scene, turbulence ? c.bodies_stoch : c.bodies_det);
    RunSpec s = make_spec(base.integrator, base.dt, turbulence, threads);
    s.effects = EffectMode::Full;
    const RunResult full = run(scene, field, s, c.every);
    for (EffectMode mode : {EffectMode::Full, EffectMode::Auto, EffectMode::Minimal}) {
      s.effects = mode;
      const RunResult r = mode == EffectMode::Full ? full : run(scene, field, s, c.every);
      if (!turbulence) {
        add(c, "effects_det", s, "", "trajectory", pathwise_error(r, full), 0, r);
      } else {
        for (const auto& nm : kStochMetrics)
          if (std::string(nm.name) != "strong")
            add(c, "effects", s, "", nm.name, nm.fn(r, full), 0, r);
      }
      log(c.name + ": effects " + effect_mode_name(mode) + (turbulence ? " (turbulence)" : ""));
    }
  }
}

// the same scene on several grids of the same case, against the finest (the last)
void sweep_grids(const Case& c, const Scene& base, const std::vector<std::string>& grids,
                 int threads) {
  std::vector<FluidField> fields;
  for (const auto& g : grids) {
    Scene s = base;
    s.field_path = g;
    s.uniform_field = false;
    fields.push_back(load_field(s, StreamMode::Off, true));
  }
  for (bool turbulence : {false, true}) {
    Scene scene = base;
    scale_bodies(&scene, turbulence ? c.bodies_stoch : c.bodies_det);
    RunSpec s = make_spec(base.integrator, base.dt, turbulence, threads);
    const RunResult fine = run(scene, fields.back(), s, c.every);
    for (size_t g = 0; g + 1 < grids.size(); ++g) {
      const RunResult r = run(scene, fields[g], s, c.every);
      const std::string gname = grids[g].substr(grids[g].find_last_of('/') + 1);
      if (!turbulence) {
        add(c, "grid", s, gname, "trajectory", pathwise_error(r, fine), 0, r);
        add(c, "grid", s, gname, "trajectory_t1", pathwise_error(r, fine, 1), 0, r);
      } else {
        for (const auto& nm : kStochMetrics)
          if (std::string(nm.name) != "strong")
            add(c, "grid", s, gname, nm.name, nm.fn(r, fine), 0, r);
      }
      log(c.name + ": grid " + gname + (turbulence ? " (turbulence)" : ""));
    }
  }
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, sep))
    if (!item.empty()) out.push_back(item);
  return out;
}

bool file_exists(const std::string& p) { return std::ifstream(p).good(); }

int study(int argc, char** argv) {
  std::string src = LRIGID_SOURCE_DIR;
  std::string out = src + "/docs/accuracy";
  std::vector<std::string> only, grid_spec, field_override;
  std::vector<std::string> sweeps = {"det", "stoch", "effects"};
  std::vector<std::string> schemes = {"euler", "rk4", "splitting", "strang"};
  bool quick = false;
  int threads = 1;
  int bodies_stoch = 0;  // > 0: the stochastic sweeps' body count instead of each case's
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw Error(ExitCode::Usage, a + " needs a value");
      return argv[++i];
    };
    if (a == "--quick") quick = true;
    else if (a == "--out") out = value();
    else if (a == "--scenes") only = split(value(), ',');
    else if (a == "--integrators") schemes = split(value(), ',');
    else if (a == "--sweeps") sweeps = split(value(), ',');
    else if (a == "--threads") threads = std::stoi(value());
    else if (a == "--bodies-stoch") bodies_stoch = std::stoi(value());
    else if (a == "--grids") grid_spec.push_back(value());
    else if (a == "--field") field_override.push_back(value());
    else if (a == "--source-dir") src = value();
    else if (a == "-h" || a == "--help") {
      std::cout << "usage: accuracy_study [--quick] [--out DIR] [--scenes a,b] [--integrators "
                   "a,b] [--sweeps det,stoch,effects] [--threads N] [--bodies-stoch N] "
                   "[--grids NAME:SCENE.json:F1,F2,...(finest last)] "
                   "[--field SCENE=FILE (another converted field for a standard scene)]\n";
      return 0;
    } else {
      throw Error(ExitCode::Usage, "unknown argument '" + a + "' (see --help)");
    }
  }
  for (const auto& s : schemes) integrator_from_name(s);
  for (const auto& s : sweeps)
    if (s != "det" && s != "stoch" && s != "effects")
      throw Error(ExitCode::Usage, "--sweeps: unknown sweep '" + s + "' (det, stoch, effects)");

  std::vector<Case> cases;
  if (quick) {
    // seconds: a short uniform-box run on three coarse steps
    Case c{"uniform_box", src + "/scenes/uniform_box.json", 40, 200, 0.4, 0.2, 1e-4, {5, 10, 20}};
    cases.push_back(c);
  } else {
    // dt from 1e-4 to 1e-2 s (7 values over two decades) on a path resolved at 1e-4 s
    const std::vector<int> ratios = {1, 2, 5, 10, 20, 50, 100};
    cases.push_back({"uniform_box", src + "/scenes/uniform_box.json", 100, 1000, 2.0, 0.5, 1e-4,
                     ratios});
    // leaves spawned 0.5-3 m above the ground (the scene's 14-20 m take ~15 s to fall) for 4 s,
    // so that about 90 % of the 1200 bodies land: the landing-point metrics need >= 1000
    cases.push_back({"leaves_wind", src + "/scenes/leaves_wind.json", 100, 1200, 4.0, 1.0, 1e-4,
                     ratios, 0.5, 3.0});
    cases.push_back({"debris_tank", src + "/scenes/debris_tank.json", 100, 1000, 2.0, 0.5, 1e-4,
                     ratios});
  }
  const auto t0 = std::chrono::steady_clock::now();
  for (Case c : cases) {
    if (!only.empty() && std::find(only.begin(), only.end(), c.name) == only.end()) continue;
    // more bodies: a lower Monte Carlo floor for the weak errors (docs/accuracy.md)
    if (bodies_stoch > 0) c.bodies_stoch = bodies_stoch;
    if (!file_exists(c.scene_path)) {
      log("skipping " + c.name + ": no " + c.scene_path);
      continue;
    }
    // the scene with its field replaced by --field (the reader checks that the field exists)
    nlohmann::json j = nlohmann::json::parse(std::ifstream(c.scene_path));
    for (const auto& f : field_override)
      if (f.rfind(c.name + "=", 0) == 0) j["fluid"]["field"] = f.substr(c.name.size() + 1);
    Scene scene;
    try {
      scene = parse_scene(j.dump(), c.scene_path);
    } catch (const Error& e) {
      log("skipping " + c.name + ": " + e.what() + " (./Allrun, ./Allrun -all, or --field)");
      continue;
    }
    scene.duration = c.duration;
    apply_spawn(c, &scene);
    const FluidField field = load_field(scene, StreamMode::Off, true);
    auto wanted = [&](const char* s) {
      return std::find(sweeps.begin(), sweeps.end(), s) != sweeps.end();
    };
    if (wanted("det")) sweep_deterministic(c, scene, field, threads, schemes);
    if (wanted("stoch")) sweep_stochastic(c, scene, field, threads, schemes);
    if (wanted("effects")) sweep_effects(c, scene, field, threads);
    write_csv(out);  // after every scene, so a later failure keeps the measured points
  }
  for (const auto& spec : grid_spec) {
    const auto parts = split(spec, ':');
    if (parts.size() != 3) throw Error(ExitCode::Usage, "--grids NAME:SCENE:F1,F2,... got " + spec);
    const auto files = split(parts[2], ',');
    if (files.size() < 2) throw Error(ExitCode::Usage, "--grids needs at least two grid files");
    Scene scene = read_scene(parts[1]);
    if (quick) scene.duration = 0.4;
    // the scene's own duration, compared at four times
    Case c{parts[0], parts[1], quick ? 40 : 100, quick ? 200 : 1200, scene.duration,
           scene.duration / 4, 0, {}};
    sweep_grids(c, scene, files, threads);
  }
  if (g_rows.empty()) throw Error(ExitCode::BadInput, "no scene could be run");
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  write_csv(out);
  log("wrote " + out + "/accuracy.csv (" + std::to_string(g_rows.size()) + " points) in " +
      std::to_string(total) + " s");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return study(argc, argv);
  } catch (const Error& e) {
    std::cerr << "accuracy_study: " << e.what() << "\n";
    return static_cast<int>(e.code());
  } catch (const std::exception& e) {
    std::cerr << "accuracy_study: " << e.what() << "\n";
    return 1;
  }
}
