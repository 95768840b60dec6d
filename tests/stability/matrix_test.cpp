// Stability matrix: the splitting and strang schemes at every
// combination of
//   density ratio rho_b/rho_f in {0.001, 0.01, 0.1, 1, 10, 1000} (bubble to steel, in air),
//   aspect ratio 1, 10, 100, 1000 (sphere to a sheet of paper; oblate ellipsoids, 10 cm wide),
//   dt in {1e-4, 1e-3, 1e-2, 0.05} s and eps/k dt in {0.01, 1, 100},
// gravity, buoyancy, added mass, drag, mean flow and turbulence on (base_effects), in a uniform
// mean flow of 3 m/s with k = 0.5 m^2/s^2, 20000 steps each.
// Every step: finite, ||q| - 1| < 1e-12, speed and kinetic energy under the physical bound of
// hard_case.h. Per run: the variance of the seen turbulent velocity is that of the field
// (2k/3, exact OU update) within a factor 1.5 (not exploding, not collapsing).
#include <gtest/gtest.h>

#include <map>
#include <tuple>

#include "compile/compile_model.h"
#include "effects/registry.h"
#include "stability/hard_case.h"

namespace lrigid {
namespace {

constexpr double kRhoAir = 1.204, kNuAir = 1.5e-5;
constexpr double kK = 0.5;
const Vec3 kU(3, 0, 0);
constexpr uint64_t kSteps = 20000;

struct MatrixCase {
  double density_ratio;
  double aspect;
  bool box;  // box (BEM added mass) instead of an ellipsoid
};

Shape shape_of(const MatrixCase& c) {
  const double a = 0.05;  // half width, m
  if (c.aspect == 1 && !c.box) return Shape::sphere(a);
  if (c.box) return Shape::box(2 * a, 2 * a, 2 * a / c.aspect);
  return Shape::ellipsoid(a, a, a / c.aspect);
}

// compile_model with the added mass computed once per shape (the BEM of a box takes seconds and
// does not depend on dt or the turbulence)
Model compile_cached(const Scene& s) {
  using Key = std::tuple<int, double, double, double, double, int>;
  static std::map<Key, AddedMass> cache;
  FluidField f = FluidField::uniform(s.uniform_U, s.uniform_k, s.uniform_epsilon,
                                     s.kinematic_viscosity, s.drift);
  return compile_model(s, std::move(f), [](const Shape& sh, double rho, int panels) {
    const Key key{int(sh.type), sh.half_extents.x(), sh.half_extents.y(), sh.half_extents.z(),
                  rho, panels};
    auto it = cache.find(key);
    if (it == cache.end()) it = cache.emplace(key, added_mass(sh, rho, panels)).first;
    return it->second;
  });
}

// one matrix cell (every dt and eps/k dt) on one scheme
void expect_stable(const MatrixCase& c, Integrator scheme) {
  for (double dt : {1e-4, 1e-3, 1e-2, 0.05}) {
    for (double ek_dt : {0.01, 1.0, 100.0}) {
      Scene s = test::sphere_scene(1, c.density_ratio * kRhoAir, kRhoAir, kNuAir);
      s.bodies[0].shape = shape_of(c);
      s.bodies[0].orientation = Quat(Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()));
      s.effects = stability::base_effects();
      s.integrator = scheme;
      s.uniform_U = kU;
      s.uniform_k = kK;
      s.uniform_epsilon = ek_dt * kK / dt;
      s.dt = dt;
      s.duration = dt * kSteps;
      const Model m = compile_cached(s);
      State st = initial_state(m, s);
      const stability::Observed o = stability::run_observed(m, &st, kU);
      const FluidSample fs = stability::sample_at(m, Vec3::Zero());
      const stability::Bound b = stability::Bound::of(m, m.types[0]);
      std::ostringstream id;
      id << integrator_name(scheme) << ": rho_b/rho_f = " << c.density_ratio << ", aspect " << c.aspect
         << (c.box ? " box" : "") << ", dt = " << dt << " s, eps/k dt = " << ek_dt
         << " (alpha dt = " << fs.alpha * dt << "), v_T bound " << b.v_T << " m/s, G " << b.G
         << ": max |V-U| " << o.max_speed << " m/s, max E/bound " << o.max_energy_ratio;
      SCOPED_TRACE(id.str());
      EXPECT_EQ(o.failure, "");
      EXPECT_EQ(o.stats.failed, 0u);
      EXPECT_EQ(o.stats.exited, 0u);
      EXPECT_EQ(st.status[0], BodyStatus::Moving);
      EXPECT_EQ(o.stats.steps, kSteps);
      // the exact OU update keeps the field's variance whatever alpha dt (>= 75 independent
      // samples here, so a factor 1.5 is far outside the sampling error)
      ASSERT_GT(fs.sigma2, 0);
      EXPECT_GT(o.seen_var / fs.sigma2, 1 / 1.5);
      EXPECT_LT(o.seen_var / fs.sigma2, 1.5);
      if (!o.failure.empty()) return;  // one report per matrix cell is enough
    }
  }
}

class StabilityMatrix : public ::testing::TestWithParam<MatrixCase> {};

TEST_P(StabilityMatrix, SplittingStaysFiniteAndBounded) {
  expect_stable(GetParam(), Integrator::Splitting);
}

// strang's force half steps are ROS2 (L-stable) around the same free flow and exact OU steps
TEST_P(StabilityMatrix, StrangStaysFiniteAndBounded) {
  expect_stable(GetParam(), Integrator::Strang);
}

std::vector<MatrixCase> ellipsoid_cases() {
  std::vector<MatrixCase> v;
  for (double r : {0.001, 0.01, 0.1, 1.0, 10.0, 1000.0})
    for (double a : {1.0, 10.0, 100.0, 1000.0}) v.push_back({r, a, false});
  return v;
}

std::string case_name(const ::testing::TestParamInfo<MatrixCase>& info) {
  std::ostringstream n;
  n << "ratio" << info.param.density_ratio << "_aspect" << info.param.aspect
    << (info.param.box ? "_box" : "");
  std::string s = n.str();
  for (char& ch : s)
    if (ch == '.') ch = 'p';
  return s;
}

INSTANTIATE_TEST_SUITE_P(Ellipsoids, StabilityMatrix, ::testing::ValuesIn(ellipsoid_cases()),
                         case_name);

// Boxes get their added mass from the boundary element method: the thin ones check that the
// BEM tensor of a plate keeps the step stable too.
INSTANTIATE_TEST_SUITE_P(Boxes, StabilityMatrix,
                         ::testing::Values(MatrixCase{0.001, 10, true}, MatrixCase{1, 10, true},
                                           MatrixCase{1000, 10, true},
                                           MatrixCase{0.001, 100, true},
                                           MatrixCase{1000, 100, true}),
                         case_name);

}  // namespace
}  // namespace lrigid
