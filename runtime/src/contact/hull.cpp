#include "contact/hull.h"

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace lrigid {

namespace {

// the facet's vertices ordered counter-clockwise about its outward normal
std::vector<int> facet_loop(const std::vector<Vec3>& pts, std::vector<int> ids, const Vec3& n) {
  Vec3 c = Vec3::Zero();
  for (int i : ids) c += pts[size_t(i)];
  c /= double(ids.size());
  // an in-plane basis (u, v) with u x v = n
  const Vec3 u = (pts[size_t(ids[0])] - c - n * n.dot(pts[size_t(ids[0])] - c)).normalized();
  const Vec3 v = n.cross(u);
  std::vector<std::pair<double, int>> by_angle;
  for (int i : ids) {
    const Vec3 d = pts[size_t(i)] - c;
    by_angle.emplace_back(std::atan2(d.dot(v), d.dot(u)), i);
  }
  std::sort(by_angle.begin(), by_angle.end());
  for (size_t k = 0; k < ids.size(); ++k) ids[k] = by_angle[k].second;
  return ids;
}

}  // namespace

ConvexHull convex_hull(const std::vector<Vec3>& pts) {
  ConvexHull hull;
  if (pts.size() < 4) return hull;
  std::vector<coordT> coords(3 * pts.size());
  for (size_t i = 0; i < pts.size(); ++i)
    for (int a = 0; a < 3; ++a) coords[3 * i + a] = pts[i][a];
  qhT qh_storage;
  qhT* qh = &qh_storage;
  // Qhull's messages go to a memory buffer, not to the user's terminal
  char* buffer = nullptr;
  size_t size = 0;
  FILE* err = open_memstream(&buffer, &size);
  qh_zero(qh, err);
  // merged facets (Qhull's default for 3D): a box's face is one quadrilateral, not two triangles
  char flags[] = "qhull";
  const int code = qh_new_qhull(qh, 3, int(pts.size()), coords.data(), False, flags, nullptr, err);
  if (code == 0) {
    vertexT* vertex;
    FORALLvertices hull.vertices.push_back(qh_pointid(qh, vertex->point));
    facetT* facet;
    FORALLfacets {
      ConvexHull::Facet f;
      f.normal = Vec3(facet->normal[0], facet->normal[1], facet->normal[2]);
      f.offset = -facet->offset;
      std::vector<int> ids;
      vertexT** vertexp;
      FOREACHvertex_(facet->vertices) ids.push_back(qh_pointid(qh, vertex->point));
      f.loop = facet_loop(pts, std::move(ids), f.normal);
      hull.facets.push_back(std::move(f));
    }
  }
  qh_freeqhull(qh, !qh_ALL);
  int curlong = 0, totlong = 0;
  qh_memfreeshort(qh, &curlong, &totlong);
  if (err) std::fclose(err);
  std::free(buffer);
  std::sort(hull.vertices.begin(), hull.vertices.end());
  return hull;
}

}  // namespace lrigid
