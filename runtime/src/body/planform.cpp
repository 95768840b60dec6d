#include "body/planform.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "body/mass_properties.h"
#include "body/outline.h"

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
  p.e1 = Vec3::Unit(i1);
  p.e2 = Vec3::Unit(i2);
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
    case ShapeType::Mesh: {
      // the tightest rectangle around the vertices seen along the normal (those of the faces:
      // the shape's bounding box counts the same), in the coordinates (i1, i2)
      const TriangleMesh& m = *shape.mesh;
      std::vector<char> used(m.vertices.size(), 0);
      for (const auto& f : m.faces)
        for (int k = 0; k < 3; ++k) used[f[k]] = 1;
      std::vector<Vec2> seen;
      seen.reserve(m.vertices.size());
      for (size_t v = 0; v < m.vertices.size(); ++v)
        if (used[v]) seen.emplace_back(m.vertices[v][i1], m.vertices[v][i2]);
      const OutlineRectangle r = min_area_rectangle(seen);
      p.h1 = r.h1;
      p.h2 = r.h2;
      p.angle = r.angle();
      p.e1 = Vec3::Zero();
      p.e2 = Vec3::Zero();
      p.e1[i1] = r.axis1.x();
      p.e1[i2] = r.axis1.y();
      p.e2[i1] = r.axis2.x();
      p.e2[i2] = r.axis2.y();
      p.area = projected_area(m, normal_axis);
      p.rectangularity = p.area / (4.0 * p.h1 * p.h2);
      break;
    }
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
