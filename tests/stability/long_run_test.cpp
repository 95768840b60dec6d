// Long runs: 10^6 splitting steps of one body, every step checked as in the matrix.
// With 10^5 and more Lagrangian time scales the statistics are sharp, so they are checked
// tightly: the seen turbulent velocity has the field's variance 2k/3 within 3 %, and a
// neutrally buoyant sphere, which filters the turbulence it sees, moves with at most that
// variance.
#include <gtest/gtest.h>

#include "compile/compile_model.h"
#include "effects/registry.h"
#include "stability/hard_case.h"

namespace lrigid {
namespace {

constexpr double kLongRhoAir = 1.204, kLongNuAir = 1.5e-5;
constexpr uint64_t kLongSteps = 1000000;

struct LongCase {
  const char* name;
  double density_ratio;
  double aspect;
  double dt;
  double ek_dt;  // eps/k dt
};

class LongRun : public ::testing::TestWithParam<LongCase> {};

TEST_P(LongRun, MillionStepsStayFiniteBoundedAndStatisticallyRight) {
  const LongCase c = GetParam();
  const Vec3 U(1, 0.5, 0);
  const double k = 0.2;
  Scene s = test::sphere_scene(0.005, c.density_ratio * kLongRhoAir, kLongRhoAir, kLongNuAir);
  if (c.aspect > 1) s.bodies[0].shape = Shape::ellipsoid(0.02, 0.02, 0.02 / c.aspect);
  s.effects = stability::base_effects();
  s.integrator = Integrator::Splitting;
  s.uniform_U = U;
  s.uniform_k = k;
  s.uniform_epsilon = c.ek_dt * k / c.dt;
  s.dt = c.dt;
  s.duration = c.dt * kLongSteps;
  const Model m = test::compile(s);
  State st = initial_state(m, s);
  const stability::Observed o = stability::run_observed(m, &st, U);
  const FluidSample fs = stability::sample_at(m, Vec3::Zero());
  SCOPED_TRACE(std::string(c.name) + ": alpha dt = " + std::to_string(fs.alpha * c.dt) +
               ", max |V-U| = " + std::to_string(o.max_speed) +
               " m/s, max E/bound = " + std::to_string(o.max_energy_ratio));
  EXPECT_EQ(o.failure, "");
  EXPECT_EQ(o.stats.steps, kLongSteps);
  EXPECT_EQ(o.stats.failed + o.stats.exited, 0u);
  EXPECT_LT(o.max_q_err, 1e-12);
  EXPECT_NEAR(fs.sigma2 / (2 * k / 3), 1, 1e-6) << "stationary drift keeps the field's k";
  EXPECT_NEAR(o.seen_var / fs.sigma2, 1, 0.03) << "variance of the seen velocity";
  if (c.density_ratio == 1 && c.aspect == 1) {
    EXPECT_LT(o.body_var / fs.sigma2, 1.03) << "a neutrally buoyant sphere filters turbulence";
  }
}

INSTANTIATE_TEST_SUITE_P(
    Long, LongRun,
    ::testing::Values(LongCase{"neutral_sphere", 1, 1, 1e-3, 0.1},
                      LongCase{"bubble", 0.001, 1, 1e-3, 0.1},
                      LongCase{"paper_sheet", 600, 1000, 1e-3, 0.1},
                      LongCase{"light_plate_coarse_dt", 0.01, 100, 0.02, 2}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace lrigid
