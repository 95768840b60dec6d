// The effect plan of a body type (effects/plan.h, plan.cpp): only the selected effects become
// wrench terms, in order; the mean flow and the turbulence change the field sampling instead.
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

}  // namespace
}  // namespace lrigid
