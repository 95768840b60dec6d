#include "contact/pair_geometry.h"

#include <cmath>

namespace lrigid {

// placeholder until the narrow phase lands: every shape is its bounding sphere
std::shared_ptr<const PairShape> pair_shape(const Shape& shape, const Vec3& com) {
  auto s = std::make_shared<PairShape>();
  s->kind = PairShape::Kind::Sphere;
  s->semi_axes = shape.half_extents;
  s->centre = -com;
  s->radius = shape.half_extents.maxCoeff() + com.norm();
  return s;
}

void pair_aabb(const PairShape& s, const PairPose& p, Vec3* lo, Vec3* hi) {
  *lo = p.x - Vec3::Constant(s.radius);
  *hi = p.x + Vec3::Constant(s.radius);
}

int collide(const PairShape& a, const PairPose& pa, const PairShape& b, const PairPose& pb,
            double margin, PairManifold* out) {
  out->count = 0;
  const Vec3 ca = pa.x + pa.R * a.centre, cb = pb.x + pb.R * b.centre;
  const double ra = a.semi_axes.maxCoeff(), rb = b.semi_axes.maxCoeff();
  const Vec3 d = ca - cb;
  const double dist = d.norm();
  const double gap = dist - ra - rb;
  if (gap >= margin) return 0;
  const Vec3 n = dist > 0 ? Vec3(d / dist) : Vec3::UnitZ();
  PairPoint& q = out->pts[0];
  q.n = n;
  q.depth = -gap;
  q.p = cb + n * (rb - 0.5 * q.depth);
  out->count = 1;
  return 1;
}

}  // namespace lrigid
