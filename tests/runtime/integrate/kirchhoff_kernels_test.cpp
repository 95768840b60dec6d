// The free Kirchhoff flow's and the implicit force step's kernels (integrate/kirchhoff.h), called
// as the scalar step calls them (T = double, the body type's diagonal or full M) and as the
// batched loops call them (DiagonalMass, double and float), on the same inputs: the two mass
// forms agree to round-off, float agrees to float's round-off, and each kernel agrees with its
// equation written directly in Eigen (effects/wrench.h kirchhoff_gyro, finite differences of G,
// the dense solve of (M + h J + b P) x = M b).
#include "integrate/kirchhoff.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <random>

#include "effects/wrench.h"

namespace lrigid {
namespace {

struct Case {
  Mat6 M;            // diagonal
  DiagonalMass diag;
  Mat6 Mi;
  FullMass full;
  Vec6 Y;
};

// a plate-like diagonal M (kg, kg m^2 several orders apart) and an impulse
Case make_case(std::mt19937_64& gen) {
  std::uniform_real_distribution<double> u(-1, 1), s(0.5, 2.0);
  Case c;
  Vec6 d;
  d << 1e-3 * s(gen), 1e-3 * s(gen), 3e-3 * s(gen), 2e-6 * s(gen), 3e-6 * s(gen), 5e-6 * s(gen);
  c.M = d.asDiagonal();
  c.Mi = c.M.inverse();
  for (int a = 0; a < 6; ++a) {
    c.diag.M[a] = d[a];
    c.diag.Mi[a] = 1.0 / d[a];
  }
  c.full = FullMass{c.M.data(), c.Mi.data()};
  for (int a = 0; a < 3; ++a) {
    c.Y[a] = d[a] * u(gen);             // v ~ 1 m/s
    c.Y[3 + a] = d[3 + a] * 20 * u(gen);  // w ~ 20 rad/s
  }
  return c;
}

TEST(KirchhoffKernels, GyroMatchesTheEquationInBothMassForms) {
  std::mt19937_64 gen(3);
  for (int trial = 0; trial < 100; ++trial) {
    Case c = make_case(gen);
    const Vec6 xi = c.Mi * c.Y;
    const Vec6 ref = kirchhoff_gyro(xi.head<3>(), xi.tail<3>(), c.Y);
    Vec6 gd, gf;
    kirchhoff_gyro_kernel(c.diag, c.Y.data(), gd.data());
    kirchhoff_gyro_kernel(c.full, c.Y.data(), gf.data());
    EXPECT_LE((gd - ref).norm(), 1e-14 * ref.norm());
    EXPECT_LE((gf - ref).norm(), 1e-14 * ref.norm());
    float Yf[6], g32[6];
    for (int a = 0; a < 6; ++a) Yf[a] = float(c.Y[a]);
    kirchhoff_gyro_kernel(c.diag, Yf, g32);
    for (int a = 0; a < 6; ++a) EXPECT_NEAR(g32[a], ref[a], 1e-5 * ref.norm());
  }
}

TEST(KirchhoffKernels, NewtonMatrixIsTheDerivativeOfTheMidpointEquation) {
  // A = I + h/2 dG/dY: central differences of Y -> Y + h/2 G(Y)
  std::mt19937_64 gen(5);
  const double h = 1e-3;
  for (int trial = 0; trial < 50; ++trial) {
    Case c = make_case(gen);
    double Ad[36], Af[36];
    kirchhoff_newton_matrix(c.diag, c.Y.data(), 0.5 * h, Ad);
    kirchhoff_newton_matrix(c.full, c.Y.data(), 0.5 * h, Af);
    for (int col = 0; col < 6; ++col) {
      const double e = 1e-6 * std::abs(c.Y[col]) + 1e-12;
      Vec6 yp = c.Y, ym = c.Y, gp, gm;
      yp[col] += e;
      ym[col] -= e;
      kirchhoff_gyro_kernel(c.full, yp.data(), gp.data());
      kirchhoff_gyro_kernel(c.full, ym.data(), gm.data());
      for (int row = 0; row < 6; ++row) {
        const double fd = (row == col ? 1.0 : 0.0) + 0.5 * h * (gp[row] - gm[row]) / (2 * e);
        EXPECT_NEAR(Ad[row * 6 + col], fd, 1e-6 * (1 + std::abs(fd))) << row << "," << col;
        EXPECT_NEAR(Af[row * 6 + col], Ad[row * 6 + col], 1e-14 * (1 + std::abs(fd)));
      }
    }
  }
}

TEST(KirchhoffKernels, FixedPointAndResidualAgreeWithTheMidpointEquation) {
  std::mt19937_64 gen(9);
  const double h = 1e-3;
  for (int trial = 0; trial < 50; ++trial) {
    Case c = make_case(gen);
    Vec6 Y;
    kirchhoff_predictor(c.diag, h, c.Y.data(), Y.data());
    const Vec6 mid = 0.5 * (c.Y + Y);
    const Vec6 xi = c.Mi * mid;
    const Vec6 next_ref = c.Y - h * kirchhoff_gyro(xi.head<3>(), xi.tail<3>(), mid);
    Vec6 next_d, next_f, r;
    const double sd = kirchhoff_fixed_point(c.diag, h, c.Y.data(), Y.data(), next_d.data());
    const double sf = kirchhoff_fixed_point(c.full, h, c.Y.data(), Y.data(), next_f.data());
    EXPECT_LE((next_d - next_ref).norm(), 1e-15 * next_ref.norm());
    EXPECT_LE((next_f - next_ref).norm(), 1e-15 * next_ref.norm());
    const Vec6 upd = next_ref - Y;
    EXPECT_NEAR(sd, upd.dot(c.Mi * upd), 1e-12 * sd + 1e-300);
    EXPECT_NEAR(sf, sd, 1e-12 * sd + 1e-300);
    kirchhoff_residual(c.diag, h, c.Y.data(), Y.data(), r.data());
    EXPECT_LE((r - (next_ref - Y)).norm(), 1e-15 * next_ref.norm());
  }
}

TEST(KirchhoffKernels, ImplicitImpulseSolvesTheImplicitForceStep) {
  std::mt19937_64 gen(13);
  std::uniform_real_distribution<double> u(-1, 1), s(0.0, 5.0);
  const double h = 1e-3;
  for (int trial = 0; trial < 100; ++trial) {
    Case c = make_case(gen);
    DragOut<double> d{};
    d.c_lin = 1e-3 * s(gen);
    d.p = s(gen);
    d.c_ang = 1e-6 * s(gen);
    Vec3 uh(u(gen), u(gen), u(gen));
    uh.normalize();
    for (int a = 0; a < 3; ++a) d.u_hat[a] = uh[a];
    const double b = trial % 2 ? 2e-4 : 0.0;  // with and without the Basset mass
    Vec6 rhs;
    for (int a = 0; a < 6; ++a) rhs[a] = c.M(a, a) * u(gen);
    Mat6 A = c.M;
    A.topLeftCorner<3, 3>() += h * d.c_lin * (Mat3::Identity() + d.p * uh * uh.transpose()) +
                               b * Mat3::Identity();
    A.bottomRightCorner<3, 3>() += h * d.c_ang * Mat3::Identity();
    const Vec6 ref = c.M * A.fullPivLu().solve(rhs);
    Vec6 xd, xf;
    EXPECT_TRUE(implicit_impulse(c.diag, b, d, h, rhs.data(), xd.data()));
    EXPECT_TRUE(implicit_impulse(c.full, b, d, h, rhs.data(), xf.data()));
    EXPECT_LE((xd - ref).norm(), 1e-13 * ref.norm());
    EXPECT_LE((xf - ref).norm(), 1e-13 * ref.norm());
  }
}

TEST(KirchhoffKernels, ImplicitImpulseOfAnIsotropicMassIsTheDiagonalOne) {
  // the sphere step's closed form against the diagonal kernel on M = diag(m, m, m, J, J, J)
  std::mt19937_64 gen(17);
  std::uniform_real_distribution<double> u(-1, 1), s(0.0, 5.0);
  for (int trial = 0; trial < 100; ++trial) {
    const IsotropicMass iso{2e-3 * (1 + s(gen)), 4e-7 * (1 + s(gen))};
    DiagonalMass diag;
    for (int a = 0; a < 3; ++a) {
      diag.M[a] = iso.m;
      diag.Mi[a] = 1 / iso.m;
      diag.M[3 + a] = iso.J;
      diag.Mi[3 + a] = 1 / iso.J;
    }
    DragOut<double> d{};
    d.c_lin = 1e-3 * s(gen);
    d.p = s(gen);
    d.c_ang = 1e-7 * s(gen);
    Vec3 uh(u(gen), u(gen), u(gen));
    uh.normalize();
    for (int a = 0; a < 3; ++a) d.u_hat[a] = uh[a];
    Vec6 b;
    for (int a = 0; a < 6; ++a) b[a] = 1e-3 * u(gen);
    Vec6 xi, xd;
    implicit_impulse(iso, 1e-4, d, 1e-3, b.data(), xi.data());
    implicit_impulse(diag, 1e-4, d, 1e-3, b.data(), xd.data());
    EXPECT_LE((xi - xd).norm(), 1e-14 * xd.norm());
  }
}

}  // namespace
}  // namespace lrigid
