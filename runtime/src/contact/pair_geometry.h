// The narrow phase of the contacts between bodies (docs/contacts.md, "The narrow phase between bodies"): the convex
// shape of a body type, built once per type, and the contact manifold of two such shapes at two
// poses -- up to kPairMaxPoints points, each with a world point, a normal from B towards A and a
// depth. Sphere-sphere and sphere-polytope are exact; pairs with an ellipsoid take one point from
// libccd's GJK/EPA; polytope pairs (boxes, thin plates, mesh hulls) the separating-axis test with
// the reference face clipped against the incident face.
#pragma once
#include <memory>
#include <vector>

#include "body/shape.h"
#include "util/types.h"

namespace lrigid {

// The convex shape of a body type for contacts between bodies, in the BODY frame (origin at the
// centre of mass, axes of the shape), built once per type (pair_shape).
struct PairShape {
  enum class Kind { Sphere, Ellipsoid, Polytope } kind = Kind::Sphere;
  // sphere, ellipsoid: semi-axes; box: half extents, m
  Vec3 semi_axes = Vec3::Zero();
  // sphere, ellipsoid, box: the shape's centre minus the centre of mass, m
  Vec3 centre = Vec3::Zero();
  // polytope: a box (the semi-axes and centre above describe it) or a mesh's convex hull
  bool box = false;

  // polytope: one face, a convex polygon with its vertices in loops[first, first + count)
  // counter-clockwise seen from outside
  struct Face {
    Vec3 n;      // outward unit normal
    double d;    // n . x = d on the face's plane, m
    int first, count;
  };
  // polytope: one edge, from v0 to v1 counter-clockwise in face f0, the other way in face f1
  struct Edge {
    int v0, v1, f0, f1;
  };
  std::vector<Vec3> vertices;  // polytope: relative to the centre of mass, m
  std::vector<int> loops;      // polytope: the faces' vertex indices
  std::vector<Face> faces;
  std::vector<Edge> edges;
  Vec3 interior = Vec3::Zero();  // polytope: the mean of its vertices (inside), m
  // a mesh whose vertices span no volume (flat): thickened by this much along its plane's
  // normal (kPairFlatThickness times its size), m; 0 otherwise
  double flat_thickness = 0;

  double radius = 0;  // bounding sphere radius about the centre of mass, m
};

// A flat mesh (no 3D hull) becomes a plate this thick relative to its largest extent.
constexpr double kPairFlatThickness = 1e-5;

// The pair shape of `shape` whose centre of mass is at `com` (shape coordinates, m). A mesh uses
// its convex hull (contact/hull.h); a flat one is thickened by kPairFlatThickness times its
// largest extent. Throws lrigid::Error (BadInput) on a mesh with fewer than three vertices not
// on a line.
std::shared_ptr<const PairShape> pair_shape(const Shape& shape, const Vec3& com);

// A body's pose: the world position of its centre of mass and its rotation body -> world.
struct PairPose {
  Vec3 x;
  Mat3 R;
};

// The world-frame axis-aligned bounding box of the shape at the pose (tight for every kind).
void pair_aabb(const PairShape& s, const PairPose& p, Vec3* lo, Vec3* hi);

constexpr int kPairMaxPoints = 8;

// One contact point. p: the world point midway between the two surfaces; n: the world unit
// normal from B towards A (the direction A moves to separate); depth: >= 0 penetration, m;
// < 0: the surfaces are apart by -depth there (a speculative point, -depth < margin).
struct PairPoint {
  Vec3 p;
  Vec3 n;
  double depth;
};
struct PairManifold {
  PairPoint pts[kPairMaxPoints];
  int count = 0;
};

// The contact manifold of A and B; points apart by less than `margin` (m, >= 0) are included
// with negative depth. Returns out->count (0: apart by at least margin). Deterministic, and
// symmetric: collide(B, A) gives the same points with the normals negated.
int collide(const PairShape& a, const PairPose& pa, const PairShape& b, const PairPose& pb,
            double margin, PairManifold* out);

// The overlap of A and B along the unit normal n (from B towards A): how far A must move along n
// to separate, m (negative: the gap along n). The depth is its least value over all n, so it
// bounds the depth of collide's deepest point from above along any n.
double pair_overlap(const PairShape& a, const PairPose& pa, const PairShape& b, const PairPose& pb,
                    const Vec3& n);

}  // namespace lrigid
