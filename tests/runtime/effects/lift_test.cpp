// The lift of flat bodies (effects/lift.h, lift.cpp) against APW's circulation model in 3D
// (docs/physics/lift.md): the translational lift rho C_T S U^2 sin a cos a normal to the
// velocity, the rotational lift 1/2 rho C_R l S w x u, the circulation fading below the wake
// instability; and the lift is a term of flat bodies only.
#include "effects/lift.h"

#include <gtest/gtest.h>

#include <cmath>

#include "effects/drag.h"
#include "effects/plan.h"
#include "effects/plate.h"
#include "effects_fixture.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

using effects_test::disk_model;
using test::compile;
using test::effects;

// a viscosity so small that the circulation is fully developed (Re ~ 1e10)
constexpr double kNuInviscid = 1e-12;

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
  const double C_T = plate_coefficients(t).C_T;  // APW's for every plate (physics/lift.md)
  for (double deg : {0.0, 10.0, 30.0, 45.0, 60.0, 90.0}) {
    const double a = deg * M_PI / 180;
    const Vec3 u(U * std::cos(a), 0, -U * std::sin(a));
    const Wrench w = lift_wrench(t, u, Vec3::Zero(), rho, kNuInviscid);
    const Vec3 f = w.head<3>();
    EXPECT_NEAR(f.dot(u), 0.0, 1e-15) << deg;  // perpendicular to u
    EXPECT_NEAR(f.y(), 0.0, 1e-15) << deg;     // in the plane of u and n
    // |F| = rho C_T S U^2 |sin a cos a|
    const double sc = std::abs(std::sin(a) * std::cos(a));
    EXPECT_NEAR(f.norm(), rho * C_T * S * U * U * sc, 1e-12) << deg;
  }
  // sign as in APW's 2D equations: F_x = -rho Gamma v_y, F_y = rho Gamma v_x with
  // Gamma = -C_T l v_x v_y / |v| (per unit span; x along the plate, y = n)
  const Vec3 u(0.2, 0, -0.1);
  const Vec3 f = lift_wrench(t, u, Vec3::Zero(), rho, kNuInviscid).head<3>();
  const double gamma_per_area = -C_T * u.x() * u.z() / u.norm();
  EXPECT_NEAR(f.x(), -rho * S * gamma_per_area * u.z(), 1e-12);
  EXPECT_NEAR(f.z(), rho * S * gamma_per_area * u.x(), 1e-12);
}

TEST(Lift, RotationalLiftIsHalfRhoCRChordAreaOmegaCrossU) {
  const Model m = disk_model(effects({Effect::Lift}));
  const BodyType& t = m.types[0];
  const double rho = 1000;
  const Vec3 u(0.2, 0, 0), w(0, 3, 0);  // edgewise motion: no translational lift
  const Vec3 f = lift_wrench(t, u, w, rho, kNuInviscid).head<3>();
  const double C_R = plate_coefficients(t).C_R;
  // APW's 1/2 rho C_R l^2 per unit span on the mid-chord strip of an ellipse: l the chord
  // across the axis (the disk's diameter), span S / l
  const Vec3 expect = 0.5 * rho * C_R * (2 * 0.02) * t.plate_area * w.cross(u);
  EXPECT_TRUE(test::near(f, expect, 1e-12));
  // spin about the normal gives no lift
  EXPECT_NEAR(lift_wrench(t, u, Vec3(0, 0, 5), rho, kNuInviscid).norm(), 0.0, 1e-15);
}

// the circulation fades below the wake-instability Reynolds number: f = x / (1 + x),
// x = (Re / Re_c)^n, Re = |u| w / nu with w the planform width (the disk's diameter)
TEST(Lift, CirculationFadesAtLowReynoldsNumber) {
  const Model m = disk_model(effects({Effect::Lift}));
  const BodyType& t = m.types[0];
  EXPECT_NEAR(plate_width(t), 0.04, 1e-15);
  const double rho = 1000, U = 0.1;
  const Vec3 u(U, 0, U);  // 45 degrees: largest translational lift
  const double full = lift_wrench(t, u, Vec3::Zero(), rho, kNuInviscid).head<3>().norm();
  const double nu_c = u.norm() * 0.04 / kLiftReCritical;  // Re = Re_c
  EXPECT_NEAR(lift_wrench(t, u, Vec3::Zero(), rho, nu_c).head<3>().norm() / full, 0.5, 1e-9);
  EXPECT_NEAR(circulation_factor(kLiftReCritical / 2), 1.0 / 17.0, 1e-12);
  EXPECT_LT(lift_wrench(t, u, Vec3::Zero(), rho, 100 * nu_c).head<3>().norm() / full, 1e-7);
  // a box's width is its own, not that of the area-equivalent ellipse
  Scene s = test::sphere_scene(1, 2700, 1000, 1e-6);
  s.bodies[0].shape = Shape::box(0.02, 0.1, 0.0005);
  s.effects = effects({Effect::Lift});
  const Model mb = compile(s);
  EXPECT_NEAR(plate_width(mb.types[0]), 0.02, 1e-15);
  EXPECT_NEAR(plate_chord(mb.types[0], Vec3(1, 0, 0)), 0.02, 1e-15);
  EXPECT_NEAR(plate_chord(mb.types[0], Vec3(0, 1, 0)), 0.1, 1e-15);
}

}  // namespace
}  // namespace lrigid
