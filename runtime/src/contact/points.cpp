#include "contact/points.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "contact/hull.h"
#include "model/model.h"
#include "util/error.h"

namespace lrigid {

namespace {

void add_point(ContactParams* k, const Vec3& p, int end0 = ContactParams::kNotOnEdge,
               int end1 = ContactParams::kNotOnEdge) {
  for (int a = 0; a < 3; ++a) k->points.push_back(p[a]);
  k->edge_ends.push_back(uint8_t(end0));
  k->edge_ends.push_back(uint8_t(end1));
}

}  // namespace

ContactParams contact_params(const Shape& shape, const Vec3& com, double restitution,
                             double friction, double max_gap, double rolling_resistance) {
  if (!(restitution >= 0 && restitution <= 1)) {
    std::ostringstream m;
    m << "contact restitution must lie in [0, 1], got " << restitution;
    throw Error(ExitCode::BadInput, m.str());
  }
  if (!(friction >= 0) || !std::isfinite(friction)) {
    std::ostringstream m;
    m << "contact friction must be >= 0, got " << friction;
    throw Error(ExitCode::BadInput, m.str());
  }
  if (!(rolling_resistance >= 0) || !std::isfinite(rolling_resistance)) {
    std::ostringstream m;
    m << "contact rolling_resistance must be >= 0, got " << rolling_resistance;
    throw Error(ExitCode::BadInput, m.str());
  }
  ContactParams k;
  k.restitution = restitution;
  k.friction = friction;
  k.rolling_resistance = rolling_resistance;
  const Vec3 h = shape.half_extents;
  switch (shape.type) {
    case ShapeType::Sphere:
    case ShapeType::Ellipsoid:
      k.support = true;
      for (int a = 0; a < 3; ++a) {
        k.semi_axes[a] = h[a];
        k.centre[a] = -com[a];  // analytic shapes are centred at the origin
      }
      break;
    case ShapeType::Box: {
      // the 8 corners, then the interior points of the 12 edges
      for (int c = 0; c < 8; ++c)
        add_point(&k, Vec3(c & 1 ? h.x() : -h.x(), c & 2 ? h.y() : -h.y(),
                           c & 4 ? h.z() : -h.z()) -
                          com);
      for (int axis = 0; axis < 3; ++axis) {
        const double len = 2 * h[axis];
        int inner = max_gap > 0 ? int(std::ceil(len / max_gap - 1e-9)) - 1 : 0;
        inner = std::clamp(inner, 0, kContactEdgePoints);
        const int b1 = (axis + 1) % 3, b2 = (axis + 2) % 3;
        for (int e = 0; e < 4; ++e) {
          // the edge's two corners: bit `axis` of the corner index clear and set
          const int c0 = ((e & 1) << b1) | ((e & 2) >> 1 << b2);
          for (int i = 1; i <= inner; ++i) {
            Vec3 p;
            p[axis] = -h[axis] + len * i / (inner + 1);
            p[b1] = e & 1 ? h[b1] : -h[b1];
            p[b2] = e & 2 ? h[b2] : -h[b2];
            add_point(&k, p - com, c0, c0 | (1 << axis));
          }
        }
      }
      break;
    }
    case ShapeType::Mesh: {
      const std::vector<Vec3>& v = shape.mesh->vertices;
      std::vector<int> ids = convex_hull(v).vertices;
      if (ids.empty())
        for (size_t i = 0; i < v.size(); ++i) ids.push_back(int(i));
      for (int i : ids) add_point(&k, v[size_t(i)] - com);
      break;
    }
  }
  return k;
}

ContactParams contact_params(const BodyType& type, double restitution, double friction,
                             double max_gap, double rolling_resistance) {
  return contact_params(type.shape, type.com, restitution, friction, max_gap,
                        rolling_resistance);
}

}  // namespace lrigid
