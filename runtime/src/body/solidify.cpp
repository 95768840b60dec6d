#include "body/solidify.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>
#include <vector>

#include "util/error.h"

namespace lrigid {

namespace {

using Edge = std::pair<int, int>;  // directed: the order of a face's winding

// each directed edge of the faces, with the face it belongs to
std::map<Edge, std::vector<int>> directed_edges(const TriangleMesh& m) {
  std::map<Edge, std::vector<int>> e;
  for (int f = 0; f < static_cast<int>(m.faces.size()); ++f)
    for (int k = 0; k < 3; ++k) e[{m.faces[f][k], m.faces[f][(k + 1) % 3]}].push_back(f);
  return e;
}

std::string edge_name(const TriangleMesh& m, const Edge& e) {
  const Vec3& a = m.vertices[e.first];
  const Vec3& b = m.vertices[e.second];
  char buf[160];
  std::snprintf(buf, sizeof buf, "the edge from vertex %d (%.4g %.4g %.4g) to %d (%.4g %.4g %.4g)",
                e.first + 1, a.x(), a.y(), a.z(), e.second + 1, b.x(), b.y(), b.z());
  return buf;
}

[[noreturn]] void refuse(const std::string& source, const std::string& what) {
  throw Error(ExitCode::BadInput, source + ": surface " + what);
}

}  // namespace

int boundary_edge_count(const TriangleMesh& mesh) {
  std::map<Edge, int> undirected;
  for (const auto& f : mesh.faces)
    for (int k = 0; k < 3; ++k) {
      const int a = f[k], b = f[(k + 1) % 3];
      ++undirected[{std::min(a, b), std::max(a, b)}];
    }
  int n = 0;
  for (const auto& [e, count] : undirected) n += count == 1;
  return n;
}

TriangleMesh solidify_surface(const TriangleMesh& s, double thickness,
                              const std::string& source) {
  if (!(thickness > 0 && std::isfinite(thickness)))
    throw Error(ExitCode::BadInput, source + ": thickness must be > 0 m");
  const int nv = static_cast<int>(s.vertices.size());
  for (const auto& f : s.faces)
    for (int k = 0; k < 3; ++k)
      if (f[k] < 0 || f[k] >= nv) refuse(source, "has a face with a vertex that does not exist");

  // the edges: each direction of an edge in one face at most (two faces passing it the same way
  // are flipped against each other, or a third face joins the edge)
  const auto edges = directed_edges(s);
  std::vector<Edge> boundary;
  for (const auto& [e, faces] : edges) {
    if (faces.size() > 1)
      refuse(source, "is not one consistently oriented sheet: " + edge_name(s, e) +
                         " is in " + std::to_string(faces.size()) +
                         " faces the same way round (faces " + std::to_string(faces[0] + 1) +
                         " and " + std::to_string(faces[1] + 1) + ")");
    // with each direction in one face at most, an edge has two faces at most
    if (edges.find({e.second, e.first}) == edges.end()) boundary.push_back(e);
  }
  if (boundary.empty())
    refuse(source, "is closed: \"thickness\" is for an open, single-sided surface (a closed mesh "
                   "is a solid of its own; remove the key)");

  // two sheets touching at one vertex (a bow tie): the vertex is the start of two boundary edges
  std::vector<int> starts(nv, 0);
  for (const Edge& e : boundary)
    if (++starts[e.first] > 1) {
      const Vec3& p = s.vertices[e.first];
      char buf[96];
      std::snprintf(buf, sizeof buf, "vertex %d (%.4g %.4g %.4g)", e.first + 1, p.x(), p.y(),
                    p.z());
      refuse(source, std::string("has two sheets meeting at ") + buf +
                         ": split the vertex or the mesh into separate bodies");
    }

  // vertex normals: the faces' unit normals weighted by their angle at the vertex
  std::vector<Vec3> normal(nv, Vec3::Zero());
  for (const auto& f : s.faces) {
    const Vec3 n = (s.vertices[f[1]] - s.vertices[f[0]]).cross(s.vertices[f[2]] - s.vertices[f[0]]);
    const double len = n.norm();
    if (!(len > 0)) continue;  // a degenerate face adds nothing (the closed check refuses it)
    for (int k = 0; k < 3; ++k) {
      const Vec3 a = s.vertices[f[(k + 1) % 3]] - s.vertices[f[k]];
      const Vec3 b = s.vertices[f[(k + 2) % 3]] - s.vertices[f[k]];
      const double angle = std::atan2(a.cross(b).norm(), a.dot(b));
      normal[f[k]] += angle * n / len;
    }
  }
  std::vector<bool> used(nv, false);
  for (const auto& f : s.faces)
    for (int k = 0; k < 3; ++k) used[f[k]] = true;
  for (int v = 0; v < nv; ++v) {
    if (!used[v]) continue;
    const double len = normal[v].norm();
    if (!(len > 1e-9)) {
      const Vec3& p = s.vertices[v];
      char buf[96];
      std::snprintf(buf, sizeof buf, "vertex %d (%.4g %.4g %.4g)", v + 1, p.x(), p.y(), p.z());
      refuse(source, std::string("folds back on itself at ") + buf +
                         ": its faces' normals cancel, so it has no side to thicken");
    }
    normal[v] /= len;
  }

  TriangleMesh out;
  out.vertices.resize(2 * static_cast<size_t>(nv));
  const double half = 0.5 * thickness;
  for (int v = 0; v < nv; ++v) {
    out.vertices[v] = s.vertices[v] + half * normal[v];
    out.vertices[nv + v] = s.vertices[v] - half * normal[v];
  }
  out.faces.reserve(2 * s.faces.size() + 2 * boundary.size());
  for (const auto& f : s.faces) out.faces.push_back(f);  // + side, as wound
  for (const auto& f : s.faces) out.faces.push_back({nv + f[0], nv + f[2], nv + f[1]});
  // the wall along a boundary edge a -> b of the + side: each edge of the closed body is then
  // passed once in each direction (+ side a -> b, wall b -> a; - side b' -> a', wall a' -> b')
  for (const Edge& e : boundary) {
    const int a = e.first, b = e.second;
    out.faces.push_back({b, a, nv + a});
    out.faces.push_back({b, nv + a, nv + b});
  }
  if (s.has_uv()) {
    // texture coordinates: both sides as the surface's (a texture seen from either side), the
    // walls those of the edge's ends
    std::vector<Vec2> at(static_cast<size_t>(nv), Vec2::Zero());
    for (size_t i = 0; i < s.faces.size(); ++i)
      for (int k = 0; k < 3; ++k) at[static_cast<size_t>(s.faces[i][k])] = s.uv[i][k];
    out.uv = s.uv;
    for (const auto& t : s.uv) out.uv.push_back({t[0], t[2], t[1]});
    for (const Edge& e : boundary) {
      const Vec2 &ta = at[static_cast<size_t>(e.first)], &tb = at[static_cast<size_t>(e.second)];
      out.uv.push_back({tb, ta, ta});
      out.uv.push_back({tb, ta, tb});
    }
  }
  return out;  // a vertex no face uses stays unused, as in the surface
}

}  // namespace lrigid
