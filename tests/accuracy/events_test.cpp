// Events located inside the step (contact/events.h locate_touchdown): a body that reaches the
// ground within a step lands where and when its motion through the step touched it, so that a
// landing does not cap a scheme's order at 1 (a body stopped at the end of the step lies up to
// one step's travel below the ground: rk4's measured slope is then 1.05 on uniform_box). The
// located root itself against a closed-form free fall: runtime/contact/events_test.cpp.
//   the measured orders of the landing point and time: euler, splitting 1; strang 2; rk4 4;
//   the batched steps land where the scalar step does; a colliding ground records the same
//   first touchdown (landings.csv) as a stopping one.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "compile/compile_model.h"
#include "integrate/simulation.h"
#include "accuracy/cases.h"
#include "contact/events.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

using test::effects;

struct Landing {
  std::vector<Vec3> x;        // where each body stopped, m
  std::vector<double> t;      // when, s
  std::vector<double> t_touch;  // the first touchdown (colliding ground), s
  std::vector<Vec3> x_touch;
};

Landing run(Scene s, Integrator integ, double dt, bool batched = true) {
  s.integrator = integ;
  s.dt = dt;
  s.batched = batched;
  Model m = test::compile(s);
  State st = initial_state(m, s);
  RunOptions opt;
  opt.every = s.duration;
  opt.threads = 1;
  const RunStats stats = simulate(m, &st, opt);
  EXPECT_EQ(stats.failed, 0u);
  if (s.ground_contact == ContactMode::Stop) {
    for (size_t i = 0; i < st.size(); ++i)
      EXPECT_EQ(st.status[i], BodyStatus::Landed) << integrator_name(integ) << " dt " << dt;
  }
  return {st.x, st.t_stop, st.t_touch, st.x_touch};
}

double events_log_log_slope(const std::vector<double>& dt, const std::vector<double>& err) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = double(dt.size());
  for (size_t i = 0; i < dt.size(); ++i) {
    const double x = std::log(dt[i]), y = std::log(err[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// the slope of the landing points' and times' errors against rk4 at dt_ref
struct Slopes {
  double x, t;
};
Slopes landing_slopes(const Scene& s, Integrator integ, const std::vector<double>& dts,
                      double dt_ref, const char* label) {
  const Landing ref = run(s, Integrator::RK4, dt_ref);
  std::vector<double> ex, et;
  for (double dt : dts) {
    const Landing l = run(s, integ, dt);
    double sx = 0, st = 0;
    for (size_t i = 0; i < l.x.size(); ++i) {
      sx += (l.x[i] - ref.x[i]).squaredNorm();
      st += (l.t[i] - ref.t[i]) * (l.t[i] - ref.t[i]);
    }
    ex.push_back(std::sqrt(sx / double(l.x.size())));
    et.push_back(std::sqrt(st / double(l.x.size())));
    std::printf("%s %s dt %.3g s: landing point error %.3e m, time error %.3e s\n", label,
                integrator_name(integ), dt, ex.back(), et.back());
  }
  const Slopes p{events_log_log_slope(dts, ex), events_log_log_slope(dts, et)};
  std::printf("%s %s: slopes %.2f (point), %.2f (time)\n", label, integrator_name(integ), p.x,
              p.t);
  return p;
}

// 1 mm glass spheres in water thrown sideways 4-8 mm above a ground that stops them (the
// convergence tests' sinking sphere); they land after 0.03-0.07 s
Scene landing_spheres() {
  Scene s = accuracy::sinking_sphere(4);
  s.bodies[0].spawn_in_box = true;
  s.bodies[0].box_lo = Vec3(0, 0, 0.004);
  s.bodies[0].box_hi = Vec3(0.002, 0.002, 0.008);
  s.has_ground = true;
  s.ground_z = 0;
  s.ground_contact = ContactMode::Stop;
  s.duration = 0.1;
  return s;
}

// the tumbling ellipsoids a little heavier (1300 kg/m^3), falling onto the ground: where they
// touch depends on their orientation (added mass with its Munk moment)
Scene landing_ellipsoids() {
  Scene s = accuracy::tumbling_ellipsoid(1300, 3);
  s.bodies[0].spawn_in_box = true;
  s.bodies[0].box_lo = Vec3(0, 0, 0.012);
  s.bodies[0].box_hi = Vec3(0.01, 0.01, 0.016);
  s.has_ground = true;
  s.ground_contact = ContactMode::Stop;
  s.duration = 0.6;
  return s;
}

TEST(Touchdown, LandingsKeepEachSchemesOrderOnSinkingSpheres) {
  const Scene s = landing_spheres();
  const std::vector<double> dts = {2e-3, 1e-3, 5e-4, 2.5e-4};
  const Slopes euler = landing_slopes(s, Integrator::Euler, dts, 1e-5, "spheres");
  const Slopes split = landing_slopes(s, Integrator::Splitting, dts, 1e-5, "spheres");
  const Slopes strang = landing_slopes(s, Integrator::Strang, dts, 1e-5, "spheres");
  const Slopes rk4 = landing_slopes(s, Integrator::RK4, dts, 1e-5, "spheres");
  EXPECT_NEAR(euler.x, 1.0, 0.25);
  EXPECT_NEAR(split.x, 1.0, 0.25);
  EXPECT_NEAR(strang.x, 2.0, 0.3);
  EXPECT_NEAR(strang.t, 2.0, 0.3);
  // rk4's landing would measure about 1 at the end of the step
  EXPECT_GT(rk4.x, 3.5);
  EXPECT_GT(rk4.t, 3.5);
}

TEST(Touchdown, LandingsKeepEachSchemesOrderOnTumblingEllipsoids) {
  const Scene s = landing_ellipsoids();
  const std::vector<double> dts = {4e-3, 2e-3, 1e-3, 5e-4};
  const Slopes strang = landing_slopes(s, Integrator::Strang, dts, 5e-5, "ellipsoids");
  const Slopes rk4 = landing_slopes(s, Integrator::RK4, dts, 5e-5, "ellipsoids");
  EXPECT_NEAR(strang.x, 2.0, 0.3);
  EXPECT_GT(rk4.x, 3.5);
  EXPECT_GT(rk4.t, 3.5);
}

TEST(Touchdown, TheBatchedStepsLandWhereTheScalarStepDoes) {
  for (const Scene& s : {landing_spheres(), landing_ellipsoids()})
    for (Integrator integ : {Integrator::Splitting, Integrator::Strang}) {
      const Landing batched = run(s, integ, 1e-3, true), scalar = run(s, integ, 1e-3, false);
      for (size_t i = 0; i < batched.x.size(); ++i) {
        EXPECT_NEAR(batched.t[i], scalar.t[i], 1e-9) << integrator_name(integ) << " body " << i;
        EXPECT_LT((batched.x[i] - scalar.x[i]).norm(), 1e-9) << integrator_name(integ);
        // and not at the end of a step (a multiple of dt)
        const double steps = batched.t[i] / 1e-3;
        EXPECT_GT(std::abs(steps - std::round(steps)), 1e-6) << batched.t[i];
      }
    }
}

TEST(Touchdown, ACollidingGroundRecordsTheSameFirstTouchdown) {
  // landings.csv keeps its meaning in both ground modes: the first touchdown of a bouncing
  // sphere is where and when a stopping ground stops it
  Scene s = landing_spheres();
  const Landing stop = run(s, Integrator::Strang, 1e-3);
  s.ground_contact = ContactMode::Collide;
  for (bool batched : {true, false}) {
    const Landing collide = run(s, Integrator::Strang, 1e-3, batched);
    for (size_t i = 0; i < stop.x.size(); ++i) {
      EXPECT_NEAR(collide.t_touch[i], stop.t[i], 1e-9) << "batched " << batched;
      EXPECT_LT((collide.x_touch[i] - stop.x[i]).norm(), 1e-9) << "batched " << batched;
    }
  }
}

}  // namespace
}  // namespace lrigid
