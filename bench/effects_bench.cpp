// Cost per body-step of representative effect sets (docs/effects.md), and of each effect of the
// registry: the leaf with every effect against the leaf with every effect but one
// (Leaf_AllEffects_Splitting, Leaf_AllEffectsBut_<name>_Splitting, one pair per row of
// effects/registry.cpp, the row's cost_ns). Each benchmark advances 1024 bodies of one type by
// step_body, single thread, uniform field; the reported "ns_per_body_step" is wall time /
// body-steps.
//   build/bin/effects_bench --benchmark_min_time=0.5
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "body/added_mass.h"
#include "compile/compile_model.h"
#include "effects/registry.h"
#include "integrate/integrators.h"
#include "model/state.h"

namespace lrigid {
namespace {

enum class Body { SteelBall, Bubble, Leaf, NeutralSphere };

Scene make_scene(Body body, EffectSet e, Integrator integ) {
  Scene s;
  s.file = "<bench>";
  s.gravity = Vec3(0, 0, -9.81);
  s.integrator = integ;
  s.dt = 1e-3;
  s.duration = 10;
  BodySpec b;
  b.name = "b";
  b.count = 1024;
  b.spawn_in_box = true;
  b.box_lo = Vec3(0, 0, 0);
  b.box_hi = Vec3(1, 1, 1);
  b.random_orientation = true;
  switch (body) {
    case Body::SteelBall:
      s.fluid_density = 1.204, s.kinematic_viscosity = 1.5e-5;
      b.shape = Shape::sphere(2.5e-3), b.density = 7850;
      break;
    case Body::Bubble:
      s.fluid_density = 1000, s.kinematic_viscosity = 1e-6;
      b.shape = Shape::sphere(2.5e-4), b.density = 1.2;
      break;
    case Body::Leaf:
      s.fluid_density = 1.204, s.kinematic_viscosity = 1.5e-5;
      b.shape = Shape::ellipsoid(0.03, 0.02, 0.0002), b.density = 600;
      break;
    case Body::NeutralSphere:
      s.fluid_density = 1000, s.kinematic_viscosity = 1e-6;
      b.shape = Shape::sphere(1e-3), b.density = 1000;
      break;
  }
  s.uniform_U = Vec3(2, 0, 0);
  s.uniform_k = 0.5, s.uniform_epsilon = 0.2;
  b.angular_velocity = Vec3(0, 5, 0);
  s.bodies.push_back(b);
  s.effects = e;
  return s;
}

EffectSet set_of(std::initializer_list<Effect> l) {
  EffectSet e;
  for (Effect x : l) e.add(x);
  return e;
}

void run(benchmark::State& bs, Body body, EffectSet e, Integrator integ) {
  const Scene s = make_scene(body, e, integ);
  FluidField f = FluidField::uniform(s.uniform_U, s.uniform_k, s.uniform_epsilon,
                                     s.kinematic_viscosity, s.drift);
  const Model m = compile_model(s, std::move(f), [](const Shape& sh, double rho, int panels) {
    return added_mass(sh, rho, panels);
  });
  State st0 = initial_state(m, s);
  const BodyType& type = m.types[0];
  const size_t n = st0.size();
  uint64_t step = 0;
  size_t failed = 0;
  for (auto _ : bs) {
    // restart from the initial state every 200 steps so bodies stay in the same regime
    State st = st0;
    for (int k = 0; k < 200; ++k, ++step) {
      for (size_t i = 0; i < n; ++i) {
        BodyState b{st.x[i], st.q[i], st.v[i], st.w[i], st.u_seen[i], st.history_of(i)};
        std::string reason;
        if (step_body(m, type, uint32_t(i), step, k * m.dt, &b, &reason) != StepOutcome::Ok)
          ++failed;
        st.x[i] = b.x, st.q[i] = b.q, st.v[i] = b.v, st.w[i] = b.w, st.u_seen[i] = b.u_seen;
      }
    }
    benchmark::DoNotOptimize(st.x.data());
  }
  const double body_steps = double(bs.iterations()) * 200.0 * double(n);
  // kIsRate | kInvert gives seconds per body-step; report nanoseconds
  bs.counters["ns_per_body_step"] = benchmark::Counter(
      body_steps * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  bs.counters["failed"] = double(failed);
}

const EffectSet kGD = set_of({Effect::Gravity, Effect::Drag});
const EffectSet kBubble = set_of({Effect::Buoyancy, Effect::AddedMass, Effect::Drag});
const EffectSet kFull = set_of({Effect::Gravity, Effect::Buoyancy, Effect::AddedMass,
                                Effect::Drag, Effect::MeanFlow, Effect::Turbulence});
const EffectSet kLeaf = set_of({Effect::Gravity, Effect::AddedMass, Effect::Drag,
                                Effect::MeanFlow, Effect::Turbulence, Effect::Lift});
EffectSet plus(EffectSet a, Effect e) {
  a.add(e);
  return a;
}

#define LR_BENCH(name, body, set, integ)                                            \
  void name(benchmark::State& s) { run(s, Body::body, set, Integrator::integ); } \
  BENCHMARK(name)->Unit(benchmark::kMillisecond)

LR_BENCH(SteelBall_GravityDrag_Splitting, SteelBall, kGD, Splitting);
LR_BENCH(SteelBall_GravityDrag_Euler, SteelBall, kGD, Euler);
LR_BENCH(SteelBall_GravityDrag_RK4, SteelBall, kGD, RK4);
LR_BENCH(SteelBall_AllSixBaseEffects_Splitting, SteelBall, kFull, Splitting);
LR_BENCH(Bubble_BuoyancyAddedMassDrag_Splitting, Bubble, kBubble, Splitting);
LR_BENCH(Bubble_PlusBasset_Splitting, Bubble, plus(kBubble, Effect::Basset), Splitting);
LR_BENCH(Neutral_Base6_Splitting, NeutralSphere, kFull, Splitting);
LR_BENCH(Neutral_Base6PlusBasset_Splitting, NeutralSphere, plus(kFull, Effect::Basset),
         Splitting);
LR_BENCH(Neutral_Base6PlusBasset_RK4, NeutralSphere, plus(kFull, Effect::Basset), RK4);
LR_BENCH(Leaf_NoLift_Splitting, Leaf, kFull, Splitting);
LR_BENCH(Leaf_Lift_Splitting, Leaf, kLeaf, Splitting);
LR_BENCH(Leaf_LiftMagnus_Splitting, Leaf, plus(kLeaf, Effect::Magnus), Splitting);
LR_BENCH(Leaf_Lift_RK4, Leaf, kLeaf, RK4);

// the leaf (flat and spinning: every effect acts on it) with every effect of the registry, and
// without each one in turn
void register_each_effect() {
  EffectSet all;
  for (const EffectInfo& e : all_effects()) all.add(e.effect);
  auto add = [](const std::string& name, EffectSet set) {
    benchmark::RegisterBenchmark(name.c_str(), [set](benchmark::State& s) {
      run(s, Body::Leaf, set, Integrator::Splitting);
    })->Unit(benchmark::kMillisecond);
  };
  add("Leaf_AllEffects_Splitting", all);
  for (const EffectInfo& e : all_effects()) {
    EffectSet less = all;
    less.remove(e.effect);
    add(std::string("Leaf_AllEffectsBut_") + e.name + "_Splitting", less);
  }
}

}  // namespace
}  // namespace lrigid

int main(int argc, char** argv) {
  lrigid::register_each_effect();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
