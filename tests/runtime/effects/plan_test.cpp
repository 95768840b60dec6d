// The effect plan of a body type (effects/plan.h, plan.cpp): only the selected effects become
// wrench terms, in order; the mean flow and the turbulence change the field sampling instead;
// an unselected effect has no term and no memory (no Basset history without the effect).
#include "effects/plan.h"

#include <gtest/gtest.h>

#include "effects_fixture.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

using effects_test::disk_model;
using test::effects;

TEST(Plan, OnlySelectedWrenchTermsAreEvaluated) {
  const Model m = disk_model(effects({Effect::Gravity, Effect::Drag, Effect::Lift}));
  const EffectPlan& p = m.types[0].plan;
  ASSERT_EQ(p.terms.size(), 3u);
  EXPECT_EQ(p.term_effect[0], Effect::Gravity);
  EXPECT_EQ(p.term_effect[1], Effect::Drag);
  EXPECT_EQ(p.term_effect[2], Effect::Lift);
  EXPECT_FALSE(p.sample_field);
  EXPECT_FALSE(p.basset);
  // mean flow and turbulence are no wrench terms: they change what the field sampling does
  const Model f = disk_model(effects({Effect::MeanFlow, Effect::Turbulence}));
  EXPECT_TRUE(f.types[0].plan.terms.empty());
  EXPECT_TRUE(f.types[0].plan.sample_field);
  EXPECT_TRUE(f.types[0].plan.seen);
}

// A flat body with an offset centre of mass in a mean flow, gravity and drag only: two terms,
// no field sampled, no history memory.
TEST(EffectSwitch, UnselectedEffectsHaveNoTerms) {
  Scene s = test::sphere_scene(1, 1200, 1000, 1e-6);
  s.bodies[0].shape = Shape::ellipsoid(0.02, 0.05, 0.002);
  s.bodies[0].mass_offset = Vec3(0.001, 0, -0.0002);
  s.uniform_U = Vec3(0.3, -0.1, 0.05);
  s.effects = effects({Effect::Gravity, Effect::Drag});
  const Model m = test::compile(s);
  EXPECT_EQ(m.types[0].plan.terms.size(), 2u);
  EXPECT_FALSE(m.types[0].plan.sample_field);
  EXPECT_TRUE(initial_state(m, s).history.empty());  // no Basset: no history memory
}

}  // namespace
}  // namespace lrigid
