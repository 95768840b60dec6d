// Kernels of the step on the wind scene's field: the normal generator, one field
// sample, and step_body per integrator with every effect selected. Single thread.
//   build/bin/step_bench --benchmark_min_time=0.5 [--benchmark_format=json]
// Needs results/grids/windCourtyard.vti (./Allrun); the field kernels are skipped without it.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "compile/compile_model.h"
#include "effects/registry.h"
#include "integrate/integrators.h"
#include "io/added_mass_cache.h"
#include "io/grid_reader.h"
#include "io/scene_json.h"
#include "model/state.h"
#include "util/rng.h"

namespace lrigid {
namespace {

const std::string kScene = std::string(LRIGID_SOURCE_DIR) + "/scenes/leaves_wind.json";

// the wind scene with every effect, n bodies, the given integrator (loaded once per process)
struct Wind {
  Scene scene;
  FluidField field;
  bool ok = false;
  Wind() {
    scene = read_scene(kScene);
    if (!std::filesystem::exists(scene.field_path)) return;
    const GridFile g = read_grid(scene.field_path);
    field = FluidField::grid(g.geometry, g.frames, scene.kinematic_viscosity, scene.drift,
                             scene.time_mode);
    ok = true;
  }
};
const Wind& wind() {
  static const Wind w;
  return w;
}

void BM_Normals12(benchmark::State& bs) {
  double n[12];
  uint32_t body = 0;
  for (auto _ : bs) {
    NormalStream(7, body++, 3).normals(n);
    benchmark::DoNotOptimize(n);
  }
  bs.SetItemsProcessed(bs.iterations() * 12);
}
BENCHMARK(BM_Normals12);

void BM_FieldSample(benchmark::State& bs) {
  const Wind& w = wind();
  if (!w.ok) return bs.SkipWithError("no wind grid (run ./Allrun)");
  const bool gradients = bs.range(0) != 0;
  // positions spread over the scene's spawn box
  const BodySpec& b = w.scene.bodies[0];
  std::vector<Vec3> xs(4096);
  for (size_t i = 0; i < xs.size(); ++i) {
    const double f[3] = {(i * 0.618034) - std::floor(i * 0.618034),
                         (i * 0.414214) - std::floor(i * 0.414214),
                         (i * 0.732051) - std::floor(i * 0.732051)};
    for (int a = 0; a < 3; ++a) xs[i][a] = b.box_lo[a] + f[a] * (b.box_hi[a] - b.box_lo[a]);
  }
  size_t i = 0;
  FluidSample s;
  for (auto _ : bs) {
    benchmark::DoNotOptimize(w.field.sample(xs[i++ & 4095], 0.0, gradients, &s));
    benchmark::DoNotOptimize(s);
  }
  bs.SetItemsProcessed(bs.iterations());
}
BENCHMARK(BM_FieldSample)->Arg(0)->Arg(1);

// step_body over 1024 bodies of the wind scene (all effects), restarted every 50 steps
void BM_StepBody(benchmark::State& bs) {
  const Wind& w = wind();
  if (!w.ok) return bs.SkipWithError("no wind grid (run ./Allrun)");
  Scene s = w.scene;
  s.integrator = static_cast<Integrator>(bs.range(0));
  for (const EffectInfo& e : all_effects()) s.effects.add(e.effect);
  s.effects_auto = false;
  const int per = 1024 / int(s.bodies.size());
  for (BodySpec& b : s.bodies) b.count = per;
  const Model m = compile_model(s, w.field, cached_added_mass);
  const State st0 = initial_state(m, s);
  const size_t n = st0.size();
  size_t failed = 0;
  uint64_t body_steps = 0;
  for (auto _ : bs) {
    State st = st0;
    for (uint64_t k = 0; k < 50; ++k) {
      for (size_t i = 0; i < n; ++i) {
        BodyState b{st.x[i], st.q[i], st.v[i], st.w[i], st.u_seen[i], st.history_of(i)};
        std::string reason;
        if (step_body(m, m.types[st.type[i]], uint32_t(i), k, double(k) * m.dt, &b, &reason) !=
            StepOutcome::Ok)
          ++failed;
        st.x[i] = b.x, st.q[i] = b.q, st.v[i] = b.v, st.w[i] = b.w, st.u_seen[i] = b.u_seen;
      }
    }
    body_steps += 50 * n;
    benchmark::DoNotOptimize(st.x.data());
  }
  bs.SetItemsProcessed(int64_t(body_steps));
  bs.counters["failed"] = double(failed);
}
BENCHMARK(BM_StepBody)
    ->ArgName("integrator")
    ->Arg(int(Integrator::Euler))
    ->Arg(int(Integrator::RK4))
    ->Arg(int(Integrator::Splitting))
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace lrigid

BENCHMARK_MAIN();
