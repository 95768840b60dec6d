// The camera of `lrigid render` and `lrigid view` as plain geometry (no VTK): a look-at pose with
// a vertical field of view, fitting a box into that field of view, and the true-scale rule that
// decides whether a body entry is drawn at its real size or enlarged. Metres and degrees.
#pragma once
#include <vector>

#include "util/types.h"

namespace lrigid::app {

// An axis-aligned box, m; empty until a point is added.
struct Bounds {
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  void add(const Vec3& p) { lo = lo.cwiseMin(p), hi = hi.cwiseMax(p); }
  bool empty() const { return lo.x() > hi.x(); }
  double diag() const { return empty() ? 0.0 : (hi - lo).norm(); }
  Vec3 centre() const { return 0.5 * (lo + hi); }
};

// A perspective camera: where it is, what it looks at (the centre of the picture), which way is
// up in the picture, and the vertical field of view (degrees, in (0, 180)).
struct CameraPose {
  Vec3 position = Vec3(0, 0, 1);
  Vec3 target = Vec3::Zero();
  Vec3 up = Vec3::UnitZ();
  double fov_deg = 30;
};

// The default field of view (degrees): VTK's and every earlier picture's.
constexpr double kDefaultFovDeg = 30;
// The default direction from the target to the camera: in front, to the left and above (Z up).
Vec3 default_view_direction();

// The picture's up for a camera at `position` looking at `target`: world +z made perpendicular
// to the line of sight, or +y when looking straight up or down.
Vec3 view_up(const Vec3& position, const Vec3& target);

// A camera looking at box's centre from `direction` (towards the camera, any length) with a
// vertical field of view `fov_deg`, in a picture `aspect` = width / height, as far away as it
// must be for the box's bounding sphere, shrunk by `fill`, to fit in both the vertical and the
// horizontal field of view. fill = 0.77 crops the sphere (a box's corners rarely reach it) the
// way lrigid's pictures always have; 1 keeps all of the sphere.
CameraPose fit_box(const Bounds& box, const Vec3& direction, double fov_deg, double aspect,
                   double fill = 0.77);

// Pixels per metre across the line of sight at point p, for a picture `height` pixels tall;
// 0 for a point at or behind the camera.
double pixels_per_metre(const CameraPose& c, const Vec3& p, int height);

// The true-scale rule: a body entry is drawn at its real size when its median body spans at
// least kMinBodyPixels pixels; otherwise all of its bodies are drawn enlarged by one factor, so
// that the median body spans kMinBodyPixels.
constexpr double kMinBodyPixels = 4;

// The factor of one body entry: `sizes` (m) the largest extent of each of its bodies, `centres`
// (m) where they are in the frames drawn (visible ones only). 1 when the median body spans at
// least kMinBodyPixels at the median depth of the bodies in front of the camera (or when none is
// in front), else kMinBodyPixels over what it spans.
double true_scale_factor(const CameraPose& c, int height, std::vector<double> sizes,
                         const std::vector<Vec3>& centres);

}  // namespace lrigid::app
