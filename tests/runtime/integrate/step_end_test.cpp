// The end of a step (integrate/step_end.h), which the scalar and the batched drivers both call:
// a failed step stops the body where the step began; a body far from every surface is only
// marked flying; on a "stop" ground a body that reached it lands where its lowest point met the
// ground inside the step (closed form for a free fall); a body dropped onto a colliding ground
// gets its first touchdown at the time the free fall gives; the quiet test agrees with what
// finish_step does. And the two drivers, through finish_step, stop and land the same bodies at
// the same times.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "integrate/simulation.h"
#include "integrate/step_end.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

constexpr double kG = 9.81;
constexpr double kR = 0.01;  // sphere radius, m

// one steel sphere of radius kR falling in vacuum-like air (gravity only), ground at z = 0
Scene drop_scene(ContactMode ground, bool batched) {
  Scene s = test::sphere_scene(kR, 7800, 1.2, 1.5e-5);
  s.effects = test::effects({Effect::Gravity});
  s.bodies[0].position = Vec3(0, 0, 0.5);
  s.has_ground = true;
  s.ground_z = 0;
  s.ground_contact = ground;
  s.dt = 1e-3;
  s.duration = 0.5;
  s.batched = batched;
  return s;
}

TEST(StepEnd, AFailedStepStopsTheBodyWhereItBegan) {
  const Scene s = drop_scene(ContactMode::Stop, false);
  const Model m = test::compile(s);
  State st = initial_state(m, s);
  BodyState b = load_body(st, 0);
  const BodyState start = b;
  const StepEnd end = finish_step(m, m.types[0], 0, 0.25, 1000, StepOutcome::Failed,
                                  "non-finite velocity", false, nullptr, &start, nullptr, &b, &st);
  EXPECT_EQ(end.next, AfterStep::Stopped);
  EXPECT_EQ(st.status[0], BodyStatus::Failed);
  EXPECT_DOUBLE_EQ(st.t_stop[0], 0.25);
  EXPECT_NE(st.reason[0].find("non-finite velocity"), std::string::npos) << st.reason[0];
  EXPECT_EQ(b.x, start.x);  // where the step began
}

TEST(StepEnd, AFarBodyIsOnlyMarkedFlying) {
  const Scene s = drop_scene(ContactMode::Collide, false);
  const Model m = test::compile(s);
  ASSERT_TRUE(m.contacts());
  State st = initial_state(m, s);
  st.contact[0] = ContactState::Sliding;
  st.rest_steps[0] = 7;
  BodyState b = load_body(st, 0);
  const BodyState before = b;
  ASSERT_TRUE(step_end_is_quiet(m, StepOutcome::Ok, false, false));
  const StepEnd end = finish_step(m, m.types[0], 0, 0.0, 1000, StepOutcome::Ok, "", false,
                                  nullptr, &before, nullptr, &b, &st);
  EXPECT_EQ(end.next, AfterStep::Moving);
  EXPECT_FALSE(end.moved);
  EXPECT_EQ(st.contact[0], ContactState::Flying);
  EXPECT_EQ(st.rest_steps[0], 0u);
  EXPECT_EQ(b.x, before.x);
  EXPECT_EQ(b.v, before.v);
  // near a surface, or landing on a "stop" ground, the end of the step is not quiet
  EXPECT_FALSE(step_end_is_quiet(m, StepOutcome::Ok, true, false));
  EXPECT_FALSE(step_end_is_quiet(m, StepOutcome::Exited, false, false));
  const Model stop = test::compile(drop_scene(ContactMode::Stop, false));
  EXPECT_FALSE(step_end_is_quiet(stop, StepOutcome::Ok, false, true));
  EXPECT_TRUE(step_end_is_quiet(stop, StepOutcome::Ok, false, false));
}

// free fall from rest at height z0 (lowest point): it touches the ground at sqrt(2 z0 / g)
double touchdown_time() { return std::sqrt(2 * (0.5 - kR) / kG); }

class StepEndDrivers : public ::testing::TestWithParam<bool> {};

TEST_P(StepEndDrivers, AStopGroundLandsTheBodyWhereItTouched) {
  const Scene s = drop_scene(ContactMode::Stop, GetParam());
  const Model m = test::compile(s);
  State st = initial_state(m, s);
  simulate(m, &st, RunOptions{});
  ASSERT_EQ(st.status[0], BodyStatus::Landed);
  // located inside the step by the cubic interpolant: the free fall's time to round-off of the
  // scheme (the motion is a parabola, which the Hermite interpolant holds exactly)
  EXPECT_NEAR(st.t_stop[0], touchdown_time(), 1e-9);
  EXPECT_NEAR(st.x[0].z(), kR, 1e-9);
  EXPECT_EQ(st.v[0], Vec3::Zero());
}

TEST_P(StepEndDrivers, ACollidingGroundRecordsTheFirstTouchdownInsideTheStep) {
  Scene s = drop_scene(ContactMode::Collide, GetParam());
  s.bodies[0].contact.restitution = 0.5;
  const Model m = test::compile(s);
  State st = initial_state(m, s);
  simulate(m, &st, RunOptions{});
  ASSERT_FALSE(std::isnan(st.t_touch[0]));
  EXPECT_NEAR(st.t_touch[0], touchdown_time(), 1e-6);
  EXPECT_NE(st.status[0], BodyStatus::Landed);  // a colliding ground holds it up, never lands it
  EXPECT_GE(st.impacts[0], 1u);
}

INSTANTIATE_TEST_SUITE_P(ScalarAndBatched, StepEndDrivers, ::testing::Bool(),
                         [](const auto& info) { return info.param ? "batched" : "scalar"; });

}  // namespace
}  // namespace lrigid
