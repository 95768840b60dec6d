#include "body/tessellate.h"

#include <cmath>
#include <cstdint>
#include <map>
#include <tuple>
#include <unordered_map>

#include "util/error.h"

namespace lrigid {

namespace {

// number of 4-way splits k so that base * 4^k is nearest to target in ratio
int splits_for(int base, int target, int max_splits) {
  int k = 0;
  double best = std::abs(std::log(static_cast<double>(base) / target));
  for (int j = 1; j <= max_splits; ++j) {
    const double err = std::abs(std::log(base * std::pow(4.0, j) / target));
    if (err < best) {
      best = err;
      k = j;
    }
  }
  return k;
}

// regular icosahedron with unit circumradius: vertices (0, +-1, +-phi) and cyclic permutations;
// faces are the vertex triples at mutual distance 2 (before scaling), oriented outwards
TriangleMesh icosahedron() {
  const double p = 0.5 * (1.0 + std::sqrt(5.0));
  TriangleMesh m;
  for (double s1 : {-1.0, 1.0})
    for (double s2 : {-1.0, 1.0}) {
      m.vertices.emplace_back(0, s1, s2 * p);
      m.vertices.emplace_back(s1, s2 * p, 0);
      m.vertices.emplace_back(s2 * p, 0, s1);
    }
  const auto adjacent = [&](int i, int j) {
    return std::abs((m.vertices[i] - m.vertices[j]).norm() - 2.0) < 1e-9;
  };
  for (int i = 0; i < 12; ++i)
    for (int j = i + 1; j < 12; ++j)
      for (int k = j + 1; k < 12; ++k)
        if (adjacent(i, j) && adjacent(j, k) && adjacent(k, i)) {
          const Vec3& a = m.vertices[i];
          const Vec3& b = m.vertices[j];
          const Vec3& c = m.vertices[k];
          if ((b - a).cross(c - a).dot(a + b + c) > 0)
            m.faces.push_back({i, j, k});
          else
            m.faces.push_back({i, k, j});
        }
  for (Vec3& v : m.vertices) v.normalize();
  return m;
}

TriangleMesh ellipsoid_mesh(const Vec3& semi_axes, int target) {
  TriangleMesh m = icosahedron();
  const int k = splits_for(20, target, 7);
  for (int i = 0; i < k; ++i) {
    m = subdivide(m);
    for (Vec3& v : m.vertices) v.normalize();
  }
  for (Vec3& v : m.vertices) v = v.cwiseProduct(semi_axes);
  return m;
}

// node i of n along an edge, in [0, 1], cosine spacing: cells shrink towards the box edges,
// where the potential flow is singular (cube: error at ~1200 panels 1.3 % instead of 2.1 %
// with uniform cells); symmetric about 1/2
double graded(int i, int n) { return 0.5 * (1.0 - std::cos(M_PI * i / n)); }

TriangleMesh box_mesh(const Vec3& h, int target) {
  const Vec3 l = 2.0 * h;
  // 4 triangles per cell: faces ~ 8 (lx ly + ly lz + lz lx) / cell^2
  const double half_area = l.x() * l.y() + l.y() * l.z() + l.z() * l.x();
  const double cell = std::sqrt(8.0 * half_area / target);
  int n[3];
  for (int a = 0; a < 3; ++a) n[a] = std::max(1, static_cast<int>(std::lround(l[a] / cell)));

  TriangleMesh m;
  // vertices keyed by doubled lattice coordinates (cell centres have odd coordinates)
  std::map<std::tuple<int, int, int>, int> index;
  const auto vertex = [&](int i2, int j2, int k2) {
    const auto key = std::make_tuple(i2, j2, k2);
    auto it = index.find(key);
    if (it != index.end()) return it->second;
    const int id = static_cast<int>(m.vertices.size());
    const int c[3] = {i2, j2, k2};
    Vec3 p;
    for (int a = 0; a < 3; ++a) {
      // cell centres (odd doubled index) halfway between their nodes
      const double t = c[a] % 2 == 0 ? graded(c[a] / 2, n[a])
                                     : 0.5 * (graded(c[a] / 2, n[a]) + graded(c[a] / 2 + 1, n[a]));
      p[a] = -h[a] + l[a] * t;
    }
    m.vertices.push_back(p);
    index.emplace(key, id);
    return id;
  };
  // (normal axis, sign, u axis, v axis) with u x v along the outward normal
  const int faces[6][4] = {{2, 1, 0, 1},  {2, -1, 1, 0}, {0, 1, 1, 2},
                           {0, -1, 2, 1}, {1, 1, 2, 0},  {1, -1, 0, 2}};
  for (const auto& f : faces) {
    const int a = f[0], u = f[2], v = f[3];
    const int fixed = f[1] > 0 ? 2 * n[a] : 0;
    const auto at = [&](int iu2, int iv2) {
      int c[3];
      c[a] = fixed;
      c[u] = iu2;
      c[v] = iv2;
      return vertex(c[0], c[1], c[2]);
    };
    for (int i = 0; i < n[u]; ++i)
      for (int j = 0; j < n[v]; ++j) {
        const int p00 = at(2 * i, 2 * j), p10 = at(2 * i + 2, 2 * j);
        const int p11 = at(2 * i + 2, 2 * j + 2), p01 = at(2 * i, 2 * j + 2);
        const int c = at(2 * i + 1, 2 * j + 1);
        m.faces.push_back({p00, p10, c});
        m.faces.push_back({p10, p11, c});
        m.faces.push_back({p11, p01, c});
        m.faces.push_back({p01, p00, c});
      }
  }
  return m;
}

}  // namespace

TriangleMesh subdivide(const TriangleMesh& mesh) {
  TriangleMesh out;
  out.vertices = mesh.vertices;
  out.faces.reserve(4 * mesh.faces.size());
  std::unordered_map<uint64_t, int> mid;
  mid.reserve(3 * mesh.faces.size() / 2);
  const auto midpoint = [&](int a, int b) {
    const uint64_t key =
        (static_cast<uint64_t>(std::min(a, b)) << 32) | static_cast<uint32_t>(std::max(a, b));
    auto it = mid.find(key);
    if (it != mid.end()) return it->second;
    const int id = static_cast<int>(out.vertices.size());
    out.vertices.push_back(0.5 * (mesh.vertices[a] + mesh.vertices[b]));
    mid.emplace(key, id);
    return id;
  };
  const bool uv = mesh.has_uv();
  for (size_t i = 0; i < mesh.faces.size(); ++i) {
    const auto& f = mesh.faces[i];
    const int ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
    out.faces.push_back({f[0], ab, ca});
    out.faces.push_back({ab, f[1], bc});
    out.faces.push_back({ca, bc, f[2]});
    out.faces.push_back({ab, bc, ca});
    if (uv) {  // the texture coordinates split the same way
      const auto& t = mesh.uv[i];
      const Vec2 tab = 0.5 * (t[0] + t[1]), tbc = 0.5 * (t[1] + t[2]), tca = 0.5 * (t[2] + t[0]);
      out.uv.push_back({t[0], tab, tca});
      out.uv.push_back({tab, t[1], tbc});
      out.uv.push_back({tca, tbc, t[2]});
      out.uv.push_back({tab, tbc, tca});
    }
  }
  return out;
}

TriangleMesh tessellate(const Shape& shape, int target_faces) {
  if (target_faces < 1)
    throw Error(ExitCode::Usage,
                "tessellate: target face count must be >= 1, got " + std::to_string(target_faces));
  switch (shape.type) {
    case ShapeType::Sphere:
    case ShapeType::Ellipsoid:
      return ellipsoid_mesh(shape.half_extents, target_faces);
    case ShapeType::Box:
      return box_mesh(shape.half_extents, target_faces);
    case ShapeType::Mesh: {
      if (!shape.mesh)
        throw Error(ExitCode::BadInput, where(shape.source, "", "mesh shape without a mesh"));
      TriangleMesh m = *shape.mesh;
      const int k = splits_for(static_cast<int>(m.faces.size()), target_faces, 6);
      for (int i = 0; i < k; ++i) m = subdivide(m);
      return m;
    }
  }
  return {};
}

}  // namespace lrigid
