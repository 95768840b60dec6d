#include "camera.h"

#include <algorithm>
#include <cmath>

#include "util/quantile.h"

namespace lrigid::app {

namespace {
constexpr double kPi = 3.14159265358979323846;
double half_angle_rad(double fov_deg) { return 0.5 * fov_deg * kPi / 180; }
}  // namespace

Vec3 default_view_direction() { return Vec3(0.9, -1.6, 0.8).normalized(); }

Vec3 view_up(const Vec3& position, const Vec3& target) {
  const Vec3 d = (target - position).normalized();
  // +z unless the line of sight is (nearly) vertical
  const Vec3 world_up = std::abs(d.z()) > 0.999 ? Vec3::UnitY() : Vec3::UnitZ();
  return (world_up - world_up.dot(d) * d).normalized();
}

CameraPose fit_box(const Bounds& box, const Vec3& direction, double fov_deg, double aspect,
                   double fill) {
  CameraPose c;
  c.fov_deg = fov_deg;
  c.target = box.empty() ? Vec3::Zero() : box.centre();
  const double radius = std::max(0.5 * box.diag(), 1e-6);
  // the narrower of the two fields of view holds the sphere
  const double tan_v = std::tan(half_angle_rad(fov_deg));
  const double tan_half = std::min(tan_v, tan_v * aspect);
  const double distance = fill * radius / std::sin(std::atan(tan_half));
  c.position = c.target + distance * direction.normalized();
  c.up = view_up(c.position, c.target);
  return c;
}

double pixels_per_metre(const CameraPose& c, const Vec3& p, int height) {
  const Vec3 axis = (c.target - c.position).normalized();
  const double depth = (p - c.position).dot(axis);
  if (depth <= 0) return 0;
  return height / (2 * depth * std::tan(half_angle_rad(c.fov_deg)));
}

double true_scale_factor(const CameraPose& c, int height, std::vector<double> sizes,
                         const std::vector<Vec3>& centres) {
  std::vector<double> scale;  // pixels per metre where each body is
  for (const Vec3& p : centres)
    if (const double k = pixels_per_metre(c, p, height); k > 0) scale.push_back(k);
  if (scale.empty() || sizes.empty()) return 1;
  // the median depth is where the median pixels per metre is (one decreases as the other grows)
  const double spans = median(std::move(sizes)) * median(std::move(scale));
  return spans >= kMinBodyPixels ? 1.0 : kMinBodyPixels / std::max(spans, 1e-9);
}

}  // namespace lrigid::app
