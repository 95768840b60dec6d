// The free Kirchhoff flow's and the implicit force step's kernels (model/kirchhoff.h), called
// as the scalar step calls them (T = double, the body type's diagonal or full M) and as the
// batched loops call them (DiagonalMass, double and float), on the same inputs: the two mass
// forms agree to round-off, float agrees to float's round-off, and each kernel agrees with its
// equation written directly in Eigen (effects/wrench.h kirchhoff_gyro, finite differences of G,
// the dense solve of (M + h J + b P) x = M b).
#include "model/kirchhoff.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
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

// A = I + h/2 dG/dY in both mass forms against central differences of Y -> Y + h/2 G(Y)
void expect_newton_matrix_is_the_derivative(const Case& c, double h) {
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

TEST(KirchhoffKernels, NewtonMatrixIsTheDerivativeOfTheMidpointEquation) {
  std::mt19937_64 gen(5);
  for (int trial = 0; trial < 50; ++trial)
    expect_newton_matrix_is_the_derivative(make_case(gen), 1e-3);
}

// A flat body with drag keeps a share of its Munk couple (BodyType::munk_back, S): the moment
// of P is -v x (P - S v). The gyro kernel against that equation, and the Newton matrix against
// finite differences, in both mass forms (S diagonal, as for boxes and ellipsoids).
TEST(KirchhoffKernels, TheMunkShareTakenBackInBothMassForms) {
  std::mt19937_64 gen(11);
  std::uniform_real_distribution<double> share(0.2, 0.9);
  const double h = 1e-3;
  for (int trial = 0; trial < 50; ++trial) {
    Case c = make_case(gen);
    Mat3 S = Mat3::Zero();
    const double lo = c.M.diagonal().head<3>().minCoeff();
    for (int a = 0; a < 3; ++a) {
      S(a, a) = share(gen) * (c.M(a, a) - lo);
      c.diag.S[a] = S(a, a);
    }
    c.full.S = S.data();
    const Vec6 xi = c.Mi * c.Y;
    const Vec3 v = xi.head<3>();
    Vec6 ref = kirchhoff_gyro(v, xi.tail<3>(), c.Y);
    ref.tail<3>() -= v.cross(S * v);
    EXPECT_GT(v.cross(S * v).norm(), 1e-6 * ref.tail<3>().norm());  // the term is there
    Vec6 gd, gf;
    kirchhoff_gyro_kernel(c.diag, c.Y.data(), gd.data());
    kirchhoff_gyro_kernel(c.full, c.Y.data(), gf.data());
    EXPECT_LE((gd - ref).norm(), 1e-14 * ref.norm());
    EXPECT_LE((gf - ref).norm(), 1e-14 * ref.norm());
    expect_newton_matrix_is_the_derivative(c, h);
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

// a drag of random coefficients (c_ang one per axis, of the scale given) along a random
// direction, drawn as the implicit force step's tests draw it
DragOut<double> random_drag(std::mt19937_64& gen, double ang_scale) {
  std::uniform_real_distribution<double> u(-1, 1), s(0.0, 5.0);
  DragOut<double> d{};
  d.c_lin = 1e-3 * s(gen);
  d.p = s(gen);
  for (int a = 0; a < 3; ++a) d.c_ang[a] = ang_scale * s(gen);
  Vec3 uh(u(gen), u(gen), u(gen));
  uh.normalize();
  for (int a = 0; a < 3; ++a) d.u_hat[a] = uh[a];
  return d;
}

TEST(KirchhoffKernels, ImplicitImpulseSolvesTheImplicitForceStep) {
  std::mt19937_64 gen(13);
  std::uniform_real_distribution<double> u(-1, 1), s(0.0, 5.0);
  const double h = 1e-3;
  for (int trial = 0; trial < 100; ++trial) {
    Case c = make_case(gen);
    const DragOut<double> d = random_drag(gen, 1e-6);
    const Vec3 uh(d.u_hat[0], d.u_hat[1], d.u_hat[2]);
    const double b = trial % 2 ? 2e-4 : 0.0;  // with and without the Basset mass
    Vec6 rhs;
    for (int a = 0; a < 6; ++a) rhs[a] = c.M(a, a) * u(gen);
    Mat6 A = c.M;
    A.topLeftCorner<3, 3>() += h * d.c_lin * (Mat3::Identity() + d.p * uh * uh.transpose()) +
                               b * Mat3::Identity();
    A.bottomRightCorner<3, 3>() +=
        h * Mat3(Vec3(d.c_ang[0], d.c_ang[1], d.c_ang[2]).asDiagonal());
    const Vec6 ref = c.M * A.fullPivLu().solve(rhs);
    Vec6 xd, xf;
    EXPECT_TRUE(implicit_impulse(c.diag, b, d, h, rhs.data(), xd.data()));
    EXPECT_TRUE(implicit_impulse(c.full, b, d, h, rhs.data(), xf.data()));
    EXPECT_LE((xd - ref).norm(), 1e-13 * ref.norm());
    EXPECT_LE((xf - ref).norm(), 1e-13 * ref.norm());
  }
}

// A coupled M (a mesh's: the diagonal case's plate-like scales turned by a rotation R applied to
// both blocks, plus a linear-angular coupling C), symmetric positive definite, and a fluid tensor
// K with its own coupling: the full kernels against Eigen's dense algebra
TEST(KirchhoffKernels, FullMassKernelsMatchTheDenseAlgebra) {
  std::mt19937_64 gen(19);
  std::uniform_real_distribution<double> u(-1, 1), s(0.0, 5.0);
  const double h = 2e-3;
  for (int trial = 0; trial < 100; ++trial) {
    const Case c = make_case(gen);
    const Mat3 R = Eigen::AngleAxisd(3 * u(gen), Vec3(u(gen), u(gen), u(gen)).normalized())
                       .toRotationMatrix();
    Mat6 T = Mat6::Zero();
    T.topLeftCorner<3, 3>() = R;
    T.bottomRightCorner<3, 3>() = R;
    Mat6 M = T * c.M * T.transpose();
    Mat3 C;
    for (int e = 0; e < 9; ++e) C(e) = 5e-6 * u(gen);  // kg m: C^T C / m well below J
    M.topRightCorner<3, 3>() = C;
    M.bottomLeftCorner<3, 3>() = C.transpose();
    ASSERT_GT(Eigen::SelfAdjointEigenSolver<Mat6>(M).eigenvalues().minCoeff(), 0);
    const Mat6 Mi = M.inverse();
    const FullMass full{M.data(), Mi.data()};
    Mat6 K = 0.3 * M;  // a fluid tensor with a coupling of its own
    FullFluidImpulse fk;
    for (int r = 0; r < 6; ++r)
      for (int cc = 0; cc < 3; ++cc) fk.K[r * 3 + cc] = K(r, cc);
    Vec6 xi, Pi, back, ref;
    for (int a = 0; a < 6; ++a) xi[a] = (a < 3 ? 1.0 : 20.0) * u(gen);
    const Vec3 uf(u(gen), u(gen), u(gen));
    Vec6 uf6;
    uf6 << uf, Vec3::Zero();
    // Pi = M xi - K (u; 0) and back (dynamics.h velocity_from_impulse)
    impulse_of_velocity(full, fk, xi.data(), uf.data(), Pi.data());
    ref = M * xi - K * uf6;
    EXPECT_LE((Pi - ref).norm(), 1e-13 * ref.norm());
    velocity_of_impulse(full, fk, Pi.data(), uf.data(), back.data());
    EXPECT_LE((back - xi).norm(), 1e-12 * xi.norm());
    // the norms
    EXPECT_NEAR(velocity_norm2(full, xi.data()), xi.dot(M * xi), 1e-13 * xi.dot(M * xi));
    EXPECT_NEAR(energy_norm2(full, Pi.data()), Pi.dot(Mi * Pi), 1e-12 * Pi.dot(Mi * Pi));
    // the implicit force step, in one call and factored once for two right-hand sides
    const DragOut<double> d = random_drag(gen, 1e-6);
    const Vec3 uh(d.u_hat[0], d.u_hat[1], d.u_hat[2]);
    Mat6 A = M;
    A.topLeftCorner<3, 3>() += h * d.c_lin * (Mat3::Identity() + d.p * uh * uh.transpose());
    A.bottomRightCorner<3, 3>() +=
        h * Mat3(Vec3(d.c_ang[0], d.c_ang[1], d.c_ang[2]).asDiagonal());
    Vec6 b1, b2, x1, x2, x;
    for (int a = 0; a < 6; ++a) b1[a] = M(a, a) * u(gen), b2[a] = M(a, a) * u(gen);
    double lu[36];
    ASSERT_TRUE(implicit_factor(full, 0.0, d, h, lu));
    implicit_solve(lu, b1.data(), x1.data());
    implicit_solve(lu, b2.data(), x2.data());
    ASSERT_TRUE(implicit_impulse(full, 0.0, d, h, b1.data(), x.data()));
    const Vec6 r1 = A.fullPivLu().solve(b1), r2 = A.fullPivLu().solve(b2);
    EXPECT_LE((x1 - r1).norm(), 1e-12 * r1.norm());
    EXPECT_LE((x2 - r2).norm(), 1e-12 * r2.norm());
    Vec6 Mx1;
    mass_times(full, x1.data(), Mx1.data());
    EXPECT_EQ((x - Mx1).norm(), 0.0);  // the impulse change is M times the velocity change
  }
}

// ROS2 taken in the velocity (ros2_velocity) against ROS2 on the impulse as Verwer et al. write
// it, in Eigen: (I + g h J M^-1) k1 = F(Pi0), (I + g h J M^-1) k2 = F(Pi0 + h k1) - 2 k1,
// dPi = h (3/2 k1 + 1/2 k2), for a nonlinear force (a quadratic drag and a constant force) of the
// velocity xi = M^-1 Pi, with a full coupled M and an approximate J (a W-method): the velocity
// changes by M^-1 dPi
TEST(KirchhoffKernels, Ros2InTheVelocityIsRos2OnTheImpulse) {
  std::mt19937_64 gen(23);
  std::uniform_real_distribution<double> u(-1, 1);
  const double h = 2e-3, g = kRos2Gamma;
  for (int trial = 0; trial < 50; ++trial) {
    Mat6 B;
    for (int e = 0; e < 36; ++e) B(e) = u(gen);
    const Mat6 M = 1e-3 * (B * B.transpose() + Mat6::Identity());
    const Mat6 Mi = M.inverse();
    const FullMass full{M.data(), Mi.data()};
    Vec6 f0, xi0, c;
    for (int a = 0; a < 6; ++a) {
      f0[a] = 1e-3 * u(gen);
      xi0[a] = u(gen);
      c[a] = 1e-3 * (1 + u(gen));
    }
    // F(xi) = f0 - c |xi| xi (element-wise), J = its stiffness at xi0 without the |xi| derivative
    auto F = [&](const Vec6& xi) {
      return Vec6(f0 - c.cwiseProduct(xi.cwiseAbs()).cwiseProduct(xi));
    };
    const Mat6 J = Mat6(c.cwiseProduct(xi0.cwiseAbs()).asDiagonal());
    const Mat6 W = Mat6::Identity() + g * h * J * Mi;
    const Vec6 k1 = W.fullPivLu().solve(F(xi0));
    const Vec6 k2 = W.fullPivLu().solve(F(xi0 + Mi * (h * k1)) - 2 * k1);
    const Vec6 ref = Mi * (h * (1.5 * k1 + 0.5 * k2));

    auto forces = [&](const double* dxi, bool, double* out) {
      Eigen::Map<Vec6> o(out);
      o = F(xi0 + Eigen::Map<const Vec6>(dxi));
    };
    auto solve = [&](double gh, const double* b, double* y) {
      Eigen::Map<Vec6> o(y);
      o = (M + gh * J).fullPivLu().solve(Eigen::Map<const Vec6>(b));
    };
    auto m_times = [&](const double* y, double* x) { mass_times(full, y, x); };
    Vec6 dxi;
    ros2_velocity(h, forces, solve, m_times, dxi.data());
    EXPECT_LE((dxi - ref).norm(), 1e-11 * ref.norm());
  }
}

TEST(KirchhoffKernels, ImplicitImpulseOfAnIsotropicMassIsTheDiagonalOne) {
  // the isotropic M's closed form against the diagonal kernel on M = diag(m, m, m, J, J, J)
  std::mt19937_64 gen(17);
  std::uniform_real_distribution<double> u(-1, 1), s(0.0, 5.0);
  for (int trial = 0; trial < 100; ++trial) {
    const double m = 2e-3 * (1 + s(gen)), J = 4e-7 * (1 + s(gen));
    const IsotropicMass iso = isotropic_mass(m, J);
    DiagonalMass diag;
    for (int a = 0; a < 3; ++a) {
      diag.M[a] = m;
      diag.Mi[a] = 1 / m;
      diag.M[3 + a] = J;
      diag.Mi[3 + a] = 1 / J;
    }
    const DragOut<double> d = random_drag(gen, 1e-7);
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
