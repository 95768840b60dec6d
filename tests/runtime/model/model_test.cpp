// The constant model (model/model.h, model.cpp): a body type's products with M and M^-1 take
// the diagonal shortcut when M is diagonal and give the dense products; each scheme is found
// back from its name.
#include "model/model.h"

#include <gtest/gtest.h>

#include "support/fixture.h"

namespace lrigid {
namespace {

// a paper-like box: a diagonal generalized mass whose entries span orders of magnitude
Scene sheet_scene(Integrator integrator) {
  Scene s = test::sphere_scene(0.01, 800, 1.2, 1.5e-5);
  s.bodies[0].shape = Shape::box(0.148, 0.105, 0.001);
  s.bodies[0].panels = 200;
  s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::AddedMass, Effect::Drag});
  s.integrator = integrator;
  return s;
}

TEST(MassPaths, ShortcutsApplyTheSameMatrices) {
  const Model m = test::compile(sheet_scene(Integrator::Splitting));
  const BodyType& t = m.types[0];
  ASSERT_TRUE(t.M_diagonal);
  const Vec6 y = (Vec6() << 1, -2, 3, 0.5, -0.25, 0.125).finished();
  EXPECT_TRUE(test::near(t.M_inv_times(y), Vec6(t.M_inv * y), 1e-12 * (t.M_inv * y).norm()));
  EXPECT_TRUE(test::near(t.M_times(y), Vec6(t.M * y), 1e-15 * (t.M * y).norm()));
}

TEST(Model, EachSchemeIsFoundByItsName) {
  for (const Integrator i :
       {Integrator::Euler, Integrator::RK4, Integrator::Splitting, Integrator::Strang}) {
    Integrator found = i == Integrator::Euler ? Integrator::RK4 : Integrator::Euler;
    ASSERT_TRUE(integrator_from_name(integrator_name(i), &found)) << integrator_name(i);
    EXPECT_EQ(found, i);
  }
  Integrator untouched = Integrator::Strang;
  EXPECT_FALSE(integrator_from_name("rk45", &untouched));
  EXPECT_FALSE(integrator_from_name("", &untouched));
  EXPECT_EQ(untouched, Integrator::Strang);
}

}  // namespace
}  // namespace lrigid
