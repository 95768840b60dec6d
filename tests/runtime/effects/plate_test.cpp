// The plate (effects/plate.h, plate.cpp, plate_cop.cpp) against its closed forms and the values
// docs/physics/lift.md states: the finite plate's coefficients (the broadside C_D of White's
// table, Helmbold's lift-slope ratio, APW's 2D constants for a long strip), strip theory's
// planform integrals, the circulation gate, the plate's drag (APW's quadratic drag plus the Stokes
// drag of a disk, the dissipative torque), the planform of a flat mesh, the share of the Munk
// couple a finite plate keeps, and the quasi-steady centre of pressure; and the kernel as a block
// of the batched steps calls it against the scalar step's plate_drag_wrench and lift_wrench.
#include "effects/plate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "body/tessellate.h"
#include "effects/added_mass.h"
#include "effects/drag.h"
#include "effects/lift.h"
#include "effects/plate_cop.h"
#include "effects_fixture.h"
#include "support/fixture.h"
#include "util/error.h"

namespace lrigid {
namespace {

using effects_test::all_forces;
using effects_test::disk_model;
using effects_test::kNu;
using effects_test::kRho;
using effects_test::model_of;
using test::compile;
using test::effects;

// The plates the batched steps take: a rectangular and an elliptic plate (normal along z and
// along x); compiled once
const std::vector<Model>& plate_models() {
  static const std::vector<Model> m = [] {
    std::vector<Model> v;
    v.push_back(model_of(Shape::box(0.06, 0.04, 0.0004), 600, all_forces()));
    v.push_back(model_of(Shape::ellipsoid(0.0005, 0.03, 0.02), 800, all_forces()));
    return v;
  }();
  return m;
}

TEST(Plate, BlockAgreesWithScalarStepInDouble) {
  effects_test::expect_blocks_match_scalar<double>(plate_models(), {1u, 2u, 3u}, 1e-13);
}

TEST(Plate, BlockAgreesWithScalarStepInFloat) {
  effects_test::expect_blocks_match_scalar<float>(plate_models(), {4u, 5u}, 2e-4);
}

TEST(Plate, BroadsideAndEdgewiseDragFollowTheAspectRatio) {
  // inviscid limit: broadside 1/2 rho S C_D90 U^2 with the rectangle's C_D90 (side ratio 1.5:
  // between 1.18 at 1 and 1.2 at 5, linear in 1 / aspect), edgewise APW's 1/2 rho S (A - B) U^2
  const BodyType& box = plate_models()[0].types[0];  // 6 x 4 cm, normal along z
  PlateParams k = plate_params(box, kRho, kNu, true, false);
  for (double& s : k.sf) s = 0;  // no Stokes part
  const double S = 0.06 * 0.04, U = 2.0, w[3] = {0, 0, 0};
  const double cd90 = 1.18 + (1.0 / 1.5 - 1.0) / (0.2 - 1.0) * (1.2 - 1.18);
  DragOut<double> d;
  double lift[3];
  const double broad[3] = {0, 0, -U}, edge[3] = {U, 0, 0};
  plate_kernel(k, broad, w, &d, lift);
  EXPECT_NEAR(d.f[2], 0.5 * kRho * S * cd90 * U * U, 1e-12);
  EXPECT_EQ(lift[0], 0.0);  // the lift factor is 0
  plate_kernel(k, edge, w, &d, lift);
  EXPECT_NEAR(d.f[0], -0.5 * kRho * S * (kPlateDragA - kPlateDragB) * U * U, 1e-12);
}

// The finite-span coefficients: the broadside C_D of the table (White Table 7.3 after Hoerner:
// square 1.18, disk 1.17, side ratio 5: 1.2, 10: 1.3, 20: 1.5), the pitch-rate terms (C_R, mu1,
// mu2) times Helmbold's lift-slope ratio, APW's 2D constants in the limit of an infinite strip;
// C_T and the edgewise drag A - B are APW's for every plate
TEST(Plate, CoefficientsReduceToApwForLongStrips) {
  EXPECT_NEAR(plate_broadside_cd(1, true), 1.18, 1e-12);
  EXPECT_NEAR(plate_broadside_cd(1, false), 1.17, 1e-12);
  EXPECT_NEAR(plate_broadside_cd(5, true), 1.2, 1e-12);
  EXPECT_NEAR(plate_broadside_cd(10, true), 1.3, 1e-12);
  EXPECT_NEAR(plate_broadside_cd(20, true), 1.5, 1e-12);
  EXPECT_NEAR(plate_broadside_cd(40, true), 1.95, 1e-12);   // halfway to APW's 2.4 in 1 / aspect
  EXPECT_NEAR(plate_broadside_cd(0.5, true), 1.18, 1e-12);  // aspect is >= 1 by definition
  double last = 0;
  for (double ar = 1; ar < 1e4; ar *= 1.3) {  // monotone in the aspect ratio
    EXPECT_GE(plate_broadside_cd(ar, true), last) << ar;
    last = plate_broadside_cd(ar, true);
  }
  auto type_of = [](const Shape& sh) { return model_of(sh, 600, all_forces()).types[0]; };
  const PlateCoeffs sq = plate_coefficients(type_of(Shape::box(0.05, 0.05, 0.0001)));
  EXPECT_NEAR(sq.aspect, 1.0, 1e-12);
  EXPECT_NEAR(sq.A + sq.B, 1.18, 1e-12);
  EXPECT_NEAR(sq.A - sq.B, kPlateDragA - kPlateDragB, 1e-12);
  const double r = (1.18 - 0.4) / 2.0;
  EXPECT_NEAR(sq.span_factor, r, 1e-12);
  EXPECT_NEAR(sq.B, kPlateDragB * r, 1e-12);
  EXPECT_NEAR(sq.C_T, kLiftTranslational, 1e-12);  // the translational circulation: APW's
  // the pitch-rate terms: a square's aspect ratio span^2 / S is 1, Helmbold's ratio 1/(2 + sqrt 5)
  EXPECT_NEAR(sq.span_aspect, 1.0, 1e-12);
  const double h_sq = 1.0 / (2.0 + std::sqrt(5.0));
  EXPECT_NEAR(sq.finite_span, h_sq, 1e-12);
  EXPECT_NEAR(sq.C_R, kLiftRotational * h_sq, 1e-12);
  EXPECT_NEAR(sq.mu1, kPlateTorqueMu1 * h_sq, 1e-12);
  EXPECT_NEAR(sq.mu2, kPlateTorqueMu2 * h_sq, 1e-12);
  // the aspect ratio of a plate whose normal is not body z, and of an ellipse
  const PlateCoeffs rect = plate_coefficients(type_of(Shape::box(0.0002, 0.02, 0.1)));
  EXPECT_NEAR(rect.aspect, 5.0, 1e-12);
  EXPECT_NEAR(rect.A + rect.B, 1.2, 1e-12);
  const PlateCoeffs ell = plate_coefficients(type_of(Shape::ellipsoid(0.03, 0.01, 0.0005)));
  EXPECT_NEAR(ell.aspect, 3.0, 1e-12);
  EXPECT_NEAR(ell.A + ell.B, plate_broadside_cd(3, false), 1e-12);
  // an ellipse of semi-axes a, b: span^2 / S = (2a)^2 / (pi a b) = 4/pi times its axis ratio
  EXPECT_NEAR(ell.span_aspect, 12.0 / M_PI, 1e-12);
  EXPECT_NEAR(rect.span_aspect, 5.0, 1e-12);
  EXPECT_NEAR(rect.C_R, kLiftRotational * 5.0 / (2.0 + std::sqrt(29.0)), 1e-12);
  // a long strip (side ratio 10^6) has APW's 2D constants
  const PlateCoeffs strip = plate_coefficients(type_of(Shape::ellipsoid(0.01, 1e4, 0.001)));
  EXPECT_NEAR(strip.A, kPlateDragA, 1e-4 * kPlateDragA);
  EXPECT_NEAR(strip.B, kPlateDragB, 1e-4 * kPlateDragB);
  EXPECT_NEAR(strip.C_T, kLiftTranslational, 1e-4 * kLiftTranslational);
  EXPECT_NEAR(strip.C_R, kLiftRotational, 1e-4 * kLiftRotational);
  EXPECT_NEAR(strip.mu1, kPlateTorqueMu1, 1e-4 * kPlateTorqueMu1);
  EXPECT_NEAR(strip.mu2, kPlateTorqueMu2, 1e-4 * kPlateTorqueMu2);
}

// Helmbold's lift-slope ratio a / 2 pi = AR / (2 + sqrt(AR^2 + 4)) against its two limits:
// lifting-line theory's AR / (AR + 2) for a long wing (they differ by O(1 / AR^2)) and R. T.
// Jones' slender wing pi AR / 2 (a / 2 pi = AR / 4) for a short one; a disk (AR = 4/pi): 0.2913
TEST(Plate, FiniteSpanFollowsHelmboldsFormula) {
  EXPECT_NEAR(plate_finite_span(1.0), 0.2360680, 1e-7);
  EXPECT_NEAR(plate_finite_span(4.0 / M_PI), 0.29130, 1e-5);
  for (double ar : {50.0, 200.0, 1000.0}) {
    EXPECT_NEAR(plate_finite_span(ar), ar / (ar + 2.0), 2.0 / (ar * ar)) << ar;
  }
  for (double ar : {1e-3, 1e-2}) EXPECT_NEAR(plate_finite_span(ar), ar / 4.0, ar * ar) << ar;
  double last = 0;
  for (double ar = 0.01; ar < 1e5; ar *= 1.5) {  // rising towards the 2D slope, never above it
    EXPECT_GT(plate_finite_span(ar), last) << ar;
    EXPECT_LT(plate_finite_span(ar), 1.0) << ar;
    last = plate_finite_span(ar);
  }
}

// Strip theory's planform integrals (plate_strips) against brute-force quadrature over the
// planform, written here independently: the chord l(s) of each strip across the axis found by
// clipping a line against the shape, and x = d . r summed over a fine grid of cells.
struct Quadrature {
  double KR = 0, J2 = 0, J3 = 0;
};
Quadrature brute_strips(bool box, double c1, double c2, double d1, double d2) {
  const int n = 1200;
  Quadrature q;
  const double dx = 2 * c1 / n, dy = 2 * c2 / n;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double x = -c1 + (i + 0.5) * dx, y = -c2 + (j + 0.5) * dy;
      if (!box && (x / c1) * (x / c1) + (y / c2) * (y / c2) > 1) continue;
      const double r = d1 * x + d2 * y, dA = dx * dy;
      q.J2 += r * r * dA;
      q.J3 += std::abs(r * r * r) * dA;
    }
  }
  // K_R = int l(s)^2 ds: the axis direction is (-d2, d1); the line at offset s along it, in
  // direction d, clipped against the shape
  const double a1 = -d2, a2 = d1;
  const double smax = c1 * std::abs(a1) + c2 * std::abs(a2) + std::hypot(c1, c2);
  const int m = 20000;
  const double ds = 2 * smax / m;
  for (int k = 0; k < m; ++k) {
    const double s = -smax + (k + 0.5) * ds, px = s * a1, py = s * a2;
    double len = 0;
    if (box) {
      double lo = -1e300, hi = 1e300;
      const double p[2] = {px, py}, d[2] = {d1, d2}, c[2] = {c1, c2};
      for (int ax = 0; ax < 2; ++ax) {
        if (std::abs(d[ax]) < 1e-15) {
          if (std::abs(p[ax]) > c[ax]) lo = hi = 0;
          continue;
        }
        const double t0 = (-c[ax] - p[ax]) / d[ax], t1 = (c[ax] - p[ax]) / d[ax];
        lo = std::max(lo, std::min(t0, t1));
        hi = std::min(hi, std::max(t0, t1));
      }
      len = std::max(0.0, hi - lo);
    } else {
      // (px + t d1)^2 / c1^2 + (py + t d2)^2 / c2^2 = 1
      const double A = d1 * d1 / (c1 * c1) + d2 * d2 / (c2 * c2);
      const double B = 2 * (px * d1 / (c1 * c1) + py * d2 / (c2 * c2));
      const double C = px * px / (c1 * c1) + py * py / (c2 * c2) - 1;
      const double disc = B * B - 4 * A * C;
      len = disc > 0 ? std::sqrt(disc) / A : 0;
    }
    q.KR += len * len * ds;
  }
  return q;
}

TEST(Plate, StripIntegralsAreThePlanformsOwn) {
  // closed form: a rectangle about an axis along a side is APW's strip (l S, 2/3 c^3 L,
  // c^4 L / 2 with L the span along the axis)
  PlateStrips<double> p;
  const double c1 = 0.01, c2 = 0.05, S = 4 * c1 * c2;
  plate_strips(1.0, true, false, c1, c2, c1, c2, S, 1.0, 0.0, &p);
  EXPECT_NEAR(p.KR, 2 * c1 * S, 1e-15);
  EXPECT_NEAR(p.J2, 2.0 / 3 * std::pow(c1, 3) * 2 * c2, 1e-18);
  EXPECT_NEAR(p.J3, std::pow(c1, 4) * 2 * c2 / 2, 1e-20);
  plate_strips(1.0, true, false, c1, c2, c1, c2, S, 0.0, -1.0, &p);  // about the other side
  EXPECT_NEAR(p.KR, 2 * c2 * S, 1e-15);
  EXPECT_NEAR(p.J3, std::pow(c2, 4) * 2 * c1 / 2, 1e-18);
  // ellipses: the mid-chord strip (a disk of radius a: chord 2a, span pi a / 2), which for the
  // disk is 1.18, 1.33 and 1.47 times its own strip sums 16 a^3 / 3, pi a^4 / 4, 8 a^5 / 15
  const double a = 0.03;
  plate_strips(0.0, false, true, a, a, a, a, M_PI * a * a, 0.6, 0.8, &p);
  EXPECT_NEAR(p.KR, 2 * a * M_PI * a * a, 1e-12 * std::pow(a, 3));
  EXPECT_NEAR(p.J2, 2.0 / 3 * std::pow(a, 3) * M_PI * a / 2, 1e-12 * std::pow(a, 4));
  EXPECT_NEAR(p.J3, std::pow(a, 4) / 2 * M_PI * a / 2, 1e-12 * std::pow(a, 5));
  const Quadrature disk = brute_strips(false, a, a, 0.6, 0.8);
  EXPECT_NEAR(p.KR / disk.KR, 3 * M_PI / 8, 4e-3);
  EXPECT_NEAR(disk.J3 / (8 * std::pow(a, 5) / 15), 1.0, 4e-3);  // (the quadrature itself)
  // rectangles in any direction, against quadrature (the quadrature's own error: the chord
  // jumps to 0 at a side parallel to the axis)
  for (const double ang : {0.0, 0.3, M_PI / 4, 1.1, M_PI / 2, 2.5}) {
    const double d1 = std::cos(ang), d2 = std::sin(ang);
    plate_strips(1.0, true, false, c1, c2, c1, c2, S, d1, d2, &p);
    const Quadrature q = brute_strips(true, c1, c2, d1, d2);
    EXPECT_NEAR(p.KR / q.KR, 1.0, 5e-4) << ang;
    EXPECT_NEAR(p.J2 / q.J2, 1.0, 5e-4) << ang;
    EXPECT_NEAR(p.J3 / q.J3, 1.0, 5e-4) << ang;
  }
  // a square about its diagonal: the chord through the centre is sqrt(2) times the side's, but
  // the strip sums are within 6 % and 13 % of the side's (a mid-chord strip's: 2.8 times)
  plate_strips(1.0, true, false, a, a, a, a, 4 * a * a, M_SQRT1_2, M_SQRT1_2, &p);
  PlateStrips<double> side;
  plate_strips(1.0, true, false, a, a, a, a, 4 * a * a, 1.0, 0.0, &side);
  EXPECT_NEAR(p.KR / side.KR, 2 * std::sqrt(2.0) / 3, 1e-12);
  EXPECT_NEAR(p.J3 / side.J3, 0.8 * std::pow(M_SQRT1_2, 3) * 4, 1e-12);
  // single precision: the lanes of the float step
  PlateStrips<float> pf;
  plate_strips(1.0f, true, false, 0.01f, 0.05f, 0.01f, 0.05f, 0.002f, 0.6f, 0.8f, &pf);
  plate_strips(1.0, true, false, c1, c2, c1, c2, S, 0.6, 0.8, &p);
  EXPECT_NEAR(pf.J3 / p.J3, 1.0, 1e-5);
  EXPECT_NEAR(pf.KR / p.KR, 1.0, 1e-5);
}

TEST(Plate, CirculationGateIsTheCalibratedLaw) {
  for (double re : {0.0, 50.0, 200.0, 400.0, 3000.0}) {
    const double x = std::pow(re / kLiftReCritical, double(kLiftReExponent));
    EXPECT_NEAR(circulation_gate(re), x / (1 + x), 1e-15) << re;
    EXPECT_EQ(circulation_factor(re), circulation_gate(re));
  }
  EXPECT_EQ(ipow<5>(2.0), 32.0);
  EXPECT_EQ(ipow<1>(3.0), 3.0);
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
      -M_PI * rho * std::pow(a, 4) * span * (mu1 * t.apw_speed / a + pc.mu2 * wy) * wy -
      rho * nu * t.stokes_torque.y() * wy;
  EXPECT_NEAR(tq.y(), expect, 1e-15);
  EXPECT_GT(t.stokes_torque.y(), 0);
  EXPECT_GT(t.apw_speed, 0);
}

// A flat mesh's planform is its outline: a 48-gon paper disk's area and equivalent ellipse are
// the disk's (its bounding box's square is 4/pi larger), and a box mesh keeps the box's
TEST(Plate, AFlatMeshsPlanformIsItsOutline) {
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

// A flat body with drag keeps the finite wing's share (PlateCoeffs::munk, Helmbold's lift-slope
// ratio) of its added mass's Munk couple: BodyType::munk_back takes back the rest of K_tt's
// anisotropic part, and the added-mass kernel's moment in steady translation is munk times the
// whole couple, in the velocity form (rk4) and the impulse form (euler); in an ideal fluid (no
// drag) and for round bodies nothing is taken back. (The free Kirchhoff flow of splitting and
// strang: model/kirchhoff_test.cpp.)
TEST(Plate, AFlatBodyWithDragKeepsItsShareOfTheMunkCouple) {
  const double rho = 1.2, nu = 1.5e-5, U = 3;
  Scene s = test::sphere_scene(1, 1000, rho, nu);
  auto type = [&](const Shape& shape, EffectSet e) {
    s.bodies[0].shape = shape;
    s.effects = e;
    return compile(s).types[0];
  };
  const EffectSet all = effects({Effect::AddedMass, Effect::Drag, Effect::Lift});
  const double a = 0.01;
  const std::vector<Shape> shapes = {
      Shape::box(2 * a, 2 * a, 0.02 * a), Shape::box(2 * a, 10 * a, 0.02 * a),
      Shape::ellipsoid(a, a, 1e-3 * a), Shape::ellipsoid(a, 2 * a, 1e-3 * a),
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

// The quasi-steady centre of pressure (effects/plate_cop.h; docs/physics/lift.md, "The centre of
// pressure"): the Munk couple of the plate's own added mass over the normal force of its drag
// and translational lift. A long elliptic strip's is APW's 2D one summed over its strips
// (moment ~ l^2, force ~ l per unit span): ahead = (4/3) a cos(a) / (C_T cos^2 a + (A - B cos 2a)
// / 2), 8/(3 pi) times that of APW's strip of constant chord, (pi/2) a cos a / (...), which lies
// ahead of the leading edge up to about 30 degrees. Finite plates carry less added mass per
// strip, so their centre of pressure moves back onto the plate as the aspect ratio falls, and
// every plate's reaches the centroid broadside.
TEST(Plate, CentreOfPressureFollowsTheAspectRatio) {
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
    const double expect =
        sc.munk * 4.0 / 3.0 * a * c / (sc.C_T * c * c + 0.5 * (sc.A - sc.B * std::cos(2 * al)));
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

}  // namespace
}  // namespace lrigid
