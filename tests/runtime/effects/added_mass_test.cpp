// The added mass's force (effects/added_mass.h): none on a sphere moving with the fluid, and the
// fluid's acceleration a pulls the added mass rho V / 2 of a sphere with m_a a.
#include "effects/added_mass.h"

#include <gtest/gtest.h>

#include "support/fixture.h"

namespace lrigid {
namespace {

using test::compile;
using test::sphere_scene;

TEST(AddedMass, SphereInUniformFlowFeelsNoForceWhenCoMoving) {
  Scene s = sphere_scene(0.01, 100, 1000, 1e-6);
  const Model m = compile(s);
  const Wrench w = added_mass_wrench(m.types[0], Vec3::Zero(), Vec3::Zero(), Vec3::Zero());
  EXPECT_EQ(w.norm(), 0.0);
  // fluid acceleration a drags the added mass: F = m_a a, m_a = rho V / 2
  const Vec3 a(0.3, -0.2, 0.1);
  const Wrench f = added_mass_wrench(m.types[0], Vec3::Zero(), Vec3::Zero(), a);
  EXPECT_LT((f.head<3>() - 0.5 * 1000 * m.types[0].volume * a).norm(), 1e-15);
}

}  // namespace
}  // namespace lrigid
