// "effects": "auto" on clear cases (model/model.cpp analyze_effects; thresholds in
// docs/effects.md).
#include <gtest/gtest.h>

#include "compile/compile_model.h"
#include "effects/registry.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

Scene auto_scene(Scene s) {
  s.effects_auto = true;
  s.gravity = Vec3(0, 0, -9.81);
  return s;
}

EffectAnalysis analyze(const Scene& s) {
  const Model m = test::compile(s);
  const FlowScales f = flow_scales(s, m.field);
  EffectAnalysis a = analyze_effects(s, m.types[0], f, s.bodies[0]);
  EXPECT_EQ(a.chosen.bits, m.types[0].effects.bits) << "compile_model uses the same analysis";
  return a;
}

double size_of(const EffectAnalysis& a, Effect e) {
  for (const auto& [x, s] : a.size_rel)
    if (x == e) return s;
  return -1;
}

bool skipped(const EffectAnalysis& a, Effect e) {
  for (const auto& [x, why] : a.skipped)
    if (x == e) return !why.empty();
  return false;
}

TEST(AutoEffects, SteelBallInAirNeedsGravityAndDragOnly) {
  const EffectAnalysis a = analyze(auto_scene(test::sphere_scene(2.5e-3, 7850, 1.204, 1.5e-5)));
  EXPECT_EQ(a.chosen.bits, test::effects({Effect::Gravity, Effect::Drag}).bits)
      << "chosen: " << effect_names(a.chosen).size();
  EXPECT_TRUE(skipped(a, Effect::AddedMass));
  EXPECT_TRUE(skipped(a, Effect::Basset));
  EXPECT_TRUE(skipped(a, Effect::Buoyancy));
  EXPECT_LT(size_of(a, Effect::AddedMass), 1e-3);   // rho_f / (2 rho_b) = 7.7e-5
  EXPECT_NEAR(size_of(a, Effect::AddedMass), 0.5 * 1.204 / 7850, 1e-9);
  EXPECT_GT(a.reynolds, 1000);                       // settles at ~20-30 m/s
}

TEST(AutoEffects, LeafInWindNeedsEverythingRelevant) {
  Scene s = test::sphere_scene(1, 600, 1.204, 1.5e-5);
  s.bodies[0].shape = Shape::ellipsoid(0.025, 0.015, 0.00015);  // a 5 x 3 cm leaf
  s.uniform_U = Vec3(3, 0, 0);
  s.uniform_k = 0.5;
  s.uniform_epsilon = 0.5;
  const EffectAnalysis a = analyze(auto_scene(s));
  EXPECT_EQ(a.chosen.bits, test::effects({Effect::Gravity, Effect::AddedMass, Effect::Drag,
                                          Effect::MeanFlow, Effect::Turbulence, Effect::Lift})
                               .bits);
  EXPECT_TRUE(skipped(a, Effect::Basset));   // Re ~ 10^3: memory decays fast
  EXPECT_TRUE(skipped(a, Effect::Magnus));   // no spin
  EXPECT_LT(a.aspect_ratio, 0.01);
}

TEST(AutoEffects, NeutrallyBuoyantSphereInWaterNeedsAddedMassAndHistory) {
  Scene s = test::sphere_scene(1e-3, 1000, 1000, 1e-6);
  s.uniform_k = 1e-4;
  s.uniform_epsilon = 1e-4;
  const EffectAnalysis a = analyze(auto_scene(s));
  EXPECT_TRUE(a.chosen.has(Effect::AddedMass));
  EXPECT_TRUE(a.chosen.has(Effect::Basset));
  EXPECT_TRUE(a.chosen.has(Effect::Gravity));
  EXPECT_TRUE(a.chosen.has(Effect::Buoyancy));
  EXPECT_TRUE(a.chosen.has(Effect::Turbulence));
  EXPECT_NEAR(size_of(a, Effect::AddedMass), 0.5, 1e-6);  // sphere: m_a = rho V / 2
  EXPECT_GT(size_of(a, Effect::Basset), 0.5);   // comparable to the quasi-steady drag
  EXPECT_NEAR(a.terminal_speed, 0.0, 1e-9);
}

TEST(AutoEffects, BubbleIsBuoyancyAndAddedMass) {
  const EffectAnalysis a = analyze(auto_scene(test::sphere_scene(2.5e-4, 1.2, 1000, 1e-6)));
  EXPECT_TRUE(a.chosen.has(Effect::Buoyancy));
  EXPECT_TRUE(a.chosen.has(Effect::AddedMass));
  EXPECT_TRUE(a.chosen.has(Effect::Drag));
  EXPECT_FALSE(a.chosen.has(Effect::Gravity));      // the weight is 1/830 of the buoyancy
  EXPECT_NEAR(size_of(a, Effect::Buoyancy), 1000 / (1000 - 1.2), 1e-9);  // B / (B - W)
  EXPECT_GT(size_of(a, Effect::AddedMass), 100);    // m_a / m = rho_f / (2 rho_b) = 417
  EXPECT_LT(size_of(a, Effect::Gravity), 2e-3);
}

TEST(AutoEffects, SpinSelectsMagnus) {
  Scene s = auto_scene(test::sphere_scene(0.11, 60, 1.204, 1.5e-5));  // a light ball
  EXPECT_FALSE(analyze(s).chosen.has(Effect::Magnus));
  s.bodies[0].angular_velocity = Vec3(0, 30, 0);
  EXPECT_TRUE(analyze(s).chosen.has(Effect::Magnus));
}

}  // namespace
}  // namespace lrigid
