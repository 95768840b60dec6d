// Spheres settling from rest reach the terminal velocity the drag law predicts; with added mass
// a light sphere starts with the acceleration (rho_p - rho_f) g / (rho_p + rho_f/2). Paper plates
// held broadside reach the terminal velocity of the textbook broadside drag coefficient.
#include <gtest/gtest.h>

#include <cmath>
#include <ostream>

#include "compile/compile_model.h"
#include "effects/drag.h"
#include "integrate/simulation.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

// (rho_p - rho_f) V g = 1/2 rho_f C_D(Re) A U^2, solved by bisection
double terminal_velocity(double d, double rho_p, double rho_f, double mu, double g) {
  const double nu = mu / rho_f, V = M_PI * d * d * d / 6, A = M_PI * d * d / 4;
  double lo = 0, hi = 100;
  for (int i = 0; i < 200; ++i) {
    const double u = 0.5 * (lo + hi);
    const double drag = 0.5 * rho_f * schiller_naumann(u * d / nu) * A * u * u;
    (drag > (rho_p - rho_f) * V * g ? hi : lo) = u;
  }
  return 0.5 * (lo + hi);
}

struct Case {
  const char* name;
  double d, rho_p, rho_f, mu, dt, duration, table;  // table: physics-notes §5 value
};

class TerminalVelocity : public ::testing::TestWithParam<Case> {};

TEST_P(TerminalVelocity, MatchesSchillerNaumann) {
  const Case c = GetParam();
  Scene s = test::sphere_scene(c.d / 2, c.rho_p, c.rho_f, c.mu / c.rho_f);
  s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::AddedMass, Effect::Drag});
  s.integrator = Integrator::Splitting;
  s.dt = c.dt;
  s.duration = c.duration;
  const Model m = test::compile(s);
  State st = initial_state(m, s);
  simulate(m, &st, RunOptions{});
  const double u = -(st.q[0] * st.v[0]).z();
  const double expect = terminal_velocity(c.d, c.rho_p, c.rho_f, c.mu, 9.81);
  EXPECT_NEAR(u / expect, 1.0, 1e-3) << c.name << ": got " << u << " m/s, law " << expect;
  EXPECT_NEAR(expect / c.table, 1.0, 1e-2) << "independent solve vs physics-notes table";
}

INSTANTIATE_TEST_SUITE_P(
    Spheres, TerminalVelocity,
    ::testing::Values(Case{"glass_0.1mm_water", 1e-4, 2500, 998.2, 1.0016e-3, 1e-4, 0.1, 7.29e-3},
                      Case{"glass_1mm_water", 1e-3, 2500, 998.2, 1.0016e-3, 1e-3, 1.5, 0.146},
                      Case{"glass_5mm_air", 5e-3, 2500, 1.204, 1.813e-5, 2e-3, 20, 17.6},
                      Case{"eps_bead_5mm_air", 5e-3, 30, 1.204, 1.813e-5, 1e-3, 5, 1.71}),
    [](const auto& info) {
      std::string n = info.param.name;
      for (char& ch : n)
        if (ch == '.') ch = 'p';
      return n;
    });

// Flat plates of 70 g/m^2 paper held broadside (gravity, buoyancy and drag only: nothing turns
// them) reach the terminal velocity of the textbook broadside drag coefficient
// U = sqrt(2 (m - rho_f V) g / (rho_f S C_D)), C_D = 1.18 (square), 1.17 (disk), 1.2 (5:1
// rectangle) after Hoerner (1965) in White, Fluid Mechanics, Table 7.3; within 1 % (the model
// adds the Stokes resistance, ~0.3 % at these Re ~ 3000-4000). validation/paper_drops runs the
// same check on the CLI.
struct PlateCase {
  const char* name;
  Shape shape;
  double density, area, cd;
};

void PrintTo(const PlateCase& c, std::ostream* os) { *os << c.name; }

class BroadsidePlate : public ::testing::TestWithParam<PlateCase> {};

TEST_P(BroadsidePlate, ReachesTheTextbookTerminalVelocity) {
  const PlateCase c = GetParam();
  const double rho_f = 1.2, nu = 1.5e-5, g = 9.81;
  Scene s = test::sphere_scene(0.01, c.density, rho_f, nu);
  s.bodies[0].shape = c.shape;
  s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::Drag});
  s.integrator = Integrator::Splitting;
  s.dt = 5e-4;
  s.duration = 2.0;
  const Model m = test::compile(s);
  ASSERT_TRUE(m.types[0].flat);
  State st = initial_state(m, s);
  simulate(m, &st, RunOptions{});
  const double u = -(st.q[0] * st.v[0]).z();
  const double mass = m.types[0].mass, vol = m.types[0].volume;
  const double expect = std::sqrt(2 * (mass - rho_f * vol) * g / (rho_f * c.area * c.cd));
  EXPECT_NEAR(u / expect, 1.0, 1e-2) << c.name << ": got " << u << " m/s, C_D law " << expect;
}

constexpr double kPaperH = 6.94e-5, kPaperRho = 0.070 / kPaperH;  // 70 g/m^2, 1008 kg/m^3

INSTANTIATE_TEST_SUITE_P(
    Paper, BroadsidePlate,
    ::testing::Values(
        PlateCase{"square_5cm", Shape::box(0.05, 0.05, kPaperH), kPaperRho, 0.05 * 0.05, 1.18},
        // an oblate ellipsoid with the paper's mass per area (centre thickness kPaperH)
        PlateCase{"disk_R2p5cm", Shape::ellipsoid(0.025, 0.025, kPaperH / 2),
                  0.070 / (4.0 / 3.0 * kPaperH / 2), M_PI * 0.025 * 0.025, 1.17},
        PlateCase{"rectangle_5to1", Shape::box(0.25, 0.05, kPaperH), kPaperRho, 0.25 * 0.05,
                  1.2}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(AddedMassTransient, LightSphereStartsWithReducedAcceleration) {
  // from rest, before drag builds up: a0 = (rho_p - rho_f) g / (rho_p + C_m rho_f), C_m = 1/2
  const double rho_p = 1500, rho_f = 1000, g = 9.81;
  for (bool with_added_mass : {true, false}) {
    Scene s = test::sphere_scene(0.005, rho_p, rho_f, 1e-6);
    s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::Drag});
    if (with_added_mass) s.effects.add(Effect::AddedMass);
    s.integrator = Integrator::RK4;
    s.dt = 1e-5;
    s.duration = 1e-4;
    const Model m = test::compile(s);
    State st = initial_state(m, s);
    simulate(m, &st, RunOptions{});
    const double a = -(st.q[0] * st.v[0]).z() / s.duration;
    const double expect = (rho_p - rho_f) * g / (rho_p + (with_added_mass ? 0.5 * rho_f : 0.0));
    EXPECT_NEAR(a / expect, 1.0, 2e-3) << (with_added_mass ? "with" : "without") << " added mass";
  }
}

}  // namespace
}  // namespace lrigid
