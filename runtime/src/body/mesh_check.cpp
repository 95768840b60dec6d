#include "body/mesh_check.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <unordered_map>
#include <utility>
#include <vector>

#include "util/error.h"

namespace lrigid {

namespace {

MeshCheck fail(MeshDefect d, const std::string& message) { return MeshCheck{d, message}; }

std::string edge_name(int a, int b) {
  return "edge " + std::to_string(a) + "-" + std::to_string(b);
}

struct EdgeUse {
  int count = 0;
  int direction = 0;  // +1 for each use a->b with a < b, -1 for b->a
  int face = -1;      // first face that uses it
  int other = -1;     // second face
};

// Where segment p-q crosses the plane of triangle (a, b, c) strictly inside the triangle, with
// the endpoints strictly on either side of the plane (beyond `tol`); false when it does not.
// A segment that only touches the plane or the triangle's edges does not count, so faces that
// meet along an edge or at a vertex are not reported.
bool segment_crosses_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b,
                              const Vec3& c, double tol, Vec3* at) {
  const Vec3 n = (b - a).cross(c - a);
  const double nn = n.norm();
  if (!(nn > 0)) return false;
  const double dp = n.dot(p - a) / nn, dq = n.dot(q - a) / nn;
  if (!((dp > tol && dq < -tol) || (dp < -tol && dq > tol))) return false;
  const Vec3 x = p + (dp / (dp - dq)) * (q - p);
  // barycentric coordinates of x: each sub-triangle's area against the whole, signed along n
  const double u = n.dot((b - x).cross(c - x)) / (nn * nn);
  const double v = n.dot((c - x).cross(a - x)) / (nn * nn);
  const double w = 1.0 - u - v;
  constexpr double kInside = 1e-9;
  if (!(u > kInside && v > kInside && w > kInside)) return false;
  *at = x;
  return true;
}

int shared_vertices(const std::array<int, 3>& s, const std::array<int, 3>& t) {
  int n = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) n += s[i] == t[j];
  return n;
}

// The first pair of faces that cross, found by sweeping the faces' bounding boxes along the
// mesh's longest axis; false when none do. Faces sharing an edge meet only along it and are
// skipped; faces sharing one vertex are tested with the edges that do not hold it.
bool find_crossing(const TriangleMesh& mesh, int* f1, int* f2, Vec3* at) {
  const int nf = static_cast<int>(mesh.faces.size());
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  std::vector<Vec3> flo(nf), fhi(nf);
  for (int f = 0; f < nf; ++f) {
    flo[f] = fhi[f] = mesh.vertices[mesh.faces[f][0]];
    for (int k = 1; k < 3; ++k) {
      flo[f] = flo[f].cwiseMin(mesh.vertices[mesh.faces[f][k]]);
      fhi[f] = fhi[f].cwiseMax(mesh.vertices[mesh.faces[f][k]]);
    }
    lo = lo.cwiseMin(flo[f]);
    hi = hi.cwiseMax(fhi[f]);
  }
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  const double tol = 1e-12 * (hi - lo).norm();
  std::vector<int> order(nf);
  for (int f = 0; f < nf; ++f) order[f] = f;
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return flo[a][axis] < flo[b][axis]; });
  for (int i = 0; i < nf; ++i) {
    const int s = order[i];
    const auto& fs = mesh.faces[s];
    for (int j = i + 1; j < nf && flo[order[j]][axis] <= fhi[s][axis]; ++j) {
      const int t = order[j];
      if (((flo[t] - fhi[s]).array() > tol).any() || ((flo[s] - fhi[t]).array() > tol).any())
        continue;
      const auto& ft = mesh.faces[t];
      if (shared_vertices(fs, ft) >= 2) continue;
      const auto crosses = [&](const std::array<int, 3>& e, const std::array<int, 3>& tri) {
        for (int k = 0; k < 3; ++k)
          if (segment_crosses_triangle(mesh.vertices[e[k]], mesh.vertices[e[(k + 1) % 3]],
                                       mesh.vertices[tri[0]], mesh.vertices[tri[1]],
                                       mesh.vertices[tri[2]], tol, at))
            return true;
        return false;
      };
      if (crosses(fs, ft) || crosses(ft, fs)) {
        *f1 = std::min(s, t);
        *f2 = std::max(s, t);
        return true;
      }
    }
  }
  return false;
}

}  // namespace

MeshCheck check_mesh(const TriangleMesh& mesh) {
  const int nv = static_cast<int>(mesh.vertices.size());
  const int nf = static_cast<int>(mesh.faces.size());
  if (nf < 4)
    return fail(MeshDefect::Empty,
                "mesh has " + std::to_string(nf) + " faces; a closed surface needs at least 4");
  for (int v = 0; v < nv; ++v)
    if (!mesh.vertices[v].allFinite())
      return fail(MeshDefect::NonFinite,
                  "vertex " + std::to_string(v) + " has a non-finite coordinate");
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k)
      if (mesh.faces[f][k] < 0 || mesh.faces[f][k] >= nv)
        return fail(MeshDefect::BadIndex, "face " + std::to_string(f) + " refers to vertex " +
                                              std::to_string(mesh.faces[f][k]) + " but there are " +
                                              std::to_string(nv) + " vertices");

  // degenerate faces: repeated index, or area tiny against the longest edge (collinear vertices)
  for (int f = 0; f < nf; ++f) {
    const auto& t = mesh.faces[f];
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
      return fail(MeshDefect::Degenerate, "face " + std::to_string(f) + " repeats a vertex (" +
                                              std::to_string(t[0]) + ", " + std::to_string(t[1]) +
                                              ", " + std::to_string(t[2]) + ")");
    const Vec3& a = mesh.vertices[t[0]];
    const Vec3& b = mesh.vertices[t[1]];
    const Vec3& c = mesh.vertices[t[2]];
    const double emax2 =
        std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    const double twice_area = (b - a).cross(c - a).norm();
    if (!(emax2 > 0) || twice_area <= 1e-10 * emax2)
      return fail(MeshDefect::Degenerate, "face " + std::to_string(f) +
                                              " has zero area (coincident or collinear vertices)");
  }

  // edges: closed and manifold means each undirected edge is used exactly twice, once each way
  std::unordered_map<uint64_t, EdgeUse> edges;
  edges.reserve(3 * static_cast<size_t>(nf));
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.faces[f][k], b = mesh.faces[f][(k + 1) % 3];
      const uint64_t key =
          (static_cast<uint64_t>(std::min(a, b)) << 32) | static_cast<uint32_t>(std::max(a, b));
      EdgeUse& e = edges[key];
      if (e.count == 0)
        e.face = f;
      else if (e.count == 1)
        e.other = f;
      ++e.count;
      e.direction += a < b ? 1 : -1;
    }
  int boundary = 0, crowded = 0, flipped = 0;
  std::string first_boundary, first_crowded, first_flipped;
  for (const auto& [key, e] : edges) {
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
    if (e.count == 1) {
      if (boundary++ == 0) first_boundary = edge_name(a, b) + " of face " + std::to_string(e.face);
    } else if (e.count > 2) {
      if (crowded++ == 0)
        first_crowded = edge_name(a, b) + " is shared by " + std::to_string(e.count) + " faces";
    } else if (e.direction != 0) {
      if (flipped++ == 0)
        first_flipped = "faces " + std::to_string(e.face) + " and " + std::to_string(e.other) +
                        " (" + edge_name(a, b) + ")";
    }
  }
  if (crowded > 0)
    return fail(MeshDefect::NonManifold, "mesh is non-manifold: " + std::to_string(crowded) +
                                             " edges with more than two faces, e.g. " +
                                             first_crowded);
  if (boundary > 0)
    return fail(MeshDefect::Open, "mesh is open: " + std::to_string(boundary) +
                                      " boundary edges (holes), e.g. " + first_boundary);
  if (flipped > 0)
    return fail(MeshDefect::Inconsistent,
                "mesh orientation is inconsistent: " + std::to_string(flipped) +
                    " edges between faces of opposite orientation, e.g. " + first_flipped);

  // vertices: the faces around each vertex must form one fan (no "bow-tie" vertices).
  // with manifold edges the link of v is a union of cycles a -> b over its faces (v, a, b).
  std::vector<std::vector<std::pair<int, int>>> link(nv);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k)
      link[mesh.faces[f][k]].push_back({mesh.faces[f][(k + 1) % 3], mesh.faces[f][(k + 2) % 3]});
  for (int v = 0; v < nv; ++v) {
    const auto& l = link[v];
    if (l.empty()) continue;  // unreferenced vertex: harmless
    size_t steps = 0;
    int cur = l[0].first;
    do {
      auto it = std::find_if(l.begin(), l.end(), [cur](const auto& p) { return p.first == cur; });
      if (it == l.end()) break;
      cur = it->second;
      ++steps;
    } while (cur != l[0].first && steps <= l.size());
    if (steps != l.size())
      return fail(MeshDefect::NonManifold, "mesh is non-manifold at vertex " + std::to_string(v) +
                                               ": its " + std::to_string(l.size()) +
                                               " faces form more than one fan");
  }

  // self-intersection: two faces crossing make the inside ambiguous; the volume and the
  // boundary elements' solution are then meaningless
  int f1 = -1, f2 = -1;
  Vec3 at;
  if (find_crossing(mesh, &f1, &f2, &at)) {
    std::ostringstream s;
    s.precision(6);
    s << "mesh intersects itself: faces " << f1 << " and " << f2 << " cross near (" << at.x()
      << ", " << at.y() << ", " << at.z() << "); a body's surface must not pass through itself";
    return fail(MeshDefect::SelfIntersecting, s.str());
  }

  // orientation: outward faces enclose a positive volume (sum of signed tetrahedra)
  const Vec3 o = mesh.vertices[mesh.faces[0][0]];
  double six_volume = 0;
  double extent = 0;
  for (const auto& t : mesh.faces) {
    const Vec3 a = mesh.vertices[t[0]] - o, b = mesh.vertices[t[1]] - o,
               c = mesh.vertices[t[2]] - o;
    six_volume += a.dot(b.cross(c));
    extent = std::max({extent, a.norm(), b.norm(), c.norm()});
  }
  const double volume = six_volume / 6.0;
  if (!(volume > 1e-12 * extent * extent * extent)) {
    std::ostringstream s;
    s.precision(6);
    if (volume < 0)
      s << "mesh is inverted: its faces point inwards (signed volume " << volume
        << " m^3); reverse the vertex order of every face";
    else
      s << "mesh encloses no volume (signed volume " << volume << " m^3)";
    return fail(MeshDefect::Inverted, s.str());
  }
  return {};
}

void check_closed_mesh(const TriangleMesh& mesh, const std::string& source) {
  const MeshCheck c = check_mesh(mesh);
  if (!c.ok()) throw Error(ExitCode::BadInput, where(source, "", c.message));
}

}  // namespace lrigid
