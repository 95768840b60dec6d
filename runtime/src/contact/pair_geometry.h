// The narrow phase of contacts between bodies: the convex shape of a body type (PairShape), its
// bounding box at a pose, and the contact manifold of two shapes at their poses (collide).
#pragma once
#include <memory>

#include "body/shape.h"
#include "util/types.h"

namespace lrigid {

// The convex shape of a body type for contacts between bodies, in the BODY frame (origin at the
// centre of mass, axes of the shape), built once per type.
struct PairShape {
  enum class Kind { Sphere, Ellipsoid, Polytope } kind = Kind::Sphere;
  Vec3 semi_axes = Vec3::Zero();  // sphere, ellipsoid
  Vec3 centre = Vec3::Zero();     // the shape's centre minus the centre of mass
  double radius = 0;              // bounding sphere about the centre of mass, m
};
std::shared_ptr<const PairShape> pair_shape(const Shape& shape, const Vec3& com);

struct PairPose {
  Vec3 x;  // world position of the centre of mass, m
  Mat3 R;  // rotation body -> world
};
void pair_aabb(const PairShape& s, const PairPose& p, Vec3* lo, Vec3* hi);

constexpr int kPairMaxPoints = 8;
// p: world point midway between the two surfaces; n: world unit normal from B towards A; depth:
// >= 0 penetration (m), < 0 apart by -depth (a speculative point)
struct PairPoint {
  Vec3 p;
  Vec3 n;
  double depth;
};
struct PairManifold {
  PairPoint pts[kPairMaxPoints];
  int count = 0;
};
int collide(const PairShape& a, const PairPose& pa, const PairShape& b, const PairPose& pb,
            double margin, PairManifold* out);

}  // namespace lrigid
