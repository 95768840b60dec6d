// Time and accuracy of the boundary element precompute vs panel count (runs once per body type).
// Counters: panels, coefficients K_ii / (rho V) or per rho a^3, relative error vs the exact
// (Lamb) value where there is one. Results and the machine: docs/physics/added-mass.md.
//   build-body/bin/bem_bench --benchmark_filter=Sphere
#include <benchmark/benchmark.h>

#include <Eigen/LU>
#include <cmath>

#include "body/added_mass.h"
#include "body/bem.h"
#include "body/mass_properties.h"
#include "body/tessellate.h"

namespace {

using lrigid::AddedMass;
using lrigid::Shape;

// bem on `shape` with the given panel target; reports K_ii / (rho V) for i = 0, 2, 4 and the
// error vs the analytic tensor when `exact` is set
void run(benchmark::State& state, const Shape& shape, bool exact) {
  const int target = static_cast<int>(state.range(0));
  AddedMass am;
  for (auto _ : state) {
    am = lrigid::added_mass_bem(shape, 1.0, target);
    benchmark::DoNotOptimize(am.tensor.data());
  }
  const double v = lrigid::mass_properties(shape).volume;
  state.counters["panels"] = am.panels;
  state.counters["k_xx"] = am.tensor(0, 0) / v;
  state.counters["k_zz"] = am.tensor(2, 2) / v;
  state.counters["k_rot_x"] = am.tensor(3, 3) / v;
  state.counters["k_rot_y"] = am.tensor(4, 4) / v;
  if (exact) {
    const AddedMass ex = lrigid::added_mass(shape, 1.0);
    for (int i : {0, 2, 3, 4}) {
      if (ex.tensor(i, i) == 0) continue;
      state.counters["err_" + std::to_string(i) + std::to_string(i) + "_pct"] =
          100 * (am.tensor(i, i) / ex.tensor(i, i) - 1);
    }
  }
}

void BM_BemSphere(benchmark::State& s) { run(s, Shape::sphere(1), true); }
void BM_BemProlate2(benchmark::State& s) { run(s, Shape::ellipsoid(2, 1, 1), true); }
void BM_BemOblate10(benchmark::State& s) { run(s, Shape::ellipsoid(1, 1, 0.1), true); }
void BM_BemCube(benchmark::State& s) { run(s, Shape::box(1, 1, 1), false); }
void BM_BemPlate100(benchmark::State& s) { run(s, Shape::box(1, 1, 0.01), false); }

// the dense LU alone, for the split between assembly and solve
void BM_DenseLu(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const Eigen::MatrixXd a = Eigen::MatrixXd::Random(n, n) + n * Eigen::MatrixXd::Identity(n, n);
  for (auto _ : state) {
    Eigen::PartialPivLU<Eigen::MatrixXd> lu(a);
    benchmark::DoNotOptimize(lu.matrixLU().data());
  }
}

#define PANELS Arg(80)->Arg(320)->Arg(1280)->Arg(5120)->Unit(benchmark::kMillisecond)
BENCHMARK(BM_BemSphere)->PANELS;
BENCHMARK(BM_BemProlate2)->PANELS;
BENCHMARK(BM_BemOblate10)->PANELS;
#define BOX_PANELS \
  Arg(100)->Arg(400)->Arg(1200)->Arg(2400)->Arg(4800)->Unit(benchmark::kMillisecond)
BENCHMARK(BM_BemCube)->BOX_PANELS;
BENCHMARK(BM_BemPlate100)->BOX_PANELS;
BENCHMARK(BM_DenseLu)->Arg(1280)->Arg(2400)->Arg(5120)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
