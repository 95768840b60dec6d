// One body's state as a step takes it (model/body_state.h): rotate_body turns an orientation by
// a body-frame rotation vector, the exponential map (angle |theta| about theta / |theta|), and
// keeps it a unit quaternion; load_body and store_body copy body i out of the State and back.
#include "model/body_state.h"

#include <gtest/gtest.h>

#include <cmath>

#include "support/fixture.h"

namespace lrigid {
namespace {

TEST(BodyState, RotateBodyTurnsByTheVectorsAngleAboutItsAxis) {
  const Quat q(Eigen::AngleAxisd(0.7, Vec3(1, -2, 0.5).normalized()));
  for (const Vec3& theta : {Vec3(0.3, -0.1, 0.2), Vec3(0, 0, 3.0), Vec3(-2.0, 1.5, 0.5),
                            Vec3(1e-9, -2e-9, 5e-10), Vec3(1e-4, 0, -1e-4)}) {
    const Quat turned = rotate_body(q, theta);
    // body frame: the turn is applied after q, q exp(theta)
    const Quat exact = q * Quat(Eigen::AngleAxisd(theta.norm(), theta.normalized()));
    // (a quaternion and its negative are the same rotation)
    const double same = std::abs(turned.dot(exact));
    EXPECT_NEAR(same, 1.0, 4e-15) << theta.transpose();
    EXPECT_TRUE(test::near(turned.toRotationMatrix(), exact.toRotationMatrix(), 4e-15))
        << theta.transpose();
    EXPECT_NEAR(turned.norm(), 1.0, 4e-15);
  }
  // no turn: the orientation itself
  EXPECT_TRUE(test::near(rotate_body(q, Vec3::Zero()).coeffs(), q.coeffs(), 1e-16));
}

TEST(BodyState, LoadAndStoreCopyOneBodyOutAndBack) {
  State st;
  for (int i = 0; i < 3; ++i) {
    st.x.emplace_back(i, 2.0 * i, -1.0 * i);
    st.q.emplace_back(Eigen::AngleAxisd(0.1 * (i + 1), Vec3::UnitZ()));
    st.v.emplace_back(0.5 * i, 0, 1);
    st.w.emplace_back(0, i, 0);
    st.u_seen.emplace_back(0.01 * i, 0, 0);
  }
  st.history.assign(8, 0.0);
  st.history_offset = {State::kNoHistory, 2, State::kNoHistory};
  BodyState b = load_body(st, 1);
  EXPECT_EQ(b.x, st.x[1]);
  EXPECT_EQ(b.q.coeffs(), st.q[1].coeffs());
  EXPECT_EQ(b.v, st.v[1]);
  EXPECT_EQ(b.w, st.w[1]);
  EXPECT_EQ(b.u_seen, st.u_seen[1]);
  EXPECT_EQ(b.history, st.history.data() + 2);  // its history, in the State
  EXPECT_EQ(load_body(st, 0).history, nullptr);
  const State before = st;
  b.x = Vec3(7, 8, 9);
  b.q = Quat(Eigen::AngleAxisd(1.0, Vec3::UnitX()));
  b.v = Vec3(-1, -2, -3);
  b.w = Vec3(4, 5, 6);
  b.u_seen = Vec3(0.1, 0.2, 0.3);
  store_body(b, 1, &st);
  EXPECT_EQ(st.x[1], b.x);
  EXPECT_EQ(st.q[1].coeffs(), b.q.coeffs());
  EXPECT_EQ(st.v[1], b.v);
  EXPECT_EQ(st.w[1], b.w);
  EXPECT_EQ(st.u_seen[1], b.u_seen);
  for (const size_t i : {size_t(0), size_t(2)}) {  // the others untouched
    EXPECT_EQ(st.x[i], before.x[i]);
    EXPECT_EQ(st.q[i].coeffs(), before.q[i].coeffs());
    EXPECT_EQ(st.v[i], before.v[i]);
    EXPECT_EQ(st.w[i], before.w[i]);
    EXPECT_EQ(st.u_seen[i], before.u_seen[i]);
  }
}

}  // namespace
}  // namespace lrigid
