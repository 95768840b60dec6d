// The camera of lrigid render and lrigid view (runtime/app/camera.h): look-at, fitting a box in a
// field of view, pixels per metre and the true-scale rule, against the pinhole camera's formulas.
#include "camera.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using lrigid::Vec3;
using namespace lrigid::app;

constexpr double kPi = 3.14159265358979323846;

// where p lands in a picture of the camera, in units of the distance to the picture's edge:
// (horizontal, vertical), both within [-1, 1] when p is in view
std::pair<double, double> on_picture(const CameraPose& c, double aspect, const Vec3& p) {
  const Vec3 axis = (c.target - c.position).normalized();
  const Vec3 right = axis.cross(c.up).normalized();
  const Vec3 d = p - c.position;
  const double depth = d.dot(axis), t = std::tan(0.5 * c.fov_deg * kPi / 180);
  return {d.dot(right) / (depth * t * aspect), d.dot(c.up) / (depth * t)};
}

TEST(Camera, UpIsWorldZAcrossTheLineOfSightOrYLookingStraightDown) {
  const Vec3 up = view_up(Vec3(3, -4, 2), Vec3(0, 0, 0));
  EXPECT_NEAR(up.norm(), 1, 1e-12);
  EXPECT_NEAR(up.dot(Vec3(-3, 4, -2).normalized()), 0, 1e-12);
  EXPECT_GT(up.z(), 0.8);
  const Vec3 down = view_up(Vec3(1, 2, 10), Vec3(1, 2, 0));
  EXPECT_NEAR((down - Vec3::UnitY()).norm(), 0, 1e-12);
}

TEST(Camera, AFittedBoxIsInViewAndItsSphereTouchesTheNarrowerEdge) {
  Bounds box;
  box.add(Vec3(-4, 1, 0));
  box.add(Vec3(6, 3, 2.5));
  for (const double aspect : {16.0 / 9.0, 0.5}) {
    const CameraPose c = fit_box(box, Vec3(1, -2, 1), 40, aspect, 1.0);
    EXPECT_NEAR((c.target - box.centre()).norm(), 0, 1e-12);
    // every corner in the picture
    double widest = 0;
    for (int k = 0; k < 8; ++k) {
      const Vec3 p((k & 1) ? box.hi.x() : box.lo.x(), (k & 2) ? box.hi.y() : box.lo.y(),
                   (k & 4) ? box.hi.z() : box.lo.z());
      const auto [u, v] = on_picture(c, aspect, p);
      EXPECT_LE(std::abs(u), 1.0) << "aspect " << aspect << " corner " << k;
      EXPECT_LE(std::abs(v), 1.0) << "aspect " << aspect << " corner " << k;
      widest = std::max({widest, std::abs(u), std::abs(v)});
    }
    EXPECT_GT(widest, 0.5) << "the box should fill a good part of the picture";
    // the bounding sphere's tangent cone is the narrower half angle: distance = r / sin(half)
    const double half_v = 20 * kPi / 180;
    const double half = aspect >= 1 ? half_v : std::atan(std::tan(half_v) * aspect);
    EXPECT_NEAR((c.position - c.target).norm(), 0.5 * box.diag() / std::sin(half), 1e-9);
    // fill < 1 comes closer by that factor
    const CameraPose near = fit_box(box, Vec3(1, -2, 1), 40, aspect, 0.77);
    EXPECT_NEAR((near.position - near.target).norm(), 0.77 * (c.position - c.target).norm(), 1e-9);
  }
}

TEST(Camera, PixelsPerMetreFollowDepthAndFieldOfView) {
  CameraPose c;
  c.position = Vec3(0, 0, 0);
  c.target = Vec3(5, 0, 0);
  c.up = Vec3::UnitZ();
  c.fov_deg = 90;  // tan(45 deg) = 1: the picture is 2 * depth tall
  EXPECT_NEAR(pixels_per_metre(c, Vec3(2, 7, -3), 200), 200 / (2 * 2.0), 1e-9);
  EXPECT_NEAR(pixels_per_metre(c, Vec3(4, 0, 0), 200), 25, 1e-9);
  EXPECT_EQ(pixels_per_metre(c, Vec3(-1, 0, 0), 200), 0);  // behind
}

TEST(Camera, TrueScaleUnlessTheMedianBodyWouldSpanUnderFourPixels) {
  CameraPose c;
  c.position = Vec3(0, 0, 0);
  c.target = Vec3(1, 0, 0);
  c.fov_deg = 30;
  const int height = 720;
  const double k1 = height / (2 * std::tan(15 * kPi / 180));  // pixels per metre at 1 m
  // leaves of 5, 8 and 12 cm: the median is 8 cm
  const std::vector<double> sizes = {0.05, 0.12, 0.08};
  // at 1 m a 8 cm leaf spans about 107 pixels: true size
  EXPECT_EQ(true_scale_factor(c, height, sizes, {Vec3(1, 0, 0), Vec3(1, 0.1, 0)}), 1.0);
  // at 100 m about 1.07 pixels: one factor that makes the median body span 4 pixels
  const double f =
      true_scale_factor(c, height, sizes, {Vec3(90, 0, 0), Vec3(100, 0, 0), Vec3(110, 5, 0)});
  EXPECT_NEAR(f * 0.08 * k1 / 100, kMinBodyPixels, 1e-9);
  EXPECT_GT(f, 3.5);
  // bodies behind the camera do not count; none in front: true size
  EXPECT_EQ(true_scale_factor(c, height, sizes, {Vec3(-100, 0, 0)}), 1.0);
}

}  // namespace
