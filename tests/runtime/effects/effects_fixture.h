// What the tests of runtime/src/effects share: body types compiled from one-body scenes, and a
// block of the batched steps' lanes: the drag and plate kernels called as a block calls them (a
// loop across 32 lanes of structure-of-arrays values, in double and in float), compared with the
// scalar step's Eigen wrappers (drag_wrench, plate_drag_wrench, lift_wrench) on the same inputs.
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <initializer_list>
#include <random>
#include <vector>

#include "effects/drag.h"
#include "effects/lift.h"
#include "effects/plate.h"
#include "integrate/rigid_batch.h"
#include "support/fixture.h"

namespace lrigid::effects_test {

inline constexpr double kRho = 1.2, kNu = 1.5e-5;

inline Model model_of(const Shape& shape, double density, EffectSet e) {
  Scene s = test::sphere_scene(1, density, kRho, kNu);
  s.bodies[0].shape = shape;
  s.effects = e;
  return test::compile(s);
}

// (no added mass: the kernels do not need it, and a box's comes from the slower BEM)
inline EffectSet all_forces() {
  return test::effects(
      {Effect::Gravity, Effect::Buoyancy, Effect::Drag, Effect::Lift, Effect::Magnus});
}

// a thin circular disk (oblate ellipsoid), normal along body z, in water
inline Model disk_model(EffectSet e, double a = 0.02, double c = 0.001) {
  Scene s = test::sphere_scene(1, 2700, 1000, 1e-6);
  s.bodies[0].shape = Shape::ellipsoid(a, a, c);
  s.effects = e;
  return test::compile(s);
}

// Inputs for a block: relative velocities over four decades (and one at rest), spins.
struct Block {
  double u[3][kBatch], w[3][kBatch];
};

inline Block random_block(uint32_t seed) {
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
inline ::testing::AssertionResult close(double a, double b, double tol, double scale) {
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

// expect_block_matches_scalar for the body type of each model on the blocks of `seeds` (the
// kernels take r_cob = 0: the centroid is the centre of mass)
template <typename T>
void expect_blocks_match_scalar(const std::vector<Model>& models,
                                std::initializer_list<uint32_t> seeds, double tol) {
  for (const Model& m : models) {
    ASSERT_TRUE(m.types[0].r_cob.isZero(0.0));
    for (uint32_t seed : seeds) expect_block_matches_scalar<T>(m.types[0], random_block(seed), tol);
  }
}

}  // namespace lrigid::effects_test
