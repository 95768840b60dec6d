// Switching one effect off changes the acceleration by exactly M^-1 times that effect's wrench,
// in the velocity form (rk4) and the rates of the impulse form (euler, splitting).
#include <gtest/gtest.h>

#include <vector>

#include "effects/basset.h"
#include "compile/compile_model.h"
#include "effects/plan.h"
#include "effects/registry.h"
#include "integrate/dynamics.h"
#include "model/state.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

Scene plate_scene(EffectSet e) {
  Scene s = test::sphere_scene(1, 1200, 1000, 1e-6);
  s.bodies[0].shape = Shape::ellipsoid(0.02, 0.05, 0.002);
  s.bodies[0].mass_offset = Vec3(0.001, 0, -0.0002);
  s.uniform_U = Vec3(0.3, -0.1, 0.05);
  s.effects = e;
  return s;
}

// Every effect of the registry, one at a time, on a flat body with an offset centre of mass in
// a mean flow, spinning: each effect that is a wrench term for it (all but the added mass, which
// is in M itself, and the effects that move the fluid) changes the acceleration by exactly
// M^-1 times its term.
TEST(EffectSwitch, EachEffectChangesTheAccelerationByExactlyItsTerm) {
  EffectSet all;
  for (const EffectInfo& info : all_effects())
    if (info.effect != Effect::Turbulence) all.add(info.effect);  // (no seen fluctuation here)
  const Model on = test::compile(plate_scene(all));
  ASSERT_TRUE(on.types[0].flat);
  // a Basset history with a non-zero cached integral
  std::vector<double> hist(on.types[0].basset.stride(), 0.0);
  hist[3] = 0.02, hist[4] = -0.01, hist[5] = 0.03;
  Kinematics k{Vec3(0, 0, 0), Quat(0.9, 0.1, -0.3, 0.2).normalized().toRotationMatrix(),
               Vec3(0.1, 0.2, -0.3), Vec3(1.5, -2.0, 0.7), Vec3::Zero(), hist.data()};
  int switched = 0;
  for (const EffectInfo& info : all_effects()) {
    const Effect e = info.effect;
    if (e == Effect::AddedMass || !wrench_term(on.types[0], e)) continue;
    ++switched;
    EffectSet less = all;
    less.remove(e);
    const Model off = test::compile(plate_scene(less));
    Vec6 a_on, a_off;
    FluidSample fs;
    ASSERT_EQ(velocity_derivative(on, on.types[0], k, 0, &a_on, &fs), EvalResult::Ok);
    ASSERT_EQ(velocity_derivative(off, off.types[0], k, 0, &a_off, &fs), EvalResult::Ok);
    // the effect's own term in the same context
    EffectContext c;
    Vec3 uf;
    ASSERT_TRUE(effect_context(on, on.types[0], k, 0, false, &fs, &c, &uf));
    Vec6 term = wrench_term(on.types[0], e)(c);
    EXPECT_GT(term.norm(), 0) << info.name;
    if (e == Effect::Drag) {
      // the plate's separated flow comes with its drag: the share of the Munk moment it takes
      // back (BodyType::munk_back, written in the added-mass terms) goes with the drag's term
      const Mat3& S = on.types[0].munk_back;
      ASSERT_GT(S.norm(), 0);
      EXPECT_TRUE(off.types[0].munk_back.isZero(0.0));
      term.tail<3>() += c.v_rel.cross(S * c.v_rel);
    }
    EXPECT_TRUE(test::near(Vec6(a_on - a_off), Vec6(on.types[0].M_inv * term),
                           1e-12 * (1 + a_on.norm())))
        << info.name;
    // impulse form: the rates differ by the same wrench
    ImpulseRates r_on, r_off;
    ASSERT_EQ(impulse_rates(on, on.types[0], k, 0, &r_on, nullptr), EvalResult::Ok);
    ASSERT_EQ(impulse_rates(off, off.types[0], k, 0, &r_off, nullptr), EvalResult::Ok);
    EXPECT_TRUE(test::near(Vec6(r_on.rate - r_off.rate), term, 1e-12 * (1 + r_on.rate.norm())));
  }
  EXPECT_GE(switched, 6);  // gravity, buoyancy, drag, lift, Magnus, Basset at least
}

TEST(EffectSwitch, UnselectedEffectsHaveNoTerms) {
  const Scene s = plate_scene(test::effects({Effect::Gravity, Effect::Drag}));
  const Model m = test::compile(s);
  EXPECT_EQ(m.types[0].plan.terms.size(), 2u);
  EXPECT_FALSE(m.types[0].plan.sample_field);
  EXPECT_TRUE(initial_state(m, s).history.empty());  // no Basset: no history memory
}

}  // namespace
}  // namespace lrigid
