// The convex hull of a point set (Qhull, Debian libqhull-dev): its vertices for a mesh's contact
// points with the walls (contact/points.cpp) and its faces for the contacts between bodies
// (contact/pair_geometry.cpp).
#pragma once
#include <vector>

#include "util/types.h"

namespace lrigid {

struct ConvexHull {
  // one face of the hull: coplanar triangles merged into one polygon
  struct Facet {
    Vec3 normal;            // outward unit normal
    double offset = 0;      // normal . x = offset on the face's plane, m
    std::vector<int> loop;  // vertex indices, counter-clockwise seen from outside
  };
  std::vector<int> vertices;  // indices into the points, ascending
  std::vector<Facet> facets;
  bool empty() const { return vertices.empty(); }
};

// The convex hull of `pts`; empty when Qhull finds no 3D hull (fewer than 4 points, or all in a
// plane).
ConvexHull convex_hull(const std::vector<Vec3>& pts);

}  // namespace lrigid
