// The outline of a flat body (body/outline.h: convex hull, tightest rectangle) and its planform
// (body/planform.h) whatever way the outline is turned in its file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "body/outline.h"
#include "body/planform.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

Vec2 turned2(const Vec2& p, double angle) {
  return Vec2(std::cos(angle) * p.x() - std::sin(angle) * p.y(),
              std::sin(angle) * p.x() + std::cos(angle) * p.y());
}

// Every point inside the rectangle (to tol), and each of its four sides touched by one of them:
// the rectangle bounds the points and is as tight as its orientation allows
void expect_tight(const OutlineRectangle& r, const std::vector<Vec2>& pts, double tol) {
  EXPECT_NEAR(r.axis1.norm(), 1.0, 1e-15);
  EXPECT_NEAR(r.axis1.dot(r.axis2), 0.0, 1e-15);
  EXPECT_NEAR(r.axis1.x() * r.axis2.y() - r.axis1.y() * r.axis2.x(), 1.0, 1e-15);  // +90 deg
  double lo1 = INFINITY, hi1 = -INFINITY, lo2 = INFINITY, hi2 = -INFINITY;
  for (const Vec2& p : pts) {
    const double s = (p - r.centre).dot(r.axis1), t = (p - r.centre).dot(r.axis2);
    lo1 = std::min(lo1, s), hi1 = std::max(hi1, s), lo2 = std::min(lo2, t), hi2 = std::max(hi2, t);
  }
  EXPECT_NEAR(lo1, -r.h1, tol);
  EXPECT_NEAR(hi1, r.h1, tol);
  EXPECT_NEAR(lo2, -r.h2, tol);
  EXPECT_NEAR(hi2, r.h2, tol);
}

// the turn of a direction modulo a quarter turn, in [0, pi/2)
double quarter_turn(double angle) {
  const double q = std::fmod(angle, M_PI / 2);
  return q < 0 ? q + M_PI / 2 : q;
}

TEST(Outline, ConvexHullDropsInnerRepeatedAndCollinearPoints) {
  // a square with its edge midpoints, its centre, a repeated corner and inner points
  std::vector<Vec2> p = {{1, 1},  {-1, 1}, {-1, -1}, {1, -1}, {0, 1},    {1, 0},
                         {0, -1}, {-1, 0}, {0, 0},   {1, 1},  {0.5, 0.2}, {-0.9, 0.9}};
  std::shuffle(p.begin(), p.end(), std::mt19937(3));
  const std::vector<Vec2> h = convex_hull(p);
  ASSERT_EQ(h.size(), 4u);
  // counter-clockwise from the lowest of the leftmost points
  EXPECT_EQ(h[0], Vec2(-1, -1));
  EXPECT_EQ(h[1], Vec2(1, -1));
  EXPECT_EQ(h[2], Vec2(1, 1));
  EXPECT_EQ(h[3], Vec2(-1, 1));
  // points on one line: its two ends
  const std::vector<Vec2> line = convex_hull({{0, 0}, {2, 1}, {1, 0.5}, {-2, -1}});
  ASSERT_EQ(line.size(), 2u);
  EXPECT_EQ(line[0], Vec2(-2, -1));
  EXPECT_EQ(line[1], Vec2(2, 1));
  EXPECT_EQ(convex_hull({{3, 4}, {3, 4}}).size(), 1u);
  EXPECT_TRUE(convex_hull({}).empty());
}

// A rectangle of 3 x 1 turned by 30 degrees about an off-centre point, with points inside and on
// its sides: its own half sides, centre and angle; turned by 60 degrees its short side is the
// one nearest the x axis (at -30 degrees)
TEST(Outline, TheTightestRectangleOfATurnedRectangleIsItself) {
  const Vec2 c(0.2, -0.7);
  for (const double turn : {M_PI / 6, M_PI / 3}) {
    SCOPED_TRACE(turn);
    std::vector<Vec2> pts;
    for (const Vec2& p : {Vec2(-1.5, -0.5), Vec2(1.5, -0.5), Vec2(1.5, 0.5), Vec2(-1.5, 0.5),
                          Vec2(0.3, 0.5), Vec2(1.5, 0.1), Vec2(0.2, 0.1), Vec2(-1, -0.2)})
      pts.push_back(c + turned2(p, turn));
    const OutlineRectangle r = min_area_rectangle(pts);
    const bool long_first = turn < M_PI / 4;
    EXPECT_NEAR(r.h1, long_first ? 1.5 : 0.5, 1e-14);
    EXPECT_NEAR(r.h2, long_first ? 0.5 : 1.5, 1e-14);
    EXPECT_NEAR(r.angle(), long_first ? turn : turn - M_PI / 2, 1e-14);
    EXPECT_NEAR((r.centre - c).norm(), 0.0, 1e-14);
    EXPECT_NEAR(r.area(), 3.0, 1e-13);
    expect_tight(r, pts, 1e-14);
  }
}

// A regular hexagon of circumradius a: every rectangle with a side along an edge is 2a by
// sqrt(3) a (Freeman & Shapira: the tightest has a side along an edge), R = 3/4; its sides are
// along the edges' directions (multiples of 60 degrees) or across them
TEST(Outline, TheTightestRectangleOfARegularHexagon) {
  const double a = 0.7;
  for (const double turn : {0.0, 0.1, M_PI / 6, 1.0}) {
    SCOPED_TRACE(turn);
    std::vector<Vec2> pts;
    for (int k = 0; k < 6; ++k) pts.push_back(turned2(Vec2(a * std::cos(k * M_PI / 3),
                                                           a * std::sin(k * M_PI / 3)), turn));
    pts.emplace_back(0.1, 0.05);
    const OutlineRectangle r = min_area_rectangle(pts);
    EXPECT_NEAR(r.area(), 2 * std::sqrt(3.0) * a * a, 1e-13);
    EXPECT_NEAR(std::max(r.h1, r.h2), a, 1e-14);
    EXPECT_NEAR(std::min(r.h1, r.h2), std::sqrt(3.0) / 2 * a, 1e-14);
    EXPECT_NEAR(1.5 * std::sqrt(3.0) * a * a / r.area(), 0.75, 1e-13);
    // an edge runs along turn + 120 degrees: the sides are at turn + multiples of 30 degrees
    const double off = std::fmod(quarter_turn(r.angle() - turn) + 1e-12, M_PI / 6);
    EXPECT_LT(off, 1e-11) << r.angle();
    EXPECT_NEAR(r.centre.norm(), 0.0, 1e-14);
    expect_tight(r, pts, 1e-14);
  }
}

// A right triangle of legs p along x and q along y: a rectangle on any side is that side times
// its height, twice the triangle's area, so the least is p q (R = 1/2) with a side along a leg or
// along the hypotenuse
TEST(Outline, TheTightestRectangleOfARightTriangle) {
  const double p = 3.0, q = 1.0;
  const std::vector<Vec2> pts = {{0, 0}, {p, 0}, {0, q}, {1, 0.2}};
  const OutlineRectangle r = min_area_rectangle(pts);
  EXPECT_NEAR(r.area(), p * q, 1e-13);
  const double hyp = std::atan2(-q, p);  // the hypotenuse's direction
  const double a = quarter_turn(r.angle());
  const bool along_leg = a < 1e-14 || a > M_PI / 2 - 1e-14;
  const bool along_hyp = std::abs(a - quarter_turn(hyp)) < 1e-14;
  EXPECT_TRUE(along_leg || along_hyp) << r.angle();
  expect_tight(r, pts, 1e-14);
}

// Random point clouds: no rectangle at any of 20000 turns is smaller than the calipers' (their
// rectangle is the least over all turns, not only over the hull's edges), and the same as
// trying each hull edge against every hull point
TEST(Outline, TheTightestRectangleIsTheLeastAtAnyTurn) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int trial = 0; trial < 6; ++trial) {
    std::vector<Vec2> pts;
    const int n = 5 + 40 * trial;
    for (int i = 0; i < n; ++i) pts.emplace_back(2.0 * g(rng), 0.5 * g(rng) + 0.3 * g(rng));
    const OutlineRectangle r = min_area_rectangle(pts);
    expect_tight(r, pts, 1e-12);
    const std::vector<Vec2> h = convex_hull(pts);
    auto area_at = [&](const Vec2& d) {
      const Vec2 m(-d.y(), d.x());
      double lo1 = INFINITY, hi1 = -INFINITY, lo2 = INFINITY, hi2 = -INFINITY;
      for (const Vec2& x : h) {
        lo1 = std::min(lo1, x.dot(d)), hi1 = std::max(hi1, x.dot(d));
        lo2 = std::min(lo2, x.dot(m)), hi2 = std::max(hi2, x.dot(m));
      }
      return (hi1 - lo1) * (hi2 - lo2);
    };
    double brute = INFINITY;
    for (size_t i = 0; i < h.size(); ++i)
      brute = std::min(brute, area_at((h[(i + 1) % h.size()] - h[i]).normalized()));
    EXPECT_NEAR(r.area(), brute, 1e-12 * brute) << trial;
    for (int k = 0; k < 20000; ++k) {
      const double t = M_PI / 2 * k / 20000;
      ASSERT_GE(area_at(Vec2(std::cos(t), std::sin(t))), r.area() * (1 - 1e-12)) << trial << " " << t;
    }
  }
}

// An outline drawn along the axes keeps them exactly (the planform a square OBJ had when only
// its bounding box was read)
TEST(Outline, AnOutlineAlongTheAxesKeepsThem) {
  const OutlineRectangle r = min_area_rectangle({{-0.3, -0.1}, {0.3, -0.1}, {0.3, 0.1}, {-0.3, 0.1}});
  EXPECT_EQ(r.axis1, Vec2(1, 0));
  EXPECT_EQ(r.axis2, Vec2(0, 1));
  EXPECT_FALSE(std::signbit(r.axis2.x()));
  EXPECT_EQ(r.h1, 0.3);
  EXPECT_EQ(r.h2, 0.1);
  EXPECT_EQ(r.angle(), 0.0);
}

// rotate a mesh about z by angle
TriangleMesh turned_about_z(TriangleMesh m, double angle) {
  for (Vec3& v : m.vertices) {
    const Vec2 p = turned2(Vec2(v.x(), v.y()), angle);
    v.x() = p.x();
    v.y() = p.y();
  }
  return m;
}

Shape outline_mesh(const TriangleMesh& m) {
  return Shape::from_mesh(std::make_shared<const TriangleMesh>(m), "outline.obj");
}

// A square prism drawn turned about its normal is the square at every turn: R = 1, its half
// side, and e1, e2 along its sides (the one nearest x first); its bounding box's square is up to
// twice as large (R = 1/2 at 45 degrees), which the planform does not read
TEST(Planform, ATurnedSquareMeshIsASquare) {
  const double r = 0.03, t = 1e-4;
  for (const double deg : {0.0, 10.0, 30.0, 45.0, 60.0, 89.0}) {
    SCOPED_TRACE(deg);
    const Shape s = outline_mesh(turned_about_z(test::rect_prism(r, r, t), deg * M_PI / 180));
    const Planform p = planform_of(s, 2);
    EXPECT_NEAR(p.rectangularity, 1.0, 1e-14);
    EXPECT_NEAR(p.w, 1.0, 1e-13);
    EXPECT_NEAR(p.h1, r, 1e-16);
    EXPECT_NEAR(p.h2, r, 1e-16);
    EXPECT_NEAR(p.area, 4 * r * r, 1e-17);
    // the side nearest x: deg itself, or deg - 90 beyond 45 (at 45 either side is as near)
    const double want = (deg > 45.0 ? deg - 90.0 : deg) * M_PI / 180;
    EXPECT_NEAR(std::remainder(p.angle - want, M_PI / 2), 0.0, 1e-13);
    EXPECT_GT(p.angle, -M_PI / 4 - 1e-13);
    EXPECT_LE(p.angle, M_PI / 4 + 1e-13);
    EXPECT_NEAR((p.e1 - Vec3(std::cos(p.angle), std::sin(p.angle), 0)).norm(), 0.0, 1e-13);
    EXPECT_NEAR((p.e2 - Vec3(-std::sin(p.angle), std::cos(p.angle), 0)).norm(), 0.0, 1e-13);
    EXPECT_NEAR(p.e1.cross(p.e2).z(), 1.0, 1e-15);
    if (deg == 0.0) {
      // drawn along the axes: the axes themselves, and the bounding box's half sides
      EXPECT_EQ(p.e1, Vec3::UnitX());
      EXPECT_EQ(p.e2, Vec3::UnitY());
      EXPECT_EQ(p.h1, s.half_extents.x());
      EXPECT_EQ(p.h2, s.half_extents.y());
      EXPECT_EQ(p.rectangularity, 1.0);
    }
  }
  // a 3:1 rectangle turned by 30 degrees: its long side first
  const Planform l =
      planform_of(outline_mesh(turned_about_z(test::rect_prism(3 * r, r, t), M_PI / 6)), 2);
  EXPECT_NEAR(l.rectangularity, 1.0, 1e-14);
  EXPECT_NEAR(l.h1, 3 * r, 1e-16);
  EXPECT_NEAR(l.h2, r, 1e-16);
  EXPECT_NEAR(l.angle, M_PI / 6, 1e-13);
  // the normal along x: the in-plane axes are y and z, the angle from y towards z
  TriangleMesh side = turned_about_z(test::rect_prism(r, r, t), M_PI / 6);
  for (Vec3& v : side.vertices) v = Vec3(v.z(), v.x(), v.y());
  const Planform px = planform_of(outline_mesh(side), 0);
  EXPECT_NEAR(px.rectangularity, 1.0, 1e-14);
  EXPECT_NEAR(px.angle, M_PI / 6, 1e-13);
  EXPECT_NEAR((px.e1 - Vec3(0, std::cos(M_PI / 6), std::sin(M_PI / 6))).norm(), 0.0, 1e-13);
  EXPECT_NEAR((px.e2 - Vec3(0, -std::sin(M_PI / 6), std::cos(M_PI / 6))).norm(), 0.0, 1e-13);
}

// A regular 48-gon: its tightest rectangle is the square on two opposite edges, 2 r cos(pi/48)
// wide, at any turn, so its area, R and w do not depend on the turn; R = 0.7865, 0.14 % above an
// ellipse's pi/4 (w = 0.005): a regular polygon fills its edges' square more than a circle does
TEST(Planform, A48GonsPlanformDoesNotDependOnItsTurn) {
  const int n = 48;
  const double r = 0.045, t = 7e-5;
  const double area = 0.5 * n * r * r * std::sin(2 * M_PI / n);
  const double side = 2 * r * std::cos(M_PI / n);
  const double R = area / (side * side);
  EXPECT_NEAR(R, 0.7865, 1e-4);
  for (const double deg : {0.0, 3.75, 10.0, 45.0, 71.3}) {
    SCOPED_TRACE(deg);
    const Planform p = planform_of(outline_mesh(turned_about_z(test::polygon_prism(n, r, t), deg * M_PI / 180)), 2);
    EXPECT_NEAR(p.area, area, 1e-15);
    EXPECT_NEAR(p.h1, side / 2, 1e-15);
    EXPECT_NEAR(p.h2, side / 2, 1e-15);
    EXPECT_NEAR(p.rectangularity, R, 1e-12);
    EXPECT_NEAR(p.w, (R - M_PI / 4) / (1 - M_PI / 4), 1e-10);
    // its sides run along edges: at 3.75 degrees plus a multiple of 7.5 from the turn
    const double off = std::fmod(quarter_turn(p.angle - deg * M_PI / 180) + M_PI / 48, M_PI / 24);
    EXPECT_TRUE(off < 1e-12 || off > M_PI / 24 - 1e-12) << p.angle;
  }
}

// Analytic shapes keep their own axes and sizes
TEST(Planform, BoxesAndEllipsoidsKeepTheirAxes) {
  const Planform b = planform_of(Shape::box(0.06, 0.02, 1e-4), 2);
  EXPECT_EQ(b.e1, Vec3::UnitX());
  EXPECT_EQ(b.e2, Vec3::UnitY());
  EXPECT_EQ(b.angle, 0.0);
  EXPECT_EQ(b.c1, 0.03);
  EXPECT_EQ(b.c2, 0.01);
  EXPECT_EQ(b.w, 1.0);
  const Planform e = planform_of(Shape::ellipsoid(1e-4, 0.05, 0.02), 0);
  EXPECT_EQ(e.e1, Vec3::UnitY());
  EXPECT_EQ(e.e2, Vec3::UnitZ());
  EXPECT_EQ(e.a1, 0.05);
  EXPECT_EQ(e.a2, 0.02);
  EXPECT_EQ(e.w, 0.0);
}

}  // namespace
}  // namespace lrigid
