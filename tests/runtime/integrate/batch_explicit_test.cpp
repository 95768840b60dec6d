// What the batched euler and rk4 loops share (integrate/batch_explicit.h): rk4's four stages
// across a block make the classical Runge-Kutta step (on linear equations its step is the
// polynomial 1 + z + z^2/2 + z^3/6 + z^4/24 of z = lambda h), each stage sampled where and when it
// is (t, t + h/2, t + h/2, t + h in a gusting series) and the driver's frames given back; a lane
// whose stage left the fluid is marked; the seen fluctuation's Euler-Maruyama update is
// (1 - alpha h) u' + h a + beta sqrt(h) z, and the identity without the seen turbulence.
// (The header has internal linkage: this file compiles its own copy of what it calls.)
#include "integrate/batch_explicit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <type_traits>

#include "effects/evaluate.h"
#include "support/batch_compare.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

// x' = -lambda x (world), xi' = mu xi (body frame: v and w), theta' = w0 (a spin held fixed), on
// every lane with its own start: one step of rk4_stages and rk4_sum_lane against the closed form
// of the classical Runge-Kutta step.
TEST(BatchExplicit, Rk4StagesMakeTheClassicalRungeKuttaStep) {
  const double h = 0.05, lambda = 3.0, mu = -1.5;
  FieldConsts fc;  // no field to sample between the stages
  fc.sample = false;
  const Rk4Frames frames{};
  Samples<double> lanes{};
  Rk4Block<double> k{};
  double x0[kBatch][3], v0[kBatch][3], w0[kBatch][3];
  for (int j = 0; j < kBatch; ++j)
    for (int a = 0; a < 3; ++a) {
      x0[j][a] = 1.0 + j + 0.5 * a;
      v0[j][a] = 0.1 * (a + 1) - 0.02 * j;
      w0[j][a] = 2.0 - 0.3 * a + 0.01 * j;
    }
  const int stopped = 9;  // this lane's third stage leaves the fluid
  int calls = 0;
  auto stage = [&](auto I) {
    constexpr int i = decltype(I)::value;
    EXPECT_EQ(calls++, i) << "the stages in order";
    for (int j = 0; j < kBatch; ++j) {
      double xs[3], vs[3], ws[3], kx[3], kth[3], kxi[6];
      for (int a = 0; a < 3; ++a) {
        xs[a] = i == 0 ? x0[j][a] : k.xs[a][j];
        vs[a] = i == 0 ? v0[j][a] : k.vs[a][j];
        ws[a] = i == 0 ? w0[j][a] : k.ws[a][j];
        kx[a] = -lambda * xs[a];
        kth[a] = w0[j][a];
        kxi[a] = mu * vs[a];
        kxi[3 + a] = mu * ws[a];
      }
      const bool in = !(j == stopped && i == 2);
      rk4_sum_lane(i, &k, j, in, h, x0[j], v0[j], w0[j], kx, kth, kxi);
    }
  };
  rk4_stages(fc, frames, &lanes, &k, stage);
  EXPECT_EQ(calls, 4);
  auto rk4_poly = [](double z) { return 1 + z + z * z / 2 + z * z * z / 6 + z * z * z * z / 24; };
  const double gx = rk4_poly(-lambda * h), gv = rk4_poly(mu * h);
  for (int j = 0; j < kBatch; ++j) {
    EXPECT_EQ(k.ok[j], j == stopped ? 0.0 : 1.0) << "lane " << j;
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(x0[j][a] + h / 6 * k.Sx[a][j], gx * x0[j][a], 1e-14 * std::abs(x0[j][a]));
      EXPECT_NEAR(v0[j][a] + h / 6 * k.Sxi[a][j], gv * v0[j][a], 4e-15);
      EXPECT_NEAR(w0[j][a] + h / 6 * k.Sxi[3 + a][j], gv * w0[j][a], 1e-14);
      EXPECT_NEAR(h / 6 * k.Sth[a][j], h * w0[j][a], 1e-15);
    }
  }
}

// In a gusting series (four frames, support/batch_compare.h), between rk4's stages the block is
// sampled at the next stage's positions and times, t + h/2, t + h/2 and t + h of step s (the
// field's own sample there, effects/evaluate.h sample_fluid), and the driver's frames (the end of
// the step) are given back after the last stage.
TEST(BatchExplicit, Rk4SamplesEachStageWhereAndWhenItIs) {
  Scene s = test::sphere_scene(2.5e-4, 2500, 1.2, 1.5e-5);
  s.effects = test::effects({Effect::Drag, Effect::MeanFlow, Effect::AddedMass});
  batch_test::release_in_wind_grid(&s, 7);
  s.integrator = Integrator::RK4;
  s.dt = 0.02;
  const Model m = test::compile(s, batch_test::gusty_wind_grid(1.5e-5));
  ASSERT_GT(m.field.frame_count(), 1u);
  FieldConsts fc;
  set_field_consts(m, m.types[0], &fc);
  ASSERT_TRUE(fc.sample && fc.grid);
  const uint64_t step = 14;  // t = 0.28 s, t + h = 0.30 s: across the frame at 0.3 s
  const double t = step * m.dt, h = m.dt;
  const Rk4Frames frames = rk4_frames(m, true, step);
  Samples<double> lanes{};
  const FluidField::FrameBlend at_end = m.field.frames_at(t + h);
  lanes.frames = at_end;
  Rk4Block<double> k{};
  double x0[kBatch][3];
  for (int j = 0; j < kBatch; ++j) {
    x0[j][0] = -5 + 0.3 * j, x0[j][1] = -3 + 0.2 * j, x0[j][2] = 0.5 + 0.1 * j;
  }
  const double c[4] = {0, 0.5, 0.5, 1};
  int checked = 0;
  auto stage = [&](auto I) {
    constexpr int i = decltype(I)::value;
    for (int j = 0; j < kBatch; ++j) {
      if (i > 0) {
        const Vec3 x(k.xs[0][j], k.xs[1][j], k.xs[2][j]);
        FluidSample fs;
        const bool in = sample_fluid(m, x, t + c[i] * h, true, &fs);
        EXPECT_EQ(lanes.inside[j] != 0, in) << "stage " << i << " lane " << j;
        if (in) {
          ++checked;
          for (int a = 0; a < 3; ++a)
            EXPECT_NEAR(lanes.U[a][j], fs.U[a], 1e-12 * (1 + fs.U.norm()))
                << "stage " << i << " lane " << j;
          EXPECT_NEAR(lanes.beta[j], fs.beta, 1e-12 * fs.beta);
        }
      }
      // a wind of its own moves each stage's position: 2 m/s along x, 1 m/s along y and z
      const double kx[3] = {2.0, 1.0, 1.0}, zero[6] = {0, 0, 0, 0, 0, 0};
      rk4_sum_lane(i, &k, j, true, h, x0[j], zero, zero, kx, zero, zero);
    }
  };
  rk4_stages(fc, frames, &lanes, &k, stage);
  EXPECT_GT(checked, 3 * kBatch / 2);
  EXPECT_EQ(lanes.frames.a, at_end.a);
  EXPECT_EQ(lanes.frames.b, at_end.b);
  EXPECT_EQ(lanes.frames.lam, at_end.lam);
}

// Euler-Maruyama over h from the start of the step: us <- (1 - alpha h) us + h a + beta sqrt(h) z
// with Thomson's drift a = 1/2 grad sigma^2 + us (V0 . grad sigma^2) / (2 sigma^2) along the start's
// world velocity V0; without the seen turbulence the identity.
TEST(BatchExplicit, TheEulerMaruyamaUpdateOfTheSeenFluctuation) {
  FieldConsts fc;
  fc.h = 0.01;
  fc.turb = true;
  fc.tu = 1;
  fc.wm = 1;
  Samples<double> lanes{};
  alignas(64) double z[3][kBatch] = {};
  const int j = 17;
  const double alpha = 4.0, beta = 0.3, sigma2 = beta * beta / (2 * alpha);
  lanes.alpha[j] = alpha, lanes.beta[j] = beta, lanes.sigma2[j] = sigma2;
  const double gs[3] = {0.002, -0.001, 0.004}, V0[3] = {0.5, 1.0, -0.2}, zj[3] = {1.1, -0.4, 0.3};
  for (int a = 0; a < 3; ++a) lanes.gs[a][j] = gs[a], z[a][j] = zj[a];
  const double u0[3] = {0.05, -0.02, 0.1};
  const double proj = (V0[0] * gs[0] + V0[1] * gs[1] + V0[2] * gs[2]) / (2 * sigma2);
  double us[3] = {u0[0], u0[1], u0[2]};
  ou_euler_lane(fc, &lanes, j, V0, z, us);
  for (int a = 0; a < 3; ++a)
    EXPECT_NEAR(us[a],
                (1 - alpha * fc.h) * u0[a] + fc.h * (0.5 * gs[a] + u0[a] * proj) +
                    beta * std::sqrt(fc.h) * zj[a],
                1e-15);
  fc.turb = false;
  fc.tu = 0;
  double still[3] = {u0[0], u0[1], u0[2]};
  ou_euler_lane(fc, &lanes, j, V0, z, still);
  for (int a = 0; a < 3; ++a) EXPECT_EQ(still[a], u0[a]);
}

}  // namespace
}  // namespace lrigid
