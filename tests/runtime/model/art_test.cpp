// Art direction: field scales act exactly like a scaled field; per-body variation is drawn
// within the stated ranges, reproducibly from the seed.
#include <gtest/gtest.h>

#include <cmath>

#include "compile/compile_model.h"
#include "integrate/dynamics.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

TEST(Art, MeanFlowScaleIsAScaledField) {
  Scene a = test::sphere_scene(0.01, 500, 1000, 1e-6);
  a.effects = test::effects({Effect::Drag, Effect::MeanFlow, Effect::AddedMass});
  a.uniform_U = Vec3(0.2, 0.1, 0);
  Scene b = a;
  b.uniform_U *= 1.7;
  a.mean_flow_scale = 1.7;
  const Model ma = test::compile(a), mb = test::compile(b);
  const Kinematics k{Vec3::Zero(), Mat3::Identity(), Vec3(0.05, 0, -0.1), Vec3(0, 1, 0),
                     Vec3::Zero()};
  Vec6 xa, xb;
  FluidSample fa, fb;
  ASSERT_EQ(velocity_derivative(ma, ma.types[0], k, 0, &xa, &fa), EvalResult::Ok);
  ASSERT_EQ(velocity_derivative(mb, mb.types[0], k, 0, &xb, &fb), EvalResult::Ok);
  EXPECT_TRUE(test::near(xa, xb, 1e-12 * xb.norm()));
}

TEST(Art, TurbulenceScaleScalesTheSeenVelocity) {
  Scene a = test::sphere_scene(0.001, 1000, 1000, 1e-6, 50);
  a.effects = test::effects({Effect::Drag, Effect::Turbulence});
  a.uniform_k = 0.01, a.uniform_epsilon = 0.001;
  Scene b = a;
  b.turbulence_scale = 3.0;
  const State sa = initial_state(test::compile(a), a), sb = initial_state(test::compile(b), b);
  for (size_t i = 0; i < sa.size(); ++i)
    EXPECT_TRUE(test::near(sb.u_seen[i], Vec3(3.0 * sa.u_seen[i]), 1e-14));
  // and the noise amplitude of the step: beta scales with it, sigma2 with its square
  const Model mb = test::compile(b), ma = test::compile(a);
  FluidSample fa, fb;
  ASSERT_TRUE(sample_fluid(ma, Vec3::Zero(), 0, false, &fa));
  ASSERT_TRUE(sample_fluid(mb, Vec3::Zero(), 0, false, &fb));
  EXPECT_NEAR(fb.beta, 3.0 * fa.beta, 1e-14);
  EXPECT_NEAR(fb.sigma2, 9.0 * fa.sigma2, 1e-14);
  EXPECT_EQ(fb.alpha, fa.alpha);  // the Lagrangian time scale is kept
}

TEST(Art, SizeAndDensityVariantsStayInRangeAndAreReproducible) {
  Scene s = test::sphere_scene(0.01, 1000, 1.2, 1.5e-5, 100);
  s.effects = test::effects({Effect::Gravity, Effect::Drag});
  BodySpec& b = s.bodies[0];
  b.size_min = 0.5, b.size_max = 1.5, b.density_min = 0.8, b.density_max = 1.2, b.variants = 8;
  const Model m = test::compile(s);
  ASSERT_EQ(m.types.size(), 8u);
  size_t total = 0;
  double r_lo = 1, r_hi = 0;
  for (const BodyType& t : m.types) {
    const double f = t.shape.half_extents.x() / 0.01;
    EXPECT_GE(f, 0.5);
    EXPECT_LE(f, 1.5);
    EXPECT_GE(t.density, 800);
    EXPECT_LE(t.density, 1200);
    EXPECT_EQ(t.first_body, total);
    EXPECT_EQ(t.spec, 0u);
    EXPECT_EQ(t.variant, int(&t - m.types.data())) << "variants are numbered in order";
    total += t.count;
    r_lo = std::min(r_lo, f), r_hi = std::max(r_hi, f);
  }
  EXPECT_EQ(total, 100u);
  EXPECT_GT(r_hi - r_lo, 0.2) << "the draws spread over the range";
  const Model again = test::compile(s);
  for (size_t i = 0; i < m.types.size(); ++i) EXPECT_EQ(m.types[i].mass, again.types[i].mass);
  s.seed = 2;
  EXPECT_NE(test::compile(s).types[0].mass, m.types[0].mass);
}

TEST(Art, SpinIsDrawnFromItsRange) {
  Scene s = test::sphere_scene(0.01, 1000, 1.2, 1.5e-5, 200);
  s.bodies[0].spin_min = 3, s.bodies[0].spin_max = 5;
  const Model m = test::compile(s);
  const State st = initial_state(m, s);
  double lo = 1e9, hi = 0;
  Vec3 mean = Vec3::Zero();
  for (size_t i = 0; i < st.size(); ++i) {
    lo = std::min(lo, st.w[i].norm()), hi = std::max(hi, st.w[i].norm());
    mean += st.w[i].normalized() / double(st.size());
  }
  EXPECT_GE(lo, 3.0);
  EXPECT_LE(hi, 5.0);
  EXPECT_GT(hi - lo, 1.5);
  EXPECT_LT(mean.norm(), 0.25);  // axes spread over the sphere (|mean| ~ 1/sqrt(3 n) = 0.04)
  const State again = initial_state(m, s);
  for (size_t i = 0; i < st.size(); ++i) EXPECT_EQ(st.w[i], again.w[i]);
}

}  // namespace
}  // namespace lrigid
