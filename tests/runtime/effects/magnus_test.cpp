// The Magnus force (effects/magnus.h) against its closed form C_M rho V w x u: a ball with
// backspin is lifted, and the kernel as a block of the batched steps calls it (double and float)
// agrees with the scalar step's magnus_wrench.
#include "effects/magnus.h"

#include <gtest/gtest.h>

#include <cmath>

#include "effects_fixture.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

using effects_test::Block;
using effects_test::close;
using effects_test::kRho;
using test::compile;

TEST(Magnus, BlockAgreesWithScalarStep) {
  const Model m = effects_test::model_of(Shape::sphere(0.02), 300, test::effects({Effect::Magnus}));
  const BodyType& t = m.types[0];
  const Block in = effects_test::random_block(7);
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

TEST(Magnus, BackspinLiftsABall) {
  const Model m = compile(test::sphere_scene(0.11, 60, 1.2, 1.5e-5));
  const BodyType& t = m.types[0];
  // moving +x with backspin (w along -y): force up, C_M rho V w U
  const Vec3 f = magnus_wrench(t, Vec3(20, 0, 0), Vec3(0, -10, 0), 1.2).head<3>();
  EXPECT_NEAR(f.z(), kMagnus * 1.2 * t.volume * 10 * 20, 1e-12);
  EXPECT_NEAR(f.x(), 0, 1e-15);
  EXPECT_NEAR(f.y(), 0, 1e-15);
}

}  // namespace
}  // namespace lrigid
