// The drag of bodies that are not flat (effects/drag.h, drag.cpp) against its closed forms:
// Schiller-Naumann's C_D(Re) and its Stokes limit 6 pi mu r u, the Stokes torque 8 pi mu r^3 w,
// Oberbeck's and Jeffery's Stokes resistance of an ellipsoid; and the kernel as a block of the
// batched steps calls it against the scalar step's drag_wrench. (The plate's drag, whose kernel
// is effects/plate.h: plate_test.cpp.)
#include "effects/drag.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "effects_fixture.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

using effects_test::kNu;
using effects_test::kRho;
using effects_test::model_of;
using test::compile;
using test::sphere_scene;

// The body types the batched steps take with this drag: a sphere and an ellipsoid; compiled once
const std::vector<Model>& models() {
  static const std::vector<Model> m = [] {
    std::vector<Model> v;
    v.push_back(model_of(Shape::sphere(0.004), 2500, effects_test::all_forces()));
    v.push_back(model_of(Shape::ellipsoid(0.01, 0.006, 0.004), 900, effects_test::all_forces()));
    return v;
  }();
  return m;
}

TEST(Drag, BlockAgreesWithScalarStepInDouble) {
  effects_test::expect_blocks_match_scalar<double>(models(), {1u, 2u, 3u}, 1e-13);
}

TEST(Drag, BlockAgreesWithScalarStepInFloat) {
  effects_test::expect_blocks_match_scalar<float>(models(), {4u, 5u}, 2e-4);
}

TEST(Drag, SchillerNaumannLimits) {
  EXPECT_NEAR(schiller_naumann(1e-4) * 1e-4, 24.0, 1e-2);  // Stokes: C_D Re -> 24
  EXPECT_NEAR(schiller_naumann(100), 24.0 / 100 * (1 + 0.15 * std::pow(100, 0.687)), 1e-12);
  EXPECT_EQ(schiller_naumann(5000), 0.44);
}

TEST(Drag, SphereAtLowReynoldsIsStokesDrag) {
  const double r = 1e-5, rho = 1000, nu = 1e-6, u = 1e-4;  // Re = 2e-3
  const Model m = compile(sphere_scene(r, 2500, rho, nu));
  const Wrench w = drag_wrench(m.types[0], Vec3(u, 0, 0), Vec3::Zero(), rho, nu);
  const double stokes = 6 * M_PI * rho * nu * r * u;
  // Stokes times Schiller-Naumann's finite-Re factor (1 + 0.15 Re^0.687), Re = 2e-3
  EXPECT_NEAR(-w[0] / stokes, 1.0 + 0.15 * std::pow(2e-3, 0.687), 1e-9);
  EXPECT_NEAR(-w[0] / stokes, 1.0, 3e-3);
  EXPECT_NEAR(w.tail<3>().norm(), 0.0, 1e-30);
}

TEST(Drag, SphereFollowsSchillerNaumannAtModerateRe) {
  const double r = 5e-4, rho = 998.2, nu = 1.0016e-3 / 998.2, u = 0.146;
  const Model m = compile(sphere_scene(r, 2500, rho, nu));
  const Wrench w = drag_wrench(m.types[0], Vec3(0, 0, -u), Vec3::Zero(), rho, nu);
  const double re = u * 2 * r / nu;
  const double expect = 0.5 * rho * schiller_naumann(re) * M_PI * r * r * u * u;
  EXPECT_NEAR(w[2] / expect, 1.0, 1e-9);
}

TEST(Drag, SphereRotationalDragIsStokesTorque) {
  // no out-of-roundness: only the viscous 8 pi mu r^3 w
  const double r = 0.01, rho = 1000, nu = 1e-6;
  const Model m = compile(sphere_scene(r, 2500, rho, nu));
  const Wrench w = drag_wrench(m.types[0], Vec3::Zero(), Vec3(0, 0, 3), rho, nu);
  EXPECT_NEAR(w[5], -8 * M_PI * rho * nu * r * r * r * 3, 1e-15);
}

TEST(Drag, SphereKernelIsSchillerNaumann) {
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

// Oberbeck/Jeffery resistance against its closed-form limits: sphere (6 pi R, 8 pi R^3) and thin
// disk (16 R broadside, 32/3 R edgewise, 32/3 R^3 about a diameter; Happel & Brenner 1965)
TEST(Drag, StokesResistanceOfEllipsoidLimits) {
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

}  // namespace
}  // namespace lrigid
