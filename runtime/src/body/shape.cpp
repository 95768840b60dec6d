#include "body/shape.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "body/mesh_check.h"
#include "body/shape_limits.h"
#include "util/error.h"

namespace lrigid {

const char* shape_type_name(ShapeType t) {
  switch (t) {
    case ShapeType::Sphere:
      return "sphere";
    case ShapeType::Ellipsoid:
      return "ellipsoid";
    case ShapeType::Box:
      return "box";
    case ShapeType::Mesh:
      return "mesh";
  }
  return "unknown";
}

namespace {

// sizes must be finite and within [kMinShapeLength, kMaxShapeLength] (NaN fails the comparison)
void require_positive(const char* shape, const char* what, double v) {
  if (!(v >= kMinShapeLength && v <= kMaxShapeLength)) {
    std::ostringstream m;
    m << shape << ": " << what << " must be a length in [1e-9, 1e6] m, got " << v;
    throw Error(ExitCode::BadInput, m.str());
  }
}

}  // namespace

Shape Shape::sphere(double radius) {
  require_positive("sphere", "radius", radius);
  Shape s;
  s.type = ShapeType::Sphere;
  s.half_extents = Vec3::Constant(radius);
  return s;
}

Shape Shape::ellipsoid(double a, double b, double c) {
  require_positive("ellipsoid", "semi-axis a", a);
  require_positive("ellipsoid", "semi-axis b", b);
  require_positive("ellipsoid", "semi-axis c", c);
  Shape s;
  s.type = ShapeType::Ellipsoid;
  s.half_extents = Vec3(a, b, c);
  return s;
}

Shape Shape::box(double lx, double ly, double lz) {
  require_positive("box", "edge length lx", lx);
  require_positive("box", "edge length ly", ly);
  require_positive("box", "edge length lz", lz);
  const double ratio = std::max({lx, ly, lz}) / std::min({lx, ly, lz});
  if (!(ratio <= kMaxBoxAspect)) {
    std::ostringstream m;
    m << "box: longest edge / shortest edge must be at most 1e5 (the boundary elements lose "
         "the thin direction beyond), got " << ratio;
    throw Error(ExitCode::BadInput, m.str());
  }
  Shape s;
  s.type = ShapeType::Box;
  s.half_extents = 0.5 * Vec3(lx, ly, lz);
  return s;
}

Shape Shape::from_mesh(std::shared_ptr<const TriangleMesh> mesh, std::string source) {
  if (!mesh) throw Error(ExitCode::BadInput, where(source, "", "no mesh given"));
  check_closed_mesh(*mesh, source);
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (const auto& f : mesh->faces)
    for (int k = 0; k < 3; ++k) {
      lo = lo.cwiseMin(mesh->vertices[f[k]]);
      hi = hi.cwiseMax(mesh->vertices[f[k]]);
    }
  Shape s;
  s.type = ShapeType::Mesh;
  s.half_extents = 0.5 * (hi - lo);
  s.mesh = std::move(mesh);
  s.source = std::move(source);
  return s;
}

}  // namespace lrigid
