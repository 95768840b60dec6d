// Lift, plate drag and Magnus terms against their closed forms (effects/lift.h, drag.h,
// magnus.h), and the plan that selects them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "body/tessellate.h"
#include "effects/added_mass.h"
#include "effects/drag.h"
#include "effects/lift.h"
#include "effects/magnus.h"
#include "effects/plan.h"
#include "effects/plate.h"
#include "effects/plate_cop.h"
#include "support/fixture.h"
#include "util/error.h"

namespace lrigid {
namespace {

using test::compile;
using test::effects;

// a viscosity so small that the circulation is fully developed (Re ~ 1e10)
constexpr double kNuInviscid = 1e-12;

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

// A flat mesh's planform is its outline: a 48-gon paper disk's area and equivalent ellipse are
// the disk's (its bounding box's square is 4/pi larger), and a box mesh keeps the box's
TEST(Lift, AFlatMeshsPlanformIsItsOutline) {
  const int n = 48;
  const double r = 0.03, t = 7e-5;
  Scene s = test::sphere_scene(1, 1000, 1.2, 1.5e-5);
  s.bodies[0].shape =
      Shape::from_mesh(std::make_shared<const TriangleMesh>(test::polygon_prism(n, r, t)), "disk");
  s.effects = effects({Effect::Drag, Effect::Lift});
  const BodyType disk = compile(s).types[0];
  const double area = 0.5 * n * r * r * std::sin(2 * M_PI / n);
  ASSERT_TRUE(disk.flat);
  EXPECT_EQ(disk.normal_axis, 2);
  EXPECT_NEAR(disk.plate_area, area, 1e-12);
  EXPECT_NEAR(disk.ell.x() * disk.ell.y() * M_PI, area, 1e-12);
  EXPECT_NEAR(disk.ell.x(), disk.ell.y(), 1e-12);  // the outline's side ratio is the box's
  EXPECT_NEAR(plate_coefficients(disk).aspect, 1.0, 1e-12);
  // a box as a mesh: the planform of the analytic box, 4 h1 h2
  s.bodies[0].shape = Shape::from_mesh(
      std::make_shared<const TriangleMesh>(tessellate(Shape::box(0.06, 0.04, 4e-4), 500)), "leaf");
  const BodyType leaf = compile(s).types[0];
  s.bodies[0].shape = Shape::box(0.06, 0.04, 4e-4);
  const BodyType box = compile(s).types[0];
  EXPECT_NEAR(leaf.plate_area, 0.06 * 0.04, 1e-15);
  EXPECT_NEAR(leaf.plate_area, box.plate_area, 1e-15);
  EXPECT_TRUE(((leaf.ell - box.ell).array().abs() < 1e-15).all());
}

// The quasi-steady centre of pressure (effects/plate_cop.h; docs/physics/lift.md, "The centre of
// pressure"): the Munk couple of the plate's own added mass over the normal force of its drag
// and translational lift. A long elliptic strip's is APW's 2D one summed over its strips
// (moment ~ l^2, force ~ l per unit span): ahead = (4/3) a cos(a) / (C_T cos^2 a + (A - B cos 2a)
// / 2), 8/(3 pi) times that of APW's strip of constant chord, (pi/2) a cos a / (...), which lies
// ahead of the leading edge up to about 30 degrees. Finite plates carry less added mass per
// strip, so their centre of pressure moves back onto the plate as the aspect ratio falls, and
// every plate's reaches the centroid broadside.
TEST(Lift, CentreOfPressureFollowsTheAspectRatio) {
  const double rho = 1.2, nu = 1.5e-5, U = 10;  // Re ~ 10^4: the circulation fully developed
  Scene s = test::sphere_scene(1, 1000, rho, nu);
  s.effects = effects({Effect::AddedMass, Effect::Drag, Effect::Lift});
  auto type = [&](const Shape& shape) {
    s.bodies[0].shape = shape;
    return compile(s).types[0];
  };
  const double a = 0.01;  // half chord along body x
  const BodyType strip = type(Shape::ellipsoid(a, 1000 * a, 1e-3 * a));
  const PlateCoeffs sc = plate_coefficients(strip);
  const std::vector<double> degrees = {5, 10, 20, 30, 45, 60, 75, 85};
  for (double deg : degrees) {
    const double al = deg * M_PI / 180, c = std::cos(al);
    const PlateCentreOfPressure p = plate_centre_of_pressure(strip, rho, nu, U, al, 0);
    // APW's 2D terms summed over the strips, the Munk couple times the strip's share munk
    // (0.998 at this side ratio)
    const double expect = sc.munk * 4.0 / 3.0 * a * c /
                          (sc.C_T * c * c + 0.5 * (sc.A - sc.B * std::cos(2 * al)));
    EXPECT_NEAR(p.ahead / expect, 1.0, 3e-3) << deg;
    EXPECT_NEAR(p.chord, 2 * a, 1e-15);
  }
  // rectangles of side ratio 5, 2, 1 (chord 2a along x) and a disk: further back the lower the
  // aspect ratio, the disk behind the elliptic strip up to 45 degrees; on the plate (between the
  // leading edge and the centroid) from side ratio 2 down; at the centroid broadside
  const BodyType r5 = type(Shape::box(2 * a, 10 * a, 0.02 * a));
  const BodyType r2 = type(Shape::box(2 * a, 4 * a, 0.02 * a));
  const BodyType sq = type(Shape::box(2 * a, 2 * a, 0.02 * a));
  const BodyType disk = type(Shape::ellipsoid(a, a, 1e-3 * a));
  std::printf(
      "centre of pressure from the leading edge / chord (alpha: APW's 2D strip; "
      "elliptic strip 1000:1, rectangles 5:1, 2:1, 1:1, disk)\n");
  for (double deg : degrees) {
    const double al = deg * M_PI / 180, c = std::cos(al);
    double x[5];
    int i = 0;
    for (const BodyType* t : {&strip, &r5, &r2, &sq, &disk})
      x[i++] = plate_centre_of_pressure(*t, rho, nu, U, al, 0).from_leading_edge;
    const double apw = 0.5 - 0.5 * (M_PI / 2) * c /
                                 (kLiftTranslational * c * c +
                                  0.5 * (kPlateDragA - kPlateDragB * std::cos(2 * al)));
    std::printf("  %4.0f deg: %7.3f; %7.3f %7.3f %7.3f %7.3f %7.3f\n", deg, apw, x[0], x[1], x[2],
                x[3], x[4]);
    EXPECT_LT(x[1], x[2]) << deg;
    EXPECT_LT(x[2], x[3]) << deg;
    if (deg <= 45) {
      EXPECT_LT(x[0], x[4]) << deg;  // (broadside the disk's smaller drag moves it forward)
    }
    for (int j : {2, 3, 4}) {
      EXPECT_GT(x[j], 0.0) << deg << " " << j;
      EXPECT_LT(x[j], 0.5) << deg << " " << j;
    }
    if (deg <= 30) {
      EXPECT_LT(apw, 0.0) << deg;  // APW's: ahead of the leading edge
    }
  }
  for (const BodyType* t : {&strip, &r5, &sq, &disk})
    EXPECT_NEAR(plate_centre_of_pressure(*t, rho, nu, U, 0.5 * M_PI, 0).from_leading_edge, 0.5,
                1e-12);
  // bad input is refused with the reason
  EXPECT_THROW(plate_centre_of_pressure(sq, rho, nu, U, 0.3, sq.normal_axis), Error);
  EXPECT_THROW(plate_centre_of_pressure(sq, rho, nu, U, 0.0, 0), Error);
  EXPECT_THROW(plate_centre_of_pressure(type(Shape::sphere(0.01)), rho, nu, U, 0.3, 0), Error);
  s.bodies[0].mass_offset = Vec3(0.1 * a, 0, 0);  // the tensor is then about another point
  EXPECT_THROW(
      plate_centre_of_pressure(type(Shape::box(2 * a, 2 * a, 0.02 * a)), rho, nu, U, 0.3, 0),
      Error);
  s.bodies[0].mass_offset = Vec3::Zero();
  // without the added-mass effect the model has no pitching moment in steady translation
  s.effects = effects({Effect::Drag, Effect::Lift});
  const PlateCentreOfPressure bare =
      plate_centre_of_pressure(type(Shape::box(2 * a, 2 * a, 0.02 * a)), rho, nu, U, 0.3, 0);
  EXPECT_EQ(bare.from_leading_edge, 0.5);
  EXPECT_GT(bare.normal_force, 0);
}

// A flat body with drag keeps the finite wing's share (PlateCoeffs::munk, Helmbold's lift-slope
// ratio) of its added mass's Munk couple: BodyType::munk_back takes back the rest of K_tt's
// anisotropic part, and the added-mass kernel's moment in steady translation is munk times the
// whole couple, in the velocity form (rk4) and the impulse form (euler); in an ideal fluid (no
// drag) and for round bodies nothing is taken back. (The free Kirchhoff flow of splitting and
// strang: model/kirchhoff_kernels_test.cpp.)
TEST(Lift, AFlatBodyWithDragKeepsItsShareOfTheMunkCouple) {
  const double rho = 1.2, nu = 1.5e-5, U = 3;
  Scene s = test::sphere_scene(1, 1000, rho, nu);
  auto type = [&](const Shape& shape, EffectSet e) {
    s.bodies[0].shape = shape;
    s.effects = e;
    return compile(s).types[0];
  };
  const EffectSet all = effects({Effect::AddedMass, Effect::Drag, Effect::Lift});
  const double a = 0.01;
  const std::vector<Shape> shapes = {Shape::box(2 * a, 2 * a, 0.02 * a),
                                     Shape::box(2 * a, 10 * a, 0.02 * a),
                                     Shape::ellipsoid(a, a, 1e-3 * a),
                                     Shape::ellipsoid(a, 2 * a, 1e-3 * a),
                                     Shape::ellipsoid(a, 1000 * a, 1e-3 * a)};
  const double want_share[] = {plate_finite_span(1.0), plate_finite_span(5.0),
                               plate_finite_span(4.0 / M_PI), plate_finite_span(8.0 / M_PI),
                               plate_finite_span(4000.0 / M_PI)};
  for (size_t i = 0; i < shapes.size(); ++i) {
    const BodyType t = type(shapes[i], all);
    const PlateCoeffs pc = plate_coefficients(t);
    EXPECT_NEAR(pc.munk, want_share[i], 1e-12) << i;
    // K_tt is diagonal for these shapes; its smallest entry has no couple
    const Vec3 kd = t.K_fluid.block<3, 3>(0, 0).diagonal();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(t.munk_back(r, c), r == c ? (1 - pc.munk) * (kd[r] - kd.minCoeff()) : 0.0,
                    1e-12 * kd.maxCoeff())
            << i;
    const FullMass whole{t.K_fluid.data(), nullptr};  // the whole couple (nothing taken back)
    for (double deg : {10.0, 30.0, 60.0}) {
      for (double az : {0.0, 0.5, 1.2}) {  // the in-plane direction of the motion
        const double al = deg * M_PI / 180;
        Vec3 e1 = Vec3::Zero(), e2 = Vec3::Zero(), n = Vec3::Zero();
        n[t.normal_axis] = 1;
        e1[(t.normal_axis + 1) % 3] = 1;
        e2[(t.normal_axis + 2) % 3] = 1;
        const Vec3 d = std::cos(az) * e1 + std::sin(az) * e2;
        const Vec3 u = U * (std::cos(al) * d + std::sin(al) * n), w = Vec3::Zero();
        for (bool impulse : {false, true}) {
          double f[6], g[6];
          if (impulse) {
            added_mass_kernel<true>(fluid_tensor(t), u.data(), w.data(), w.data(), f);
            added_mass_kernel<true>(whole, u.data(), w.data(), w.data(), g);
          } else {
            added_mass_kernel<false>(fluid_tensor(t), u.data(), w.data(), w.data(), f);
            added_mass_kernel<false>(whole, u.data(), w.data(), w.data(), g);
          }
          const Vec3 kept(f[3], f[4], f[5]), couple(g[3], g[4], g[5]);
          EXPECT_GT(couple.norm(), 1e-9) << i << " " << deg;
          EXPECT_LE((kept - pc.munk * couple).norm(), 1e-12 * couple.norm())
              << i << " " << deg << " " << az << " " << impulse;
        }
      }
    }
  }
  // the square keeps about a quarter, the long strip all but 0.2 %
  EXPECT_NEAR(want_share[0], 0.236, 1e-3);
  EXPECT_GT(want_share[4], 0.998);
  // no drag (an ideal fluid) or a round body: nothing taken back
  EXPECT_TRUE(type(shapes[0], effects({Effect::AddedMass, Effect::Lift})).munk_back.isZero(0.0));
  EXPECT_TRUE(type(Shape::ellipsoid(a, a, 0.5 * a), all).munk_back.isZero(0.0));
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
    EXPECT_NEAR(f.dot(u), 0.0, 1e-15) << deg;          // perpendicular to u
    EXPECT_NEAR(f.y(), 0.0, 1e-15) << deg;             // in the plane of u and n
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

TEST(PlateDrag, BroadsideAndEdgewiseCoefficients) {
  const Model m = disk_model(effects({Effect::Drag}));
  const BodyType& t = m.types[0];
  const double rho = 1000, U = 0.1, S = t.plate_area;
  // APW's quadratic drag plus the Stokes drag of the disk (16 mu a broadside, 32/3 mu a edgewise)
  const double nu = 1e-6, mu = rho * nu, a = 0.02;
  const PlateCoeffs pc = plate_coefficients(t);
  EXPECT_NEAR(pc.A + pc.B, 1.17, 1e-12);                       // a disk's broadside C_D
  EXPECT_NEAR(pc.A - pc.B, kPlateDragA - kPlateDragB, 1e-12);  // APW's edgewise value
  const Vec3 fb = plate_drag_wrench(t, Vec3(0, 0, U), Vec3::Zero(), rho, nu).head<3>();
  EXPECT_NEAR(fb.z(), -0.5 * rho * S * (pc.A + pc.B) * U * U - 16 * mu * a * U,
              2e-3 * 16 * mu * a * U);
  const Vec3 fe = plate_drag_wrench(t, Vec3(U, 0, 0), Vec3::Zero(), rho, nu).head<3>();
  EXPECT_NEAR(fe.x(), -0.5 * rho * S * (pc.A - pc.B) * U * U - 32.0 / 3 * mu * a * U,
              0.1 * 32.0 / 3 * mu * a * U);
}

// Oberbeck/Jeffery resistance against its closed-form limits: sphere (6 pi R, 8 pi R^3) and thin
// disk (16 R broadside, 32/3 R edgewise, 32/3 R^3 about a diameter; Happel & Brenner 1965)
TEST(PlateDrag, StokesResistanceOfEllipsoidLimits) {
  Vec3 k, r;
  ellipsoid_stokes_resistance(Vec3(0.3, 0.3, 0.3), &k, &r);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(k[i], 6 * M_PI * 0.3, 1e-12);
    EXPECT_NEAR(r[i], 8 * M_PI * 0.027, 1e-12);
  }
  const double R = 0.5, c = 1e-5;  // c/R = 2e-5: corrections O(c/R)
  ellipsoid_stokes_resistance(Vec3(R, R, c), &k, &r);
  EXPECT_NEAR(k.z() / (16 * R), 1.0, 1e-4);
  EXPECT_NEAR(k.x() / (32.0 / 3 * R), 1.0, 1e-4);
  EXPECT_NEAR(r.x() / (32.0 / 3 * R * R * R), 1.0, 1e-4);
  EXPECT_NEAR(r.y() / (32.0 / 3 * R * R * R), 1.0, 1e-4);
  // spin about the normal: 32/3 R^3 as well (Jeffery's formula with s_j = s_k)
  EXPECT_NEAR(r.z() / (32.0 / 3 * R * R * R), 1.0, 1e-4);
  // a prolate spheroid moves more easily along its axis than across it
  ellipsoid_stokes_resistance(Vec3(1.0, 0.2, 0.2), &k, &r);
  EXPECT_LT(k.x(), k.y());
  EXPECT_NEAR(k.y(), k.z(), 1e-12);
}

// at low Reynolds number the plate drag is the Stokes drag: linear in the speed
TEST(PlateDrag, ViscousPartDominatesAtLowReynoldsNumber) {
  const Model m = disk_model(effects({Effect::Drag}));
  const BodyType& t = m.types[0];
  const double rho = 1000, nu = 1.0, U = 1e-4;  // Re = U 2a / nu = 4e-6
  const double fz = plate_drag_wrench(t, Vec3(0, 0, U), Vec3::Zero(), rho, nu)[2];
  EXPECT_NEAR(fz, -t.stokes_force.z() * rho * nu * U, 1e-5 * std::abs(fz));
  EXPECT_NEAR(t.stokes_force.z() / (16 * 0.02), 1.0, 0.08);  // c/a = 0.05: O(c/a) above 16 a
  const double fz2 = plate_drag_wrench(t, Vec3(0, 0, 2 * U), Vec3::Zero(), rho, nu)[2];
  EXPECT_NEAR(fz2 / fz, 2.0, 1e-4);
}

TEST(PlateDrag, DissipativeTorqueOpposesPitch) {
  const Model m = disk_model(effects({Effect::Drag}));
  const BodyType& t = m.types[0];
  const double rho = 1000, wy = 2.0, a = 0.02;
  const double nu = 1e-6;
  const Vec3 tq = plate_drag_wrench(t, Vec3::Zero(), Vec3(0, wy, 0), rho, nu).tail<3>();
  // at rest (Re below kPlateTorqueReMin) mu1 is scaled by (Re_fit / Re_min)^(1/2); a disk's mu1
  // and mu2 are APW's times Helmbold's lift-slope ratio at aspect ratio 4/pi (plate_coefficients)
  const PlateCoeffs pc = plate_coefficients(t);
  EXPECT_NEAR(pc.mu1, kPlateTorqueMu1 * plate_finite_span(4.0 / M_PI), 1e-12);
  const double mu1 = pc.mu1 * std::sqrt(kPlateTorqueFitRe / kPlateTorqueReMin);
  // APW's pi rho a^4 (mu1 U / a + mu2 |w|) w per unit span on the disk's mid-chord strip
  // (half chord a, span S / (2 a))
  const double span = t.plate_area / (2 * a);
  const double expect =
      -M_PI * rho * std::pow(a, 4) * span *
          (mu1 * t.apw_speed / a + pc.mu2 * wy) * wy -
      rho * nu * t.stokes_torque.y() * wy;
  EXPECT_NEAR(tq.y(), expect, 1e-15);
  EXPECT_GT(t.stokes_torque.y(), 0);
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
