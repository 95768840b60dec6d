// The contact solver (contact/solver.h) against closed forms: a sphere dropped on a wall
// rebounds with e times its speed; an oblique hit sticks (the contact point stops, the sphere
// keeps 5/7 of its tangential speed, rolling) when mu is large enough and slides with
// |J_t| = mu J_n when it is not; a box corner takes the textbook impulse; energy never grows;
// double and float agree to float round-off.
#include "contact/solver.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <memory>
#include <random>

#include "contact/pass.h"
#include "model/model.h"
#include "support/fixture.h"
#include "util/error.h"

namespace lrigid {
namespace {

// M^-1 of a rigid body of mass m and principal inertia I (body frame), row-major
std::array<double, 36> diag_inverse(double m, const Vec3& I) {
  std::array<double, 36> Mi{};
  for (int a = 0; a < 3; ++a) {
    Mi[7 * a] = 1 / m;
    Mi[7 * (a + 3)] = 1 / I[a];
  }
  return Mi;
}

std::array<double, 36> row_major(const Mat6& M) {
  std::array<double, 36> r{};
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) r[6 * i + j] = M(i, j);
  return r;
}

// kinetic energy 1/2 xi^T M xi of xi = (v, w), M = Minv^-1
double energy(const std::array<double, 36>& Minv, const double* v, const double* w) {
  Mat6 Mi;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) Mi(i, j) = Minv[6 * i + j];
  Vec6 xi;
  xi << v[0], v[1], v[2], w[0], w[1], w[2];
  return 0.5 * xi.dot(Mi.ldlt().solve(xi));
}

// velocity of the point r of a body moving with (v, w)
Vec3 point_velocity(const double* v, const double* w, const double* r) {
  return Vec3(v[0], v[1], v[2]) + Vec3(w[0], w[1], w[2]).cross(Vec3(r[0], r[1], r[2]));
}

constexpr double kR = 0.05, kDensity = 2500;  // a 5 cm pebble, kg/m^3

struct Sphere {
  double m = 4.0 / 3 * M_PI * kR * kR * kR * kDensity;
  double I = 0.4 * m * kR * kR;
  std::array<double, 36> Minv = diag_inverse(m, Vec3::Constant(I));
};

ContactParams sphere_params(double e, double mu) {
  return contact_params(Shape::sphere(kR), Vec3::Zero(), e, mu, 0);
}

TEST(Contact, SphereDroppedVerticallyReboundsWithESpeed) {
  const Sphere s;
  const double n[3] = {0, 0, 1}, v[3] = {0, 0, -3}, w[3] = {0, 0, 0};
  for (double e : {0.0, 0.3, 0.6, 1.0}) {
    const ContactParams k = sphere_params(e, 0.5);
    double r[3];
    ellipsoid_support_point(k, n, r);
    EXPECT_NEAR(r[2], -kR, 1e-15);
    const ContactOut<double> o = contact_kernel(k, s.Minv.data(), v, w, r, n, 1e-4);
    EXPECT_EQ(o.active, 1.0);
    EXPECT_NEAR(v[2] + o.dv[2], 3 * e, 1e-12) << e;
    EXPECT_NEAR(o.jn, (1 + e) * 3 * s.m, 1e-12) << e;
    EXPECT_NEAR(o.jt, 0, 1e-15);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(o.dw[a], 0, 1e-12);
  }
  // with added mass in the generalized mass (a compiled model: a sphere in water) the rebound
  // speed is still e v: the impulse is larger by the fluid's share
  Scene sc = test::sphere_scene(kR, kDensity, 1000, 1e-6);
  sc.effects = test::effects({Effect::Gravity, Effect::AddedMass});
  const Model model = test::compile(sc);
  const BodyType& t = model.types[0];
  EXPECT_GT(t.M(0, 0), t.mass * 1.1);  // m + rho V / 2
  const ContactParams k = contact_params(t, 0.5, 0.5, 0);
  const std::array<double, 36> Minv = row_major(t.M_inv);
  double r[3];
  ellipsoid_support_point(k, n, r);
  const ContactOut<double> o = contact_kernel(k, Minv.data(), v, w, r, n, 0.0);
  EXPECT_NEAR(v[2] + o.dv[2], 1.5, 1e-12);
  EXPECT_NEAR(o.jn, 1.5 * 3 * t.M(2, 2), 1e-9);
}

TEST(Contact, ObliqueHitSticksWithLargeFrictionAndRolls) {
  const Sphere s;
  const double e = 0.6, n[3] = {0, 0, 1}, v[3] = {2, 0, -3}, w[3] = {0, 0, 0};
  const ContactParams k = sphere_params(e, 1.0);
  double r[3];
  ellipsoid_support_point(k, n, r);
  const ContactOut<double> o = contact_kernel(k, s.Minv.data(), v, w, r, n, 0.0);
  double v1[3], w1[3];
  for (int a = 0; a < 3; ++a) v1[a] = v[a] + o.dv[a], w1[a] = w[a] + o.dw[a];
  const Vec3 vc = point_velocity(v1, w1, r);
  // the contact point stops sliding; the normal speed is e v
  EXPECT_NEAR(vc.x(), 0, 1e-12);
  EXPECT_NEAR(vc.y(), 0, 1e-12);
  EXPECT_NEAR(vc.z(), 3 * e, 1e-12);
  // a solid sphere that grips keeps 5/7 of its tangential speed and rolls: w R = v
  EXPECT_NEAR(v1[0], 2.0 * 5 / 7, 1e-12);
  EXPECT_NEAR(w1[1] * kR, v1[0], 1e-12);
  EXPECT_LT(o.jt, 1.0 * o.jn);
  EXPECT_NEAR(o.jt, s.m * 2.0 * 2 / 7, 1e-12);  // m (v - 5/7 v)
}

TEST(Contact, ObliqueHitSlidesWithSmallFrictionAndJtIsMuJn) {
  const Sphere s;
  const double e = 0.6, mu = 0.05, n[3] = {0, 0, 1}, v[3] = {2, 1, -3}, w[3] = {0, 0, 0};
  const ContactParams k = sphere_params(e, mu);
  double r[3];
  ellipsoid_support_point(k, n, r);
  const ContactOut<double> o = contact_kernel(k, s.Minv.data(), v, w, r, n, 0.0);
  EXPECT_NEAR(o.jt, mu * o.jn, 1e-12 * o.jn);
  EXPECT_NEAR(o.jn, (1 + e) * 3 * s.m, 1e-12);
  double v1[3], w1[3];
  for (int a = 0; a < 3; ++a) v1[a] = v[a] + o.dv[a], w1[a] = w[a] + o.dw[a];
  // the friction impulse opposes the slip (2, 1)/sqrt(5) and the point still slides that way
  const double slip = std::sqrt(5.0);
  EXPECT_NEAR(o.J[0], -mu * o.jn * 2 / slip, 1e-12);
  EXPECT_NEAR(o.J[1], -mu * o.jn * 1 / slip, 1e-12);
  const Vec3 vc = point_velocity(v1, w1, r);
  EXPECT_NEAR(vc.z(), 3 * e, 1e-12);
  EXPECT_GT(vc.x(), 0);
  EXPECT_NEAR(vc.y() / vc.x(), 0.5, 1e-12);
  EXPECT_LT(energy(s.Minv, v1, w1), energy(s.Minv, v, w));
}

// The textbook impulse of a frictionless hit at a box corner, body with diagonal M:
// j = -(1 + e) v_rel.n / (n.M^-1 n + (r x n).I^-1 (r x n)).
TEST(Contact, BoxCornerHitIsTheTextbookImpulse) {
  const Vec3 size(0.4, 0.2, 0.1);
  const double m = 3.0;
  const Vec3 I(m / 12 * (size.y() * size.y() + size.z() * size.z()),
               m / 12 * (size.x() * size.x() + size.z() * size.z()),
               m / 12 * (size.x() * size.x() + size.y() * size.y()));
  const std::array<double, 36> Minv = diag_inverse(m, I);
  const double e = 0.4;
  const ContactParams k = contact_params(Shape::box(size.x(), size.y(), size.z()),
                                         Vec3::Zero(), e, 0.0, 0);
  ASSERT_EQ(k.count(), 8u);
  // a tilted wall normal so that every term of the formula counts
  const Vec3 nn = Vec3(0.2, -0.3, 1).normalized();
  const double n[3] = {nn.x(), nn.y(), nn.z()};
  const double v[3] = {0.5, -0.2, -2}, w[3] = {0.3, -1.2, 0.7};
  for (size_t c = 0; c < k.count(); ++c) {
    const double* r = &k.points[3 * c];
    const Vec3 rv(r[0], r[1], r[2]);
    const double vn = point_velocity(v, w, r).dot(nn);
    if (vn >= 0) continue;  // corners leaving the wall take no impulse
    const Vec3 rxn = rv.cross(nn);
    const double j = -(1 + e) * vn / (1 / m + rxn.cwiseProduct(rxn).cwiseQuotient(I).sum());
    const ContactOut<double> o = contact_kernel(k, Minv.data(), v, w, r, n, 0.0);
    EXPECT_NEAR(o.jn, j, 1e-12 * j) << "corner " << c;
    EXPECT_NEAR(o.jt, 0, 1e-12 * j);
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(o.dv[a], j * n[a] / m, 1e-12) << c;
      EXPECT_NEAR(o.dw[a], j * rxn[a] / I[a], 1e-11) << c;
    }
    double v1[3], w1[3];
    for (int a = 0; a < 3; ++a) v1[a] = v[a] + o.dv[a], w1[a] = w[a] + o.dw[a];
    EXPECT_NEAR(point_velocity(v1, w1, r).dot(nn), -e * vn, 1e-12);
  }
}

// random symmetric positive definite 6x6 (a body with added mass couples everything)
std::array<double, 36> random_minv(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  Mat6 A;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) A(i, j) = u(rng);
  Mat6 M = A * A.transpose() + 0.2 * Mat6::Identity();
  M.block<3, 3>(0, 0) += 2 * Mat3::Identity();  // a mass that dominates, as in practice
  return row_major(M.inverse());
}

TEST(Contact, EnergyNeverIncreasesAndTheContactPointNeverApproaches) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1), pos(0, 1);
  int active = 0, slid = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const std::array<double, 36> Minv = random_minv(rng);
    ContactParams k;
    k.restitution = pos(rng);
    k.friction = 2 * pos(rng) * pos(rng);
    const Vec3 nn = Vec3(u(rng), u(rng), u(rng)).normalized();
    const double n[3] = {nn.x(), nn.y(), nn.z()};
    const double r[3] = {0.5 * u(rng), 0.5 * u(rng), 0.5 * u(rng)};
    const double v[3] = {u(rng), u(rng), u(rng)}, w[3] = {3 * u(rng), 3 * u(rng), 3 * u(rng)};
    const ContactOut<double> o = contact_kernel(k, Minv.data(), v, w, r, n, 0.01 * pos(rng));
    double v1[3], w1[3];
    for (int a = 0; a < 3; ++a) v1[a] = v[a] + o.dv[a], w1[a] = w[a] + o.dw[a];
    const double e0 = energy(Minv, v, w), e1 = energy(Minv, v1, w1);
    ASSERT_LE(e1, e0 * (1 + 1e-12)) << "trial " << trial;
    const double vn0 = point_velocity(v, w, r).dot(nn), vn1 = point_velocity(v1, w1, r).dot(nn);
    if (vn0 < 0) {
      ASSERT_EQ(o.active, 1.0);
      ASSERT_GE(vn1, -1e-12) << "trial " << trial;
      ASSERT_LE(o.jt, k.friction * o.jn * (1 + 1e-9) + 1e-15) << "trial " << trial;
      ++active;
      slid += o.jt > 0.999 * k.friction * o.jn && o.jt > 0;
    } else {
      ASSERT_EQ(o.active, 0.0);  // a point leaving the wall takes no impulse
      ASSERT_EQ(o.jn, 0.0);
    }
  }
  EXPECT_GT(active, 1000);
  EXPECT_GT(slid, 100);  // both regimes were exercised
}

TEST(Contact, DoubleAndFloatAgreeToFloatRoundOff) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1), pos(0, 1);
  double worst = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const std::array<double, 36> Minv = random_minv(rng);
    ContactParams k;
    k.restitution = pos(rng);
    k.friction = pos(rng);
    const Vec3 nn = Vec3(u(rng), u(rng), u(rng)).normalized();
    const double n[3] = {nn.x(), nn.y(), nn.z()};
    const double r[3] = {0.5 * u(rng), 0.5 * u(rng), 0.5 * u(rng)};
    const double v[3] = {u(rng), u(rng), u(rng)}, w[3] = {u(rng), u(rng), u(rng)};
    float Mf[36], nf[3], rf[3], vf[3], wf[3];
    for (int i = 0; i < 36; ++i) Mf[i] = float(Minv[i]);
    for (int a = 0; a < 3; ++a)
      nf[a] = float(n[a]), rf[a] = float(r[a]), vf[a] = float(v[a]), wf[a] = float(w[a]);
    const ContactOut<double> od = contact_kernel(k, Minv.data(), v, w, r, n, 0.001);
    const ContactOut<float> of = contact_kernel(k, Mf, vf, wf, rf, nf, 0.001f);
    ASSERT_EQ(od.active, double(of.active));
    const double scale = std::abs(od.jn) + 1e-3;
    // a case at the stick/slide boundary may fall either way in float: skip those
    if (std::abs(od.jt - k.friction * od.jn) < 1e-4 * scale) continue;
    for (int a = 0; a < 3; ++a) {
      worst = std::max(worst, std::abs(od.J[a] - double(of.J[a])) / scale);
      worst = std::max(worst, std::abs(od.dv[a] - double(of.dv[a])) / (std::abs(od.dv[a]) + 1));
    }
  }
  EXPECT_LT(worst, 1e-4) << "relative difference, float vs double";
}

TEST(Contact, PositionCorrectionMovesOutAlongTheNormalAndLeavesVelocitiesAlone) {
  const Sphere s;
  const ContactParams k = sphere_params(0.5, 0.5);
  const double n[3] = {0, 0.6, 0.8}, w[3] = {0, 0, 0};
  double r[3];
  ellipsoid_support_point(k, n, r);
  // penetrating but leaving the wall: no impulse, only the correction
  const double v[3] = {1, 0, 0.5};
  const ContactOut<double> o = contact_kernel(k, s.Minv.data(), v, w, r, n, 0.002);
  EXPECT_EQ(o.active, 0.0);
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(o.dv[a], 0.0);
    EXPECT_EQ(o.dw[a], 0.0);
    EXPECT_NEAR(o.dx[a], 0.002 * n[a], 1e-18);
  }
  // not touching (depth < 0): nothing at all
  const double down[3] = {0, 0, -1};
  const ContactOut<double> far = contact_kernel(k, s.Minv.data(), down, w, r, n, -0.01);
  EXPECT_EQ(far.active, 0.0);
  EXPECT_EQ(far.dx[2], 0.0);
}

TEST(Contact, BoxLandingFlatStopsWithoutSpinningWithZeroRestitution) {
  // (contact_resolve: the 4 lower corners at once, projected Gauss-Seidel)
  const Vec3 size(0.3, 0.2, 0.02);  // a thin plate
  const double m = 0.5;
  const Vec3 I(m / 12 * (size.y() * size.y() + size.z() * size.z()),
               m / 12 * (size.x() * size.x() + size.z() * size.z()),
               m / 12 * (size.x() * size.x() + size.y() * size.y()));
  const std::array<double, 36> Minv = diag_inverse(m, I);
  const ContactParams k =
      contact_params(Shape::box(size.x(), size.y(), size.z()), Vec3::Zero(), 0.0, 0.8, 0);
  // the 4 lower corners touch the ground together
  std::vector<double> r, n, depth;
  for (size_t c = 0; c < k.count(); ++c)
    if (k.points[3 * c + 2] < 0) {
      for (int a = 0; a < 3; ++a) r.push_back(k.points[3 * c + a]);
      n.insert(n.end(), {0.0, 0.0, 1.0});
      depth.push_back(1e-4);
    }
  ASSERT_EQ(depth.size(), 4u);
  double v[3] = {0.5, 0, -2}, w[3] = {0, 0, 0}, dx[3];
  const double e0 = energy(Minv, v, w);
  const int carrying =
      contact_resolve(k, Minv.data(), v, w, 4, r.data(), n.data(), depth.data(), 20, dx);
  EXPECT_EQ(carrying, 4);
  // the sweeps stop when no impulse changes by more than kContactTolerance of the largest: a
  // velocity error of about that fraction of the 2 m/s impact
  const double tol = 2.0 * kContactTolerance;
  EXPECT_NEAR(v[2], 0, tol);
  // the friction cone: total tangential impulse mu (m 2 m/s) = 0.8 m/s of speed, more than
  // the 0.5 m/s sliding: it stops
  EXPECT_NEAR(v[0], 0, tol);
  // (rad/s: the corners' velocities w x r, r about 0.18 m, are within tol)
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(w[a], 0, tol / 0.18) << a;
  EXPECT_LT(energy(Minv, v, w), e0);
  EXPECT_NEAR(dx[2], 1e-4, 1e-18);
  for (int i = 0; i < 4; ++i) EXPECT_GE(point_velocity(v, w, &r[3 * i]).z(), -tol);
  // with mu = 0.1 it slides on: the tangential impulse is mu times the normal one, m 2 m/s,
  // which takes 0.2 m/s off the 0.5 m/s. (Rotation locked, M^-1 without its angular block: a
  // free plate also pitches under the friction at its bottom, and its impulses have no closed
  // form.)
  const ContactParams slippery =
      contact_params(Shape::box(size.x(), size.y(), size.z()), Vec3::Zero(), 0.0, 0.1, 0);
  std::array<double, 36> locked = Minv;
  for (int a = 3; a < 6; ++a) locked[7 * a] = 0;
  double v2[3] = {0.5, 0, -2}, w2[3] = {0, 0, 0};
  contact_resolve(slippery, locked.data(), v2, w2, 4, r.data(), n.data(), depth.data(), 20, dx);
  EXPECT_NEAR(v2[2], 0, tol);
  EXPECT_NEAR(v2[0], 0.3, tol);
}

// the 4 lower corners of a box of the given size (body frame) and their common normal, +z
std::vector<double> lower_corners(const ContactParams& k) {
  std::vector<double> r;
  for (size_t c = 0; c < k.count(); ++c)
    if (k.points[3 * c + 2] < 0 && !k.on_edge(c))
      for (int a = 0; a < 3; ++a) r.push_back(k.points[3 * c + a]);
  return r;
}

// A 6 x 4 cm leaf, 0.4 mm thick, 5.76e-4 kg, lying on the ground: its diagonal M^-1 and M
// (row-major), its contact parameters (e 0.1, mu 0.6, rest_speed 0.08 m/s), its 4 lower
// corners and their normal +z.
struct LyingLeaf {
  Vec3 size{0.06, 0.04, 0.0004};
  double m = 5.76e-4;
  std::array<double, 36> Minv{}, M{};
  ContactParams k;
  std::vector<double> r, n = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  LyingLeaf() {
    const Vec3 I(m / 12 * (size.y() * size.y() + size.z() * size.z()),
                 m / 12 * (size.x() * size.x() + size.z() * size.z()),
                 m / 12 * (size.x() * size.x() + size.y() * size.y()));
    Minv = diag_inverse(m, I);
    for (int a = 0; a < 6; ++a) M[7 * a] = 1 / Minv[7 * a];
    k = contact_params(Shape::box(size.x(), size.y(), size.z()), Vec3::Zero(), 0.1, 0.6, 0.01);
    k.rest_speed = 0.08;
    r = lower_corners(k);
  }
};

TEST(Contact, ALeafLyingOnTheGroundStopsAtOnceWhereTheSweepsStopIt) {
  // a 6 x 4 cm leaf after one 2 ms step of gravity on the ground: contact_rest's certificate
  // holds and stops it exactly; the sweeps alone (no M) reach the same to their tolerance
  const LyingLeaf leaf;
  const auto& [size, m, Minv, M, k, r, n] = leaf;
  ASSERT_EQ(r.size(), 12u);
  const std::vector<double> depth = {2e-5, 1e-5, 2e-5, 1e-5};
  double v[3] = {0.004, -0.002, -9.81 * 0.002}, w[3] = {0.01, -0.02, 0.03}, dx[3];
  double vs[3] = {v[0], v[1], v[2]}, ws[3] = {w[0], w[1], w[2]};
  EXPECT_EQ(contact_resolve(k, Minv.data(), v, w, 4, r.data(), n.data(), depth.data(),
                            kContactPasses, dx, M.data()),
            3);
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(v[a], 0.0);
    EXPECT_EQ(w[a], 0.0);
  }
  EXPECT_DOUBLE_EQ(dx[2], 2e-5);
  contact_resolve(k, Minv.data(), vs, ws, 4, r.data(), n.data(), depth.data(), 200, dx);
  for (int i = 0; i < 4; ++i) EXPECT_LT(point_velocity(vs, ws, &r[3 * i]).norm(), 1e-6) << i;

  // pushed along the ground harder than friction holds: no certificate, the sweeps let it slide
  double vp[3] = {0.5, 0, -0.02}, wp[3] = {0, 0, 0};
  EXPECT_EQ(contact_rest(k, M.data(), vp, wp, 4, r.data(), n.data()), 0);
  EXPECT_EQ(vp[0], 0.5);
  // tipping over an edge: the moment asks for a centre of pressure 15 cm from the centre, past
  // the 3 cm edge
  double vt[3] = {0, 0, -0.01}, wt[3] = {0, 5, 0};
  EXPECT_EQ(contact_rest(k, M.data(), vt, wt, 4, r.data(), n.data()), 0);
  // lifted by the flow: it does not press
  double vl[3] = {0, 0, 0.01}, wl[3] = {0, 0, 0};
  EXPECT_EQ(contact_rest(k, M.data(), vl, wl, 4, r.data(), n.data()), 0);
  // approaching faster than rest_speed: it bounces, the sweeps decide
  double vb[3] = {0, 0, -0.5}, wb[3] = {0, 0, 0};
  contact_resolve(k, Minv.data(), vb, wb, 4, r.data(), n.data(), depth.data(), kContactPasses,
                  dx, M.data());
  EXPECT_NEAR(vb[2], 0.05, 1e-6);  // e = 0.1
}

TEST(Contact, ASpeculativePointApproachesNoFasterThanClosesItsGapInTheHorizon) {
  // the leaf above lying tilted: the corners at x = -3 cm touch (1e-5 m deep), those at +3 cm are
  // 1e-5 m off the ground, falling at g h after a 2 ms step. As speculative points (depth
  // -1e-5, horizon 2 ms) they may approach at 5 mm/s, no faster: the leaf stops nearly level.
  // Without them only the touching edge holds it, and it tips onto the other edge at 1.5 times
  // the speed it fell.
  const double h = 2e-3, gap = 1e-5;
  const LyingLeaf leaf;
  const auto& [size, m, Minv, M, k, r, n] = leaf;
  ASSERT_EQ(r.size(), 12u);
  std::vector<double> depth(4);
  for (int i = 0; i < 4; ++i) depth[size_t(i)] = r[3 * size_t(i)] < 0 ? 1e-5 : -gap;
  const double tol = 1e-6;
  for (const double horizon : {h, 0.0}) {
    double v[3] = {0, 0, -9.81 * h}, w[3] = {0, 0, 0}, dx[3];
    const double e0 = energy(Minv, v, w);
    const int carrying = contact_resolve(k, Minv.data(), v, w, 4, r.data(), n.data(),
                                         depth.data(), 200, dx, M.data(), horizon);
    EXPECT_LE(energy(Minv, v, w), e0);
    double slowest = HUGE_VAL;
    for (int i = 0; i < 4; ++i) {
      const double vn = point_velocity(v, w, &r[3 * i]).z();
      if (depth[size_t(i)] >= 0) {
        EXPECT_GE(vn, -tol) << "a touching point never approaches";
      } else {
        slowest = std::min(slowest, vn);
        if (horizon > 0) {
          EXPECT_NEAR(vn, -gap / horizon, tol) << "it closes the gap, no more";
        }
      }
    }
    if (horizon > 0) {
      EXPECT_EQ(carrying, 4);
      EXPECT_LT(std::abs(w[1]), 0.1) << "nearly level: 5 mm/s over 6 cm";
    } else {
      EXPECT_EQ(carrying, 2);
      // the impulse that stops one edge of a plate falling at V (K = 1/m + (L/2)^2 / I = 4/m
      // along the normal) turns it at 1.5 V / L and sends the other edge down at 1.5 V (a
      // thin plate's closed form: the 0.4 mm thickness changes it by 5e-5)
      const double V = 9.81 * h, L = size.x();
      EXPECT_NEAR(slowest / (-1.5 * V), 1.0, 1e-4) << "it tips onto the other edge";
      EXPECT_NEAR(std::abs(w[1]) / (1.5 * V / L), 1.0, 1e-4);
    }
  }
  // three corners touching, the fourth speculative, the leaf at rest but for one step of
  // gravity: contact_rest's certificate on the three touching corners stops it exactly (v = w =
  // 0 keeps the fourth 1e-5 m off, within its constraint, carrying nothing); the sweeps alone
  // (no M) come to the same
  {
    std::vector<double> d3 = {1e-5, 1e-5, 1e-5, 1e-5};
    d3[3] = -gap;
    double v3[3] = {0, 0, -9.81 * h}, w3[3] = {0, 0, 0}, dx[3];
    double vs[3] = {v3[0], v3[1], v3[2]}, ws[3] = {0, 0, 0};
    EXPECT_EQ(contact_resolve(k, Minv.data(), v3, w3, 4, r.data(), n.data(), d3.data(), 200, dx,
                              M.data(), h),
              3);
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(v3[a], 0.0);
      EXPECT_EQ(w3[a], 0.0);
    }
    contact_resolve(k, Minv.data(), vs, ws, 4, r.data(), n.data(), d3.data(), 200, dx,
                    static_cast<const double*>(nullptr), h);
    for (int i = 0; i < 4; ++i) EXPECT_LT(point_velocity(vs, ws, &r[3 * i]).norm(), 1e-6) << i;
  }
  // a speculative point moving away takes no impulse (points never pull): the leaf rising at
  // its +x edge is left alone there
  double v[3] = {0, 0, 0}, w[3] = {0, -0.5, 0}, dx[3];
  for (int i = 0; i < 4; ++i)
    if (depth[size_t(i)] < 0) {
      ASSERT_GT(point_velocity(v, w, &r[3 * i]).z(), 0);
    }
  contact_resolve(k, Minv.data(), v, w, 4, r.data(), n.data(), depth.data(), 200, dx, M.data(),
                  h);
  for (int i = 0; i < 4; ++i)
    if (depth[size_t(i)] < 0) {
      EXPECT_GT(point_velocity(v, w, &r[3 * i]).z(), -gap / h);
    }
}

TEST(Contact, TheRestCertificateHoldsOnlyWhereTheSweepsStopTheBody) {
  // random plates (a generalized mass with coupling, as added mass gives), random small
  // velocities on a plane: wherever contact_rest stops a body, the sweeps alone stop it too
  // (every point still to 1e-6 of the initial point speeds); and it catches most of the
  // cases the sweeps stop (192 of 234 when written)
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  int held = 0, swept_still = 0, both = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Vec3 size(0.02 + 0.1 * std::abs(u(rng)), 0.02 + 0.1 * std::abs(u(rng)), 0.001);
    const double m = 1e-3 * (1 + std::abs(u(rng)));
    Mat6 A = Mat6::Zero();
    for (int a = 0; a < 3; ++a) A(a, a) = m;
    A(3, 3) = m / 12 * size.y() * size.y(), A(4, 4) = m / 12 * size.x() * size.x();
    A(5, 5) = A(3, 3) + A(4, 4);
    Mat6 C = Mat6::Random() * 0.2;
    const Mat6 scale = A.diagonal().cwiseSqrt().asDiagonal();
    A += scale * (C * C.transpose()) * scale;  // symmetric positive definite, coupled
    const std::array<double, 36> M = row_major(A), Minv = row_major(Mat6(A.inverse()));
    ContactParams k = contact_params(Shape::box(size.x(), size.y(), size.z()), Vec3::Zero(), 0,
                                     0.2 + 0.6 * std::abs(u(rng)), 0);
    k.rest_speed = 0.1;
    const std::vector<double> r = lower_corners(k);
    const std::vector<double> n = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    const std::vector<double> depth = {0, 0, 0, 0};
    double v[3] = {0.02 * u(rng), 0.02 * u(rng), -0.02 * std::abs(u(rng))};
    double w[3] = {0.1 * u(rng), 0.1 * u(rng), 0.1 * u(rng)};
    bool slow = true;
    double speed = 0;
    for (int i = 0; i < 4; ++i) {
      const Vec3 vc = point_velocity(v, w, &r[3 * i]);
      slow = slow && vc.z() >= -k.rest_speed;
      speed = std::max(speed, vc.norm());
    }
    if (!slow) continue;
    double vc[3] = {v[0], v[1], v[2]}, wc[3] = {w[0], w[1], w[2]};
    const bool certified = contact_rest(k, M.data(), vc, wc, 4, r.data(), n.data()) > 0;
    double dx[3];
    contact_resolve(k, Minv.data(), v, w, 4, r.data(), n.data(), depth.data(), 2000, dx);
    double after = 0;
    for (int i = 0; i < 4; ++i) after = std::max(after, point_velocity(v, w, &r[3 * i]).norm());
    const bool still = after <= 1e-6 * speed;
    held += certified;
    swept_still += still;
    both += certified && still;
    if (certified) {
      EXPECT_TRUE(still) << "trial " << trial << ": left " << after << " of " << speed;
    }
  }
  EXPECT_GT(held, 100) << swept_still;
  EXPECT_GE(both, held);
  EXPECT_GT(double(held), 0.6 * swept_still) << held << " certified of " << swept_still;
}

TEST(Contact, APebbleRestingOnOnePointWithRollingResistanceStopsAtOnce) {
  // a 5 cm pebble (mu_r = 0.05) after a 2 ms step of gravity and a light push on the ground: the
  // impulse that stops it, P = -m v, L = -I w, presses, lies in the cone and leaves the
  // resistance a moment L - r x P within mu_r |r| P_n (checked here), so v = w = 0 at once
  // (contact_resolve with M). The single point's closed form without M (stop the point, the
  // resistance's impulse, stop the point again: one pass) leaves it rolling at 7e-5 m/s, below
  // the resting speed. Spinning at 2 rad/s it needs more than the resistance gives: it rolls on.
  const Sphere sp;
  const ContactParams k0 = contact_params(Shape::sphere(kR), Vec3::Zero(), 0.5, 0.5, 0, 0.05);
  ContactParams k = k0;
  k.rest_speed = 0.08;
  std::array<double, 36> M{};
  for (int a = 0; a < 6; ++a) M[7 * a] = 1 / sp.Minv[7 * a];
  const double r[3] = {0, 0, -kR}, n[3] = {0, 0, 1}, depth[1] = {1e-5};
  double v[3] = {1e-4, 0, -9.81 * 0.002}, w[3] = {0, 0.002, 0}, dx[3];
  double vs[3] = {v[0], v[1], v[2]}, ws[3] = {w[0], w[1], w[2]};
  EXPECT_EQ(contact_resolve(k, sp.Minv.data(), v, w, 1, r, n, depth, kContactPasses, dx,
                            M.data()),
            1);
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(v[a], 0.0);
    EXPECT_EQ(w[a], 0.0);
  }
  EXPECT_DOUBLE_EQ(dx[2], 1e-5);
  const Vec3 P = -sp.m * Vec3(vs[0], vs[1], vs[2]), L = -sp.I * Vec3(ws[0], ws[1], ws[2]);
  EXPECT_GT(P.z(), 0.0);
  EXPECT_LE(std::hypot(P.x(), P.y()), k.friction * P.z());
  EXPECT_LE((L - Vec3(r[0], r[1], r[2]).cross(P)).norm(), 0.05 * kR * P.z());
  contact_resolve(k, sp.Minv.data(), vs, ws, 1, r, n, depth, kContactPasses, dx);
  EXPECT_LT(std::abs(vs[0]), kRestFraction * k.rest_speed);
  EXPECT_NEAR(vs[0], kR * ws[1], 1e-12);  // rolling, the point at rest
  double vr[3] = {2 * kR, 0, -9.81 * 0.002}, wr[3] = {0, 2, 0};
  contact_resolve(k, sp.Minv.data(), vr, wr, 1, r, n, depth, kContactPasses, dx, M.data());
  EXPECT_GT(wr[1], 1.0);  // the resistance slowed the rolling, it did not stop it
}

}  // namespace
}  // namespace lrigid
