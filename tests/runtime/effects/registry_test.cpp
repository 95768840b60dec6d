// The registry of effects (effects/registry.cpp): one row per effect, found by name and by id;
// what it says drives the field sampling and the cost estimates.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "effects/registry.h"
#include "model/effects.h"
#include "model/model.h"

namespace lrigid {
namespace {

TEST(Registry, EveryEffectHasExactlyOneRowWithAUniqueName) {
  std::set<uint32_t> ids;
  std::set<std::string> names;
  for (const EffectInfo& e : all_effects()) {
    ids.insert(static_cast<uint32_t>(e.effect));
    names.insert(e.name);
    EXPECT_EQ(&effect_info(e.effect), &e);
    Effect back;
    ASSERT_TRUE(effect_from_name(e.name, &back));
    EXPECT_EQ(back, e.effect);
    EXPECT_NE(e.rule, nullptr) << e.name;
    EXPECT_GE(e.cost_ns, 0.0) << e.name;
  }
  EXPECT_EQ(ids.size(), all_effects().size());
  EXPECT_EQ(names.size(), all_effects().size());
  // one row per bit of the enum, the bits 0 .. n - 1 for n rows
  for (uint32_t b = 0; b < all_effects().size(); ++b) EXPECT_EQ(ids.count(1u << b), 1u) << b;
  Effect none;
  EXPECT_FALSE(effect_from_name("wind_chill", &none));
}

TEST(Registry, FieldNeedsDecideTheSample) {
  EffectSet s;
  s.add(Effect::Gravity);
  s.add(Effect::Drag);
  EXPECT_FALSE(needs_field_sample(s));
  s.add(Effect::Turbulence);
  EXPECT_TRUE(needs_field_sample(s));
  EffectSet m;
  m.add(Effect::MeanFlow);
  EXPECT_TRUE(needs_field_sample(m));
}

TEST(Registry, CostEstimatesAreTheRowsSums) {
  EffectSet none, drag;
  drag.add(Effect::Drag);
  const double d = effect_info(Effect::Drag).cost_ns;
  EXPECT_DOUBLE_EQ(estimated_cost_ns(drag, Integrator::Splitting, false, true) -
                       estimated_cost_ns(none, Integrator::Splitting, false, true),
                   d);
  EXPECT_DOUBLE_EQ(estimated_batched_cost_ns(drag, Precision::Double) -
                       estimated_batched_cost_ns(none, Precision::Double),
                   effect_info(Effect::Drag).batched_cost_ns);
  // plates and ellipsoids on the batched step: euler cheaper than splitting, rk4 dearer (four
  // force evaluations and samples)
  const double split = estimated_batched_cost_ns(drag, Precision::Double, true);
  EXPECT_LT(estimated_batched_cost_ns(drag, Precision::Double, true, Integrator::Euler), split);
  EXPECT_GT(estimated_batched_cost_ns(drag, Precision::Double, true, Integrator::RK4), split);
  // the first row without a batched kernel, if any, rules the batched step out
  EffectSet all;
  const EffectInfo* unbatched = nullptr;
  for (const EffectInfo& e : all_effects()) {
    all.add(e.effect);
    if (!e.batched && !unbatched) unbatched = &e;
  }
  EXPECT_EQ(first_unbatched(all), unbatched);
}

TEST(Registry, AutoRulesSayWhyNot) {
  AutoInputs in;
  in.weight = 1.0;
  in.F_ref = 1.0;
  in.mass = 1.0;
  in.drag_per_speed = 1e-4;
  in.speed = 1.0;
  // no spin: Magnus is skipped for that reason; drag of 1e-4 of the weight is skipped
  const AutoDecision mag = effect_info(Effect::Magnus).rule(in);
  EXPECT_FALSE(mag.keep);
  EXPECT_EQ(mag.why_not, "no initial spin");
  const AutoDecision drag = effect_info(Effect::Drag).rule(in);
  EXPECT_FALSE(drag.keep);
  EXPECT_NE(drag.why_not.find("drag = 0.0001"), std::string::npos) << drag.why_not;
  EXPECT_TRUE(effect_info(Effect::Gravity).rule(in).keep);
  // a body that is not flat has no lift, whatever its size
  in.thickness_ratio = 1.0;
  EXPECT_EQ(effect_info(Effect::Lift).rule(in).why_not.rfind("not flat", 0), 0u);
}

}  // namespace
}  // namespace lrigid
