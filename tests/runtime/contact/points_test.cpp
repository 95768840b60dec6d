// The contact points of each shape (contact/points.h): the support point of an ellipsoid, a
// box's corners and edge points, a mesh's convex hull, and the material's checks.
#include "contact/points.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "contact/solver.h"
#include "util/error.h"

namespace lrigid {
namespace {

TEST(Contact, EllipsoidSupportPointLiesOnTheSurfaceWithNormalAgainstTheWall) {
  const Vec3 com(0.01, -0.02, 0.005);
  const ContactParams k = contact_params(Shape::ellipsoid(0.3, 0.1, 0.05), com, 0.5, 0.5, 0);
  ASSERT_TRUE(k.support);
  EXPECT_EQ(k.count(), 1u);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 100; ++trial) {
    const Vec3 nn = Vec3(u(rng), u(rng), u(rng)).normalized();
    const double n[3] = {nn.x(), nn.y(), nn.z()};
    double r[3];
    ellipsoid_support_point(k, n, r);
    const Vec3 p = Vec3(r[0], r[1], r[2]) + com;  // shape coordinates
    const Vec3 s(0.3, 0.1, 0.05);
    EXPECT_NEAR(p.cwiseQuotient(s).squaredNorm(), 1, 1e-12);
    // the outward surface normal there is -n
    const Vec3 normal = p.cwiseQuotient(s.cwiseProduct(s)).normalized();
    EXPECT_NEAR(normal.dot(-nn), 1, 1e-12);
  }
}

TEST(Contact, BoxEdgesGetPointsAtMostMaxGapApart) {
  const Shape plate = Shape::box(0.3, 0.2, 0.01);
  EXPECT_EQ(contact_params(plate, Vec3::Zero(), 0.3, 0.5, 0).count(), 8u);
  // 0.3 m edges: 5 gaps of 0.06 m (4 inner points each); 0.2 m: 3 gaps (2); 0.01 m: none
  const ContactParams k = contact_params(plate, Vec3::Zero(), 0.3, 0.5, 0.07);
  EXPECT_EQ(k.count(), 8u + 4 * 4 + 4 * 2 + 4 * 0);
  // every point lies on an edge of the box (two coordinates at +-half size)
  for (size_t i = 0; i < k.count(); ++i) {
    int on = 0;
    const Vec3 h(0.15, 0.1, 0.005);
    for (int a = 0; a < 3; ++a) on += std::abs(std::abs(k.points[3 * i + a]) - h[a]) < 1e-15;
    EXPECT_GE(on, 2) << i;
  }
  // points relative to the centre of mass
  const ContactParams off = contact_params(plate, Vec3(0.01, 0, 0), 0.3, 0.5, 0);
  EXPECT_DOUBLE_EQ(off.points[0], -0.15 - 0.01);
  // the count per edge is capped
  EXPECT_EQ(contact_params(Shape::box(10, 0.1, 0.1), Vec3::Zero(), 0, 0, 1e-3).count(),
            8u + 12 * kContactEdgePoints);
}

// Each inner edge point names the two corners of its edge (ContactParams::edge_ends): it lies on
// the segment between them, strictly inside, and the corners are corners (one coordinate apart).
TEST(Contact, BoxEdgePointsNameTheirEdgesCorners) {
  const ContactParams k =
      contact_params(Shape::box(0.3, 0.2, 0.05), Vec3(0.01, -0.02, 0), 0.3, 0.5, 0.04);
  ASSERT_EQ(k.edge_ends.size(), 2 * k.count());
  auto point = [&](size_t i) {
    return Vec3(k.points[3 * i], k.points[3 * i + 1], k.points[3 * i + 2]);
  };
  size_t inner = 0;
  for (size_t i = 0; i < k.count(); ++i) {
    const uint8_t a = k.edge_ends[2 * i], b = k.edge_ends[2 * i + 1];
    if (i < 8) {
      EXPECT_EQ(a, ContactParams::kNotOnEdge) << i;
      continue;
    }
    ++inner;
    ASSERT_LT(a, 8) << i;
    ASSERT_LT(b, 8) << i;
    const Vec3 ca = point(a), cb = point(b), p = point(i);
    int differ = 0;
    for (int c = 0; c < 3; ++c) differ += std::abs(ca[c] - cb[c]) > 1e-12;
    EXPECT_EQ(differ, 1) << "corners " << int(a) << ", " << int(b) << " share an edge";
    const Vec3 e = cb - ca;
    const double t = (p - ca).dot(e) / e.squaredNorm();
    EXPECT_GT(t, 0) << i;
    EXPECT_LT(t, 1) << i;
    EXPECT_LT((ca + t * e - p).norm(), 1e-14) << i;
  }
  EXPECT_EQ(inner, 4u * (7 + 4 + 1));  // 0.3 m: 8 gaps; 0.2 m: 5; 0.05 m: 2
  for (const uint8_t e : contact_params(Shape::sphere(0.1), Vec3::Zero(), 0, 0, 0.01).edge_ends)
    EXPECT_EQ(e, ContactParams::kNotOnEdge);
}

TEST(Contact, MeshPointsAreItsConvexHullVertices) {
  // a unit cube's 8 corners, the centres of two faces pushed in (a dent) and one pulled out
  auto mesh = std::make_shared<TriangleMesh>();
  for (int c = 0; c < 8; ++c)
    mesh->vertices.push_back(Vec3(c & 1 ? 0.5 : -0.5, c & 2 ? 0.5 : -0.5, c & 4 ? 0.5 : -0.5));
  mesh->vertices.push_back(Vec3(0, 0, 0.3));    // dent in the top: inside the hull
  mesh->vertices.push_back(Vec3(0.2, 0, -0.4));  // dent in the bottom: inside
  mesh->vertices.push_back(Vec3(0, 0.9, 0));     // a bump: on the hull
  Shape s;
  s.type = ShapeType::Mesh;
  s.mesh = mesh;
  const ContactParams k = contact_params(s, Vec3(0, 0.1, 0), 0.2, 0.4, 0);
  EXPECT_FALSE(k.support);
  ASSERT_EQ(k.count(), 9u);
  bool bump = false;
  for (size_t i = 0; i < k.count(); ++i) {
    EXPECT_NE(k.points[3 * i + 2], 0.3);
    bump |= std::abs(k.points[3 * i + 1] - 0.8) < 1e-15;  // relative to the centre of mass
  }
  EXPECT_TRUE(bump);
}

TEST(Contact, ParamsRejectRestitutionOutsideZeroOneAndNegativeFriction) {
  const Shape s = Shape::sphere(0.1);
  EXPECT_THROW(contact_params(s, Vec3::Zero(), -0.1, 0.5, 0), Error);
  EXPECT_THROW(contact_params(s, Vec3::Zero(), 1.2, 0.5, 0), Error);
  EXPECT_THROW(contact_params(s, Vec3::Zero(), 0.5, -1, 0), Error);
  EXPECT_THROW(contact_params(s, Vec3::Zero(), std::nan(""), 0.5, 0), Error);
  EXPECT_NO_THROW(contact_params(s, Vec3::Zero(), 1.0, 0, 0));
}

}  // namespace
}  // namespace lrigid
