#include "body/planform.h"

#include <algorithm>
#include <cmath>

#include "body/mass_properties.h"

namespace lrigid {

double planform_weight(double rectangularity) {
  const double w = (rectangularity - M_PI / 4.0) / (1.0 - M_PI / 4.0);
  return std::clamp(w, 0.0, 1.0);
}

Planform planform_of(const Shape& shape, int normal_axis) {
  const int i1 = (normal_axis + 1) % 3, i2 = (normal_axis + 2) % 3;
  Planform p;
  p.h1 = shape.half_extents[i1];
  p.h2 = shape.half_extents[i2];
  switch (shape.type) {
    case ShapeType::Box:
      p.rectangularity = 1.0;
      p.area = 4.0 * p.h1 * p.h2;
      break;
    case ShapeType::Sphere:
    case ShapeType::Ellipsoid:
      p.rectangularity = M_PI / 4.0;
      p.area = M_PI * p.h1 * p.h2;
      break;
    case ShapeType::Mesh:
      p.area = projected_area(*shape.mesh, normal_axis);
      p.rectangularity = p.area / (4.0 * p.h1 * p.h2);
      break;
  }
  p.w = planform_weight(p.rectangularity);
  // R = 1 and R = pi/4 give the shape's own sizes exactly (sqrt(1) = 1, 4 (pi/4) / pi = 1)
  const double fc = std::sqrt(p.rectangularity), fa = std::sqrt(4.0 * p.rectangularity / M_PI);
  p.c1 = p.h1 * fc;
  p.c2 = p.h2 * fc;
  p.a1 = p.h1 * fa;
  p.a2 = p.h2 * fa;
  return p;
}

}  // namespace lrigid
