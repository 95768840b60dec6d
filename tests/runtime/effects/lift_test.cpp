// Lift, plate drag and Magnus terms against their closed forms (effects/lift.h, drag.h,
// magnus.h), and the plan that selects them.
#include <gtest/gtest.h>

#include <cmath>

#include "effects/drag.h"
#include "effects/lift.h"
#include "effects/magnus.h"
#include "effects/plan.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

using test::compile;
using test::effects;

// a thin circular disk (oblate ellipsoid), normal along body z
Model disk_model(EffectSet e, double a = 0.02, double c = 0.001) {
  Scene s = test::sphere_scene(1, 2700, 1000, 1e-6);
  s.bodies[0].shape = Shape::ellipsoid(a, a, c);
  s.effects = e;
  return compile(s);
}

TEST(Lift, FlatnessAndNormal) {
  const Model m = disk_model(effects({Effect::Lift}));
  EXPECT_TRUE(m.types[0].flat);
  EXPECT_EQ(m.types[0].normal_axis, 2);
  EXPECT_NEAR(m.types[0].plate_area, M_PI * 0.02 * 0.02, 1e-15);
  const Model sph = compile(test::sphere_scene(0.01, 2700, 1000, 1e-6));
  EXPECT_FALSE(sph.types[0].flat);
  // lift is no term for a body that is not flat; drag of a flat body is the plate drag
  EXPECT_EQ(wrench_term(sph.types[0], Effect::Lift), nullptr);
  EXPECT_NE(wrench_term(m.types[0], Effect::Lift), nullptr);
  EXPECT_NE(wrench_term(m.types[0], Effect::Drag), wrench_term(sph.types[0], Effect::Drag));
}

TEST(Lift, TranslationalLiftIsNormalToVelocityAndPeaksAt45Degrees) {
  const Model m = disk_model(effects({Effect::Lift}));
  const BodyType& t = m.types[0];
  const double rho = 1000, U = 0.3, S = t.plate_area;
  for (double deg : {0.0, 10.0, 30.0, 45.0, 60.0, 90.0}) {
    const double a = deg * M_PI / 180;
    const Vec3 u(U * std::cos(a), 0, -U * std::sin(a));
    const Wrench w = lift_wrench(t, u, Vec3::Zero(), rho);
    const Vec3 f = w.head<3>();
    EXPECT_NEAR(f.dot(u), 0.0, 1e-15) << deg;          // perpendicular to u
    EXPECT_NEAR(f.y(), 0.0, 1e-15) << deg;             // in the plane of u and n
    // |F| = rho C_T S U^2 |sin a cos a|
    const double sc = std::abs(std::sin(a) * std::cos(a));
    EXPECT_NEAR(f.norm(), rho * kLiftTranslational * S * U * U * sc, 1e-12) << deg;
  }
  // sign as in APW's 2D equations: F_x = -rho Gamma v_y, F_y = rho Gamma v_x with
  // Gamma = -C_T l v_x v_y / |v| (per unit span; x along the plate, y = n)
  const Vec3 u(0.2, 0, -0.1);
  const Vec3 f = lift_wrench(t, u, Vec3::Zero(), rho).head<3>();
  const double gamma_per_area = -kLiftTranslational * u.x() * u.z() / u.norm();
  EXPECT_NEAR(f.x(), -rho * S * gamma_per_area * u.z(), 1e-12);
  EXPECT_NEAR(f.z(), rho * S * gamma_per_area * u.x(), 1e-12);
}

TEST(Lift, RotationalLiftIsHalfRhoCRChordAreaOmegaCrossU) {
  const Model m = disk_model(effects({Effect::Lift}));
  const BodyType& t = m.types[0];
  const double rho = 1000;
  const Vec3 u(0.2, 0, 0), w(0, 3, 0);  // edgewise motion: no translational lift
  const Vec3 f = lift_wrench(t, u, w, rho).head<3>();
  const Vec3 expect = 0.5 * rho * kLiftRotational * (2 * 0.02) * t.plate_area * w.cross(u);
  EXPECT_TRUE(test::near(f, expect, 1e-12));
  // spin about the normal gives no lift
  EXPECT_NEAR(lift_wrench(t, u, Vec3(0, 0, 5), rho).norm(), 0.0, 1e-15);
}

TEST(PlateDrag, BroadsideAndEdgewiseCoefficients) {
  const Model m = disk_model(effects({Effect::Drag}));
  const BodyType& t = m.types[0];
  const double rho = 1000, U = 0.1, S = t.plate_area;
  const Vec3 fb = plate_drag_wrench(t, Vec3(0, 0, U), Vec3::Zero(), rho, 1e-6).head<3>();
  EXPECT_NEAR(fb.z(), -0.5 * rho * S * (kPlateDragA + kPlateDragB) * U * U, 1e-12);
  const Vec3 fe = plate_drag_wrench(t, Vec3(U, 0, 0), Vec3::Zero(), rho, 1e-6).head<3>();
  EXPECT_NEAR(fe.x(), -0.5 * rho * S * (kPlateDragA - kPlateDragB) * U * U, 1e-12);
}

TEST(PlateDrag, DissipativeTorqueOpposesPitch) {
  const Model m = disk_model(effects({Effect::Drag}));
  const BodyType& t = m.types[0];
  const double rho = 1000, wy = 2.0, c = 0.02, span = t.plate_area / (2 * c);
  const Vec3 tq = plate_drag_wrench(t, Vec3::Zero(), Vec3(0, wy, 0), rho, 1e-6).tail<3>();
  const double expect =
      -M_PI * rho * std::pow(c, 4) * span *
      (kPlateTorqueMu1 * t.apw_speed / c + kPlateTorqueMu2 * wy) * wy;
  EXPECT_NEAR(tq.y(), expect, 1e-15);
  EXPECT_GT(t.apw_speed, 0);
}

TEST(Magnus, BackspinLiftsABall) {
  const Model m = compile(test::sphere_scene(0.11, 60, 1.2, 1.5e-5));
  const BodyType& t = m.types[0];
  // moving +x with backspin (w along -y): force up, C_M rho V w U
  const Vec3 f = magnus_wrench(t, Vec3(20, 0, 0), Vec3(0, -10, 0), 1.2).head<3>();
  EXPECT_NEAR(f.z(), kMagnus * 1.2 * t.volume * 10 * 20, 1e-12);
  EXPECT_NEAR(f.x(), 0, 1e-15);
  EXPECT_NEAR(f.y(), 0, 1e-15);
}

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
