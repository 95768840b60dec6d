// Spheres settling from rest reach the terminal velocity the drag law predicts; with added mass
// a light sphere starts with the acceleration (rho_p - rho_f) g / (rho_p + rho_f/2).
#include <gtest/gtest.h>

#include <cmath>

#include "effects/compile_model.h"
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
