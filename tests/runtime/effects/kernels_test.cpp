// The physics kernels (effects/drag.h, plate.h, magnus.h, turbulence.h) called as the scalar
// step calls them (the Eigen wrappers drag_wrench, plate_drag_wrench, lift_wrench,
// magnus_wrench, ou_exact) and as a block of the batched steps calls them (a loop across 32
// lanes of structure-of-arrays values, in double and in float), on the same inputs: they agree
// to round-off. The kernels are also checked against closed forms written here independently.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "effects/drag.h"
#include "effects/lift.h"
#include "effects/magnus.h"
#include "effects/plate.h"
#include "effects/turbulence.h"
#include "integrate/sphere_batch.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

constexpr double kRho = 1.2, kNu = 1.5e-5;

Model model_of(const Shape& shape, double density, EffectSet e) {
  Scene s = test::sphere_scene(1, density, kRho, kNu);
  s.bodies[0].shape = shape;
  s.effects = e;
  return test::compile(s);
}

// (no added mass: the kernels do not need it, and a box's comes from the slower BEM)
EffectSet all_forces() {
  return test::effects(
      {Effect::Gravity, Effect::Buoyancy, Effect::Drag, Effect::Lift, Effect::Magnus});
}

// The body types the batched steps take: a sphere, an ellipsoid, a rectangular and an
// elliptic plate (normal along z and along x); compiled once (a box's added mass is a BEM solve)
const std::vector<Model>& models() {
  static const std::vector<Model> m = [] {
    std::vector<Model> v;
    v.push_back(model_of(Shape::sphere(0.004), 2500, all_forces()));
    v.push_back(model_of(Shape::ellipsoid(0.01, 0.006, 0.004), 900, all_forces()));
    v.push_back(model_of(Shape::box(0.06, 0.04, 0.0004), 600, all_forces()));
    v.push_back(model_of(Shape::ellipsoid(0.0005, 0.03, 0.02), 800, all_forces()));
    return v;
  }();
  return m;
}

// Inputs for a block: relative velocities over four decades (and one at rest), spins.
struct Block {
  double u[3][kBatch], w[3][kBatch];
};

Block random_block(uint32_t seed) {
  std::mt19937_64 g(seed);
  std::normal_distribution<double> n(0, 1);
  std::uniform_real_distribution<double> decade(-3, 1);
  Block b;
  for (int j = 0; j < kBatch; ++j) {
    const double speed = std::pow(10.0, decade(g)), spin = std::pow(10.0, decade(g) + 1);
    for (int a = 0; a < 3; ++a) {
      b.u[a][j] = j == 0 ? 0.0 : speed * n(g);
      b.w[a][j] = j == 1 ? 0.0 : spin * n(g);
    }
  }
  return b;
}

template <typename T>
struct BlockOut {
  T f[3][kBatch], tq[3][kBatch], lift[3][kBatch], c_lin[kBatch], p[kBatch], c_ang[3][kBatch];
};

// the kernels across a block's lanes, as integrate/*_batch.cpp call them (r_cob = 0)
template <typename T>
BlockOut<T> run_block(const BodyType& type, const Block& in) {
  const DragParams dk = drag_params(type, kRho, kNu);
  PlateParams pk;
  if (type.flat) pk = plate_params(type, kRho, kNu, true, true);
  BlockOut<T> o;
  for (int j = 0; j < kBatch; ++j) {
    T u[3], w[3], lift[3] = {0, 0, 0};
    for (int a = 0; a < 3; ++a) {
      u[a] = T(in.u[a][j]);
      w[a] = T(in.w[a][j]);
    }
    DragOut<T> d;
    if (type.flat)
      plate_kernel(pk, u, w, &d, lift);
    else
      d = ellipsoid_drag_kernel(dk, u, w);
    for (int a = 0; a < 3; ++a) {
      o.f[a][j] = d.f[a];
      o.tq[a][j] = d.tq[a];
      o.lift[a][j] = lift[a];
    }
    o.c_lin[j] = d.c_lin;
    o.p[j] = d.p;
    for (int a = 0; a < 3; ++a) o.c_ang[a][j] = d.c_ang[a];
  }
  return o;
}

// |a - b| <= tol (|b| + scale)
::testing::AssertionResult close(double a, double b, double tol, double scale) {
  if (std::abs(a - b) <= tol * (std::abs(b) + scale)) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << a << " vs " << b << " (tol " << tol << ")";
}

template <typename T>
void expect_block_matches_scalar(const BodyType& type, const Block& in, double tol) {
  const BlockOut<T> o = run_block<T>(type, in);
  for (int j = 0; j < kBatch; ++j) {
    const Vec3 u(in.u[0][j], in.u[1][j], in.u[2][j]), w(in.w[0][j], in.w[1][j], in.w[2][j]);
    DragStiffness st;
    const Wrench drag = type.flat ? plate_drag_wrench(type, u, w, kRho, kNu, &st)
                                  : drag_wrench(type, u, w, kRho, kNu, &st);
    const Wrench lift = type.flat ? lift_wrench(type, u, w, kRho, kNu) : Wrench::Zero();
    const double fs = drag.head<3>().norm() + 1e-300, ts = drag.tail<3>().norm() + 1e-300;
    const double ls = lift.head<3>().norm() + 1e-300;
    for (int a = 0; a < 3; ++a) {
      EXPECT_TRUE(close(double(o.f[a][j]), drag[a], tol, fs)) << type.name << " lane " << j;
      EXPECT_TRUE(close(double(o.tq[a][j]), drag[3 + a], tol, ts)) << type.name << " lane " << j;
      EXPECT_TRUE(close(double(o.lift[a][j]), lift[a], tol, ls)) << type.name << " lane " << j;
    }
    EXPECT_TRUE(close(double(o.c_lin[j]), st.c_lin, tol, 0)) << type.name << " lane " << j;
    EXPECT_TRUE(close(double(o.p[j]), st.p, tol, 1e-300)) << type.name << " lane " << j;
    for (int a = 0; a < 3; ++a)
      EXPECT_TRUE(close(double(o.c_ang[a][j]), st.c_ang[a], tol, 0)) << type.name << " lane " << j;
  }
}

TEST(Kernels, DragAndPlateBlockAgreesWithScalarStepInDouble) {
  for (const Model& m : models()) {
    ASSERT_TRUE(m.types[0].r_cob.isZero(0.0));
    for (uint32_t seed : {1u, 2u, 3u})
      expect_block_matches_scalar<double>(m.types[0], random_block(seed), 1e-13);
  }
}

TEST(Kernels, DragAndPlateBlockAgreesWithScalarStepInFloat) {
  for (const Model& m : models())
    for (uint32_t seed : {4u, 5u})
      expect_block_matches_scalar<float>(m.types[0], random_block(seed), 2e-4);
}

TEST(Kernels, SphereDragIsSchillerNaumann) {
  // independent of the kernel: F = 1/2 rho C_D(Re) pi r^2 |u| u with std::pow
  const Model m = model_of(Shape::sphere(0.004), 2500, test::effects({Effect::Drag}));
  const DragParams k = drag_params(m.types[0], kRho, kNu);
  const double r = 0.004;
  for (double speed : {1e-4, 1e-2, 0.3, 2.0, 10.0}) {
    const double u[3] = {0.6 * speed, 0, -0.8 * speed}, w[3] = {0, 0, 0};
    const DragOut<double> d = ellipsoid_drag_kernel(k, u, w);
    const double re = speed * 2 * r / kNu;
    const double cd = re >= 1000 ? 0.44 : 24 / re * (1 + 0.15 * std::pow(re, 0.687));
    const double f = 0.5 * kRho * cd * M_PI * r * r * speed * speed;
    EXPECT_NEAR(std::hypot(d.f[0], d.f[2]), f, 1e-12 * f) << speed;
    EXPECT_NEAR(d.f[0] / d.f[2], 0.6 / -0.8, 1e-14) << speed;
  }
}

TEST(Kernels, PlateBroadsideAndEdgewiseDragFollowTheAspectRatio) {
  // inviscid limit: broadside 1/2 rho S C_D90 U^2 with the rectangle's C_D90 (side ratio 1.5:
  // between 1.18 at 1 and 1.2 at 5, linear in 1 / aspect), edgewise APW's 1/2 rho S (A - B) U^2
  const BodyType& box = models()[2].types[0];  // 6 x 4 cm, normal along z
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
TEST(Kernels, PlateCoefficientsReduceToApwForLongStrips) {
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
TEST(Kernels, PlateFiniteSpanFollowsHelmboldsFormula) {
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

TEST(Kernels, PlateStripIntegralsAreThePlanformsOwn) {
  // closed form: a rectangle about an axis along a side is APW's strip (l S, 2/3 c^3 L,
  // c^4 L / 2 with L the span along the axis)
  PlateStrips<double> p;
  const double c1 = 0.01, c2 = 0.05, S = 4 * c1 * c2;
  plate_strips(true, c1, c2, S, 1.0, 0.0, &p);
  EXPECT_NEAR(p.KR, 2 * c1 * S, 1e-15);
  EXPECT_NEAR(p.J2, 2.0 / 3 * std::pow(c1, 3) * 2 * c2, 1e-18);
  EXPECT_NEAR(p.J3, std::pow(c1, 4) * 2 * c2 / 2, 1e-20);
  plate_strips(true, c1, c2, S, 0.0, -1.0, &p);  // about the other side
  EXPECT_NEAR(p.KR, 2 * c2 * S, 1e-15);
  EXPECT_NEAR(p.J3, std::pow(c2, 4) * 2 * c1 / 2, 1e-18);
  // ellipses: the mid-chord strip (a disk of radius a: chord 2a, span pi a / 2), which for the
  // disk is 1.18, 1.33 and 1.47 times its own strip sums 16 a^3 / 3, pi a^4 / 4, 8 a^5 / 15
  const double a = 0.03;
  plate_strips(false, a, a, M_PI * a * a, 0.6, 0.8, &p);
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
    plate_strips(true, c1, c2, S, d1, d2, &p);
    const Quadrature q = brute_strips(true, c1, c2, d1, d2);
    EXPECT_NEAR(p.KR / q.KR, 1.0, 5e-4) << ang;
    EXPECT_NEAR(p.J2 / q.J2, 1.0, 5e-4) << ang;
    EXPECT_NEAR(p.J3 / q.J3, 1.0, 5e-4) << ang;
  }
  // a square about its diagonal: the chord through the centre is sqrt(2) times the side's, but
  // the strip sums are within 6 % and 13 % of the side's (the old mid-chord form: 2.8 times)
  plate_strips(true, a, a, 4 * a * a, M_SQRT1_2, M_SQRT1_2, &p);
  PlateStrips<double> side;
  plate_strips(true, a, a, 4 * a * a, 1.0, 0.0, &side);
  EXPECT_NEAR(p.KR / side.KR, 2 * std::sqrt(2.0) / 3, 1e-12);
  EXPECT_NEAR(p.J3 / side.J3, 0.8 * std::pow(M_SQRT1_2, 3) * 4, 1e-12);
  // single precision: the lanes of the float step
  PlateStrips<float> pf;
  plate_strips(true, 0.01f, 0.05f, 0.002f, 0.6f, 0.8f, &pf);
  plate_strips(true, c1, c2, S, 0.6, 0.8, &p);
  EXPECT_NEAR(pf.J3 / p.J3, 1.0, 1e-5);
  EXPECT_NEAR(pf.KR / p.KR, 1.0, 1e-5);
}

TEST(Kernels, CirculationGateIsTheCalibratedLaw) {
  for (double re : {0.0, 50.0, 200.0, 400.0, 3000.0}) {
    const double x = std::pow(re / kLiftReCritical, double(kLiftReExponent));
    EXPECT_NEAR(circulation_gate(re), x / (1 + x), 1e-15) << re;
    EXPECT_EQ(circulation_factor(re), circulation_gate(re));
  }
  EXPECT_EQ(ipow<5>(2.0), 32.0);
  EXPECT_EQ(ipow<1>(3.0), 3.0);
}

TEST(Kernels, MagnusBlockAgreesWithScalarStep) {
  const Model m = model_of(Shape::sphere(0.02), 300, test::effects({Effect::Magnus}));
  const BodyType& t = m.types[0];
  const Block in = random_block(7);
  for (int j = 0; j < kBatch; ++j) {
    const Vec3 u(in.u[0][j], in.u[1][j], in.u[2][j]), w(in.w[0][j], in.w[1][j], in.w[2][j]);
    const Vec3 ref = magnus_wrench(t, u, w, kRho).head<3>();
    double fd[3];
    float ff[3];
    const float uf[3] = {float(u[0]), float(u[1]), float(u[2])};
    const float wf[3] = {float(w[0]), float(w[1]), float(w[2])};
    magnus_kernel(magnus_factor(t, kRho), w.data(), u.data(), fd);
    magnus_kernel(float(magnus_factor(t, kRho)), wf, uf, ff);
    // closed form C_M rho V w x u
    const Vec3 closed = kMagnus * kRho * t.volume * w.cross(u);
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(fd[a], ref[a]);
      EXPECT_TRUE(close(ff[a], ref[a], 1e-5, ref.norm()));
      EXPECT_TRUE(close(ref[a], closed[a], 1e-14, closed.norm() + 1e-300));
    }
  }
}

TEST(Kernels, OrnsteinUhlenbeckCoefficientsAreExact) {
  // independent of the kernel: exp and expm1 of the C library
  for (double alpha : {0.0, 1e-14, 1e-3, 0.7, 40.0, 2e3}) {
    for (double h : {1e-4, 1e-2}) {
      const double beta = 0.8;
      double decay, noise;
      ou_exact_kernel(alpha, beta, h, &decay, &noise);
      const double ah = alpha * h;
      const double ref_noise =
          ah > 1e-12 ? beta * std::sqrt(-std::expm1(-2 * ah) / (2 * alpha)) : beta * std::sqrt(h);
      EXPECT_NEAR(decay, std::exp(-ah), 1e-15) << alpha << " " << h;
      EXPECT_NEAR(noise, ref_noise, 1e-14 * ref_noise) << alpha << " " << h;
    }
  }
}

TEST(Kernels, OrnsteinUhlenbeckUpdateHasThomsonsDrift) {
  // the update against decay u + h a + noise z with a from well_mixed_drift (the scalar
  // step's reference form), and in float against double
  FluidSample s;
  s.sigma2 = 0.3;
  s.grad_sigma2 = Vec3(0.02, -0.05, 0.11);
  const Vec3 V(1.0, -0.4, 0.2), u0(0.3, -0.1, 0.25);
  const double z[3] = {0.5, -1.2, 0.8}, h = 5e-3, decay = 0.97, noise = 0.04;
  const Vec3 ref = decay * u0 + h * well_mixed_drift(u0, V, s) + noise * Vec3(z[0], z[1], z[2]);
  Vec3 u = u0;
  ou_update(1.0, decay, noise, s.sigma2, V.data(), s.grad_sigma2.data(), z, h, u.data());
  float uf[3] = {float(u0[0]), float(u0[1]), float(u0[2])};
  const float Vf[3] = {1.0f, -0.4f, 0.2f}, gf[3] = {0.02f, -0.05f, 0.11f};
  const float zf[3] = {0.5f, -1.2f, 0.8f};
  ou_update(1.0f, float(decay), float(noise), 0.3f, Vf, gf, zf, float(h), uf);
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(u[a], ref[a], 1e-15);
    EXPECT_NEAR(uf[a], ref[a], 1e-6);
  }
  // without the drift, and where sigma2 = 0 (no drift whatever wm says)
  Vec3 u_off = u0, u_zero = u0;
  ou_update(0.0, decay, noise, s.sigma2, V.data(), s.grad_sigma2.data(), z, h, u_off.data());
  ou_update(1.0, decay, noise, 0.0, V.data(), s.grad_sigma2.data(), z, h, u_zero.data());
  const Vec3 plain = decay * u0 + noise * Vec3(z[0], z[1], z[2]);
  EXPECT_TRUE(test::near(u_off, plain, 1e-15));
  EXPECT_TRUE(test::near(u_zero, plain, 1e-15));
}

}  // namespace
}  // namespace lrigid
