// The contact points of a body type (docs/contacts.md): what contact needs of it, built once per
// type -- the material (restitution, friction, rolling resistance) and the shape's points (the
// support point of a sphere or an ellipsoid, a box's corners and edge points, a mesh's convex
// hull) -- and the support point against a surface's normal. Everything here is in the BODY
// frame (axes of the shape, origin at the centre of mass). The solver on these points:
// contact/solver.h; the pass after each step that gathers them: contact/pass.h.
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

#include "body/shape.h"
#include "util/lane.h"
#include "util/types.h"

namespace lrigid {

struct BodyType;

// What contact needs of a body type, built once per type (contact_params).
struct ContactParams {
  double restitution = 0;  // e in [0, 1]: normal velocity after / before (Newton), -
  double friction = 0;     // mu >= 0: Coulomb friction coefficient, -
  // mu_r >= 0: rolling resistance coefficient: at a touching point r, the angular impulse
  // against the body's rotation (rolling and twisting) is at most mu_r |r| J_n
  // (contact_resolve, rolling_resistance_impulse), -
  double rolling_resistance = 0;
  // contact_resolve: a point approaching slower than this does not bounce (its target normal
  // velocity is 0, not -e v_n): no jitter of resting bodies under gravity, m/s
  double rest_speed = 0;
  // sphere and ellipsoid: the contact point is the support point of the surface against the
  // wall's normal (ellipsoid_support_point); semi-axes along the body axes and the shape's
  // centre minus the centre of mass, m
  bool support = false;
  double semi_axes[3] = {0, 0, 0};
  double centre[3] = {0, 0, 0};
  // box and mesh: fixed contact points relative to the centre of mass, body frame, 3 per
  // point, m (box: corners and edge points; mesh: its convex hull's vertices)
  std::vector<double> points;
  // box: for each point, the two corners (indices into points) of the edge it lies inside,
  // kNotOnEdge for the corners and for meshes' points. A point between two corners that touch
  // the same plane adds nothing to them: its normal velocity and depth are their average
  // (contact/touching.cpp gather leaves it out)
  static constexpr uint8_t kNotOnEdge = 255;
  std::vector<uint8_t> edge_ends;  // 2 per point
  // point p lies inside a box edge (between two corners)
  bool on_edge(size_t p) const {
    return 2 * p + 1 < edge_ends.size() && edge_ends[2 * p] != kNotOnEdge;
  }
  size_t count() const { return support ? 1 : points.size() / 3; }
};

// The contact points of a shape whose centre of mass is at `com` (shape coordinates, m).
// Box edges get evenly spaced points between the corners, at most max_gap (m) apart and at most
// kContactEdgePoints per edge, so that a solid's corner narrower than max_gap cannot pass
// between two points of a thin plate's edge; max_gap <= 0: corners only. Mesh: the vertices of
// its convex hull (Qhull); all vertices if Qhull finds no 3D hull (a flat mesh).
// Throws lrigid::Error (BadInput) on restitution outside [0, 1], negative friction or negative
// rolling resistance.
ContactParams contact_params(const Shape& shape, const Vec3& com, double restitution,
                             double friction, double max_gap, double rolling_resistance = 0);
ContactParams contact_params(const BodyType& type, double restitution, double friction,
                             double max_gap, double rolling_resistance = 0);
constexpr int kContactEdgePoints = 16;  // interior points per box edge at most

// The point of the ellipsoid (sphere) of k farthest along -n, relative to the centre of mass,
// body frame (n unit): c - A^2 n / |A n|, A = diag(semi-axes). The contact point of a support
// shape against a wall of normal n (pointing from the wall into the fluid).
template <typename T>
LRIGID_LANE void ellipsoid_support_point(const ContactParams& k, const T* n, T* r) {
  T a2n[3], s = T(0);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) {
    const T ax = T(k.semi_axes[a]);
    a2n[a] = ax * ax * n[a];
    s += a2n[a] * n[a];
  }
  const T inv = T(1) / std::sqrt(s);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) r[a] = T(k.centre[a]) - a2n[a] * inv;
}

}  // namespace lrigid
