// lrigid bench [SCENE.json] [--n 1000,...] [--integrators euler,...] [--threads 1,2]
//              [--effects scene|all|auto|LIST] [--json F]
// Scene-level throughput: the scene's field and body types, scaled to N bodies, stepped for a
// fixed number of steps per (N, integrator, threads) with no output. Reports steady-state
// body-steps per second (warm-up steps excluded, setup and writes never timed) and the memory
// per body. docs/performance.md is generated from its JSON (bench/perf/run_perf.sh).
#include <omp.h>
#include <unistd.h>
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include <nlohmann/json.hpp>

#include "checks.h"
#include "commands.h"
#include "compile/compile_model.h"
#include "effects/registry.h"
#include "integrate/simulation.h"
#include "io/added_mass_cache.h"
#include "io/atomic_file.h"
#include "io/field_loader.h"
#include "io/scene_json.h"
#include "io/source_dir.h"
#include "model/state.h"
#include "util/error.h"

namespace lrigid::app {

namespace {

namespace fs = std::filesystem;

// the repository's scenes/leaves_wind.json, found from the binary (build/bin/lrigid) or the
// source tree it was built from, not from the working directory
std::string default_scene() {
  const std::string rel = "scenes/leaves_wind.json";
  char exe[4096];
  const ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (n > 0) {
    const fs::path p = fs::path(std::string(exe, size_t(n))).parent_path().parent_path()
                           .parent_path() / rel;
    if (fs::exists(p)) return p.string();
  }
const std::string src = source_dir();
  return src.empty() ? rel : src + "/" + rel;
}

struct BenchArgs {
  std::string scene;  // empty: default_scene()
  std::vector<long long> n = {1000, 10000, 100000, 1000000};
  std::vector<std::string> integrators = {"euler", "rk4", "splitting", "strang"};
  std::vector<int> threads = {1, 2};
  std::string effects = "scene";  // the scene's own ("auto" or its list), "all", or a list
  double body_steps = 3e6;  // measured body-steps per point (at least min_steps steps)
  int min_steps = 3;
  int warmup = 1;
  std::string json;
  bool quiet = false;
};

Integrator integrator_from(const std::string& s) {
  Integrator i;
  if (integrator_from_name(s, &i)) return i;
  throw Error(ExitCode::Usage, "--integrators: unknown integrator \"" + s + "\" (" +
                                   kIntegratorNames + ")");
}

EffectSet effects_from(const std::string& s, bool* is_auto) {
  EffectSet e;
  *is_auto = s == "auto";
  if (*is_auto || s == "scene") return e;
  if (s == "all") {
    for (const EffectInfo& i : all_effects()) e.add(i.effect);
    return e;
  }
  std::stringstream ss(s);
  std::string name;
  while (std::getline(ss, name, ',')) {
    Effect x;
    if (!effect_from_name(name, &x))
      throw Error(ExitCode::Usage, "--effects: unknown effect \"" + name + "\"");
    e.add(x);
  }
  return e;
}

// CPU time of the process (all threads), s: unlike wall time it does not count the time other
// jobs on a shared machine take the cores away
double cpu_seconds() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// bytes of State per body: the per-body arrays plus the Basset histories
double state_bytes_per_body(const State& s) {
  const size_t n = s.size();
  size_t b = n * (sizeof(Vec3) * 4 + sizeof(Quat) + sizeof(uint16_t) + sizeof(BodyStatus) +
                  sizeof(double) + sizeof(std::string) + sizeof(size_t));
  b += s.history.size() * sizeof(double);
  return n ? double(b) / double(n) : 0.0;
}

// the scene's body entries scaled to n bodies in total (same proportions)
void scale_bodies(Scene* scene, long long n) {
  long long total = 0;
  for (const BodySpec& b : scene->bodies) total += b.count;
  long long left = n;
  for (size_t i = 0; i < scene->bodies.size(); ++i) {
    BodySpec& b = scene->bodies[i];
    const long long c = i + 1 == scene->bodies.size()
                            ? left
                            : std::llround(double(n) * double(b.count) / double(total));
    b.count = int(std::max(0LL, std::min(c, left)));
    left -= b.count;
  }
}

void bench(const BenchArgs& args) {
  BenchArgs a = args;
  if (a.scene.empty()) a.scene = default_scene();
  const Scene base = read_scene(a.scene);
  const FluidField field = load_field(base, StreamMode::Auto, a.quiet);
  bool eff_auto = false;
  const bool scene_effects = a.effects == "scene";
  const EffectSet effects = effects_from(a.effects, &eff_auto);
  nlohmann::json out;
  out["scene"] = a.scene;
  out["effects"] = a.effects;
  // what runs, said before the numbers (and in the JSON): the scene, the effects of each body
  // type, the columns
  {
    Scene s = base;
    if (!scene_effects) {
      s.effects_auto = eff_auto;
      if (!eff_auto) s.effects = effects;
    }
    const Model m = compile_model(s, field, cached_added_mass);
    out["body_types"] = nlohmann::json::array();
    for (const BodyType& t : m.types)
      out["body_types"].push_back({{"name", t.name}, {"effects", effect_names(t.effects)}});
  }
  if (!a.quiet) {
    std::printf("scene %s\neffects: %s\n", a.scene.c_str(),
                scene_effects ? (base.effects_auto ? "the scene's (\"auto\": chosen per body type)"
                                                   : "the scene's list")
                : a.effects == "all" ? "all, for every body type (--effects all)"
                                     : ("--effects " + a.effects).c_str());
    for (const auto& t : out["body_types"]) {
      std::string names;
      for (const auto& e : t["effects"]) names += (names.empty() ? "" : ", ") + std::string(e);
      std::printf("  %s: %s\n", std::string(t["name"]).c_str(), names.c_str());
    }
    std::printf("columns: bodies, integrator, threads, steps timed, wall_s (wall time, s), "
                "body_steps_s (body-steps per second), per_thread (that / threads), per_cpu_s "
                "(body-steps per second of CPU time, all threads), B/body (bytes of State per "
                "body), scalar%% (%% of the body-steps of batched body types handed to the "
                "scalar step, docs/batched-step.md)\n");
  }
  out["field_bytes"] = field.bytes();
  if (!base.uniform_field) out["field"] = base.field_path;
  out["max_threads"] = omp_get_max_threads();
  out["runs"] = nlohmann::json::array();
  if (!a.quiet)
    std::printf("%9s %-10s %7s %6s %9s %14s %12s %14s %10s %8s\n", "bodies", "integrator",
                "threads", "steps", "wall_s", "body_steps_s", "per_thread", "per_cpu_s", "B/body",
                "scalar%");
  for (const long long n : a.n) {
    for (const std::string& iname : a.integrators) {
      Scene s = base;
      scale_bodies(&s, n);
      check_memory(s);  // exit 5 saying how much, before anything is allocated
      s.integrator = integrator_from(iname);
      if (!scene_effects) {
        s.effects_auto = eff_auto;
        if (!eff_auto) s.effects = effects;
      }
      const int steps = std::max(a.min_steps, int(std::ceil(a.body_steps / double(n))));
      Model m = compile_model(s, field, cached_added_mass);
      const State initial = initial_state(m, s);
      for (const int th : a.threads) {
        State st = initial;
        RunOptions opt;
        opt.threads = th;
        opt.every = 1e9;  // no outputs; one parallel region per call
        m.duration = double(a.warmup) * s.dt;
        if (a.warmup > 0) simulate(m, &st, opt);
        m.duration = double(a.warmup + steps) * s.dt;
        const double cpu0 = cpu_seconds();
        const RunStats r = simulate(m, &st, opt);
        const double cpu = cpu_seconds() - cpu0;
        const double cpu_rate = cpu > 0 ? double(r.body_steps) / cpu : 0.0;
        const double rate = r.wall_seconds > 0 ? double(r.body_steps) / r.wall_seconds : 0.0;
        const double bpb = state_bytes_per_body(st);
        // steps of batched bodies handed to the scalar step (integrate/rigid_batch.h)
        const double handoff =
            r.body_steps > 0 ? 100.0 * double(r.scalar_handoffs) / double(r.body_steps) : 0.0;
        if (!a.quiet)
          std::printf("%9lld %-10s %7d %6d %9.3f %14.4g %12.4g %14.4g %10.0f %8.2f\n", n,
                      iname.c_str(), th, steps, r.wall_seconds, rate, rate / th, cpu_rate, bpb,
                      handoff);
        std::fflush(stdout);
        nlohmann::json j;
        j["n"] = n;
        j["integrator"] = iname;
        j["threads"] = th;
        j["steps"] = steps;
        j["body_steps"] = r.body_steps;
        j["wall_seconds"] = r.wall_seconds;
        j["body_steps_per_s"] = rate;
        j["cpu_seconds"] = cpu;
        j["body_steps_per_cpu_s"] = cpu_rate;  // per core-second of CPU time
        j["state_bytes_per_body"] = bpb;
        j["scalar_handoffs"] = r.scalar_handoffs;
        j["newton_steps"] = r.newton_steps;
        j["exited"] = r.exited + r.failed;
        j["landed"] = r.landed;
        out["runs"].push_back(j);
      }
    }
  }
  if (!a.json.empty())
    write_file_atomically(a.json, [&](std::ostream& os) { os << out.dump(1) << "\n"; });
}

}  // namespace

void add_bench_command(CLI::App& app) {
  auto args = std::make_shared<BenchArgs>();
  auto* cmd = app.add_subcommand(
      "bench", "Throughput of a scene's step (body-steps/s) for several body counts, "
               "integrators and thread counts; no outputs written (docs/performance.md)");
  cmd->add_option("scene", args->scene,
                  "Scene file (default: the repository's scenes/leaves_wind.json, wherever "
                  "lrigid is run from)");
  cmd->add_option("--n", args->n, "Body counts")
      ->delimiter(',')
      ->check(within(1, 1e8, "body counts from 1 to 1e8 (a scene's limit)"));
  cmd->add_option("--integrators", args->integrators, kIntegratorNames)->delimiter(',');
  cmd->add_option("--threads", args->threads, "Thread counts")
      ->delimiter(',')
      ->check(CLI::Range(1, 1024));
  cmd->add_option("--effects", args->effects,
                  "\"scene\" (default: the scene's own, \"auto\" or its list), \"all\", "
                  "\"auto\" or a comma list; the effects used are printed first");
  cmd->add_option("--body-steps", args->body_steps,
                  "Body-steps timed per point (at least --min-steps steps)")
      ->check(within(1, 2e9, "a count of body-steps from 1 to 2e9"));
  cmd->add_option("--min-steps", args->min_steps, "Fewest timed steps")
      ->check(CLI::Range(1, 1 << 20));
  cmd->add_option("--warmup", args->warmup, "Untimed steps first")->check(CLI::Range(0, 1 << 20));
  cmd->add_option("--json", args->json, "Also write the results as JSON");
  cmd->add_flag("--quiet", args->quiet, "Print nothing but errors");
  cmd->callback([args] { bench(*args); });
}

}  // namespace lrigid::app
