#include "io/mesh_io.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>
#include <vector>

#include "io/atomic_file.h"
#include "util/error.h"

namespace lrigid {

namespace {

[[noreturn]] void bad(const std::string& path, const std::string& message, int line = 0) {
  throw Error(ExitCode::BadInput,
              where(path, line > 0 ? "line " + std::to_string(line) : "", message));
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// strict number parse: the whole token must be a finite number
bool parse_double(const std::string& token, double& out) {
  if (token.empty()) return false;
  char* end = nullptr;
  out = std::strtod(token.c_str(), &end);
  return end == token.c_str() + token.size() && std::isfinite(out);
}

// merges bit-identical vertices (STL stores each triangle's corners separately)
class VertexWelder {
 public:
  explicit VertexWelder(TriangleMesh& mesh) : mesh_(mesh) {}
  int add(const Vec3& p) {
    const std::array<double, 3> key = {p.x(), p.y(), p.z()};
    auto it = index_.find(key);
    if (it != index_.end()) return it->second;
    const int id = static_cast<int>(mesh_.vertices.size());
    mesh_.vertices.push_back(p);
    index_.emplace(key, id);
    return id;
  }

 private:
  TriangleMesh& mesh_;
  std::map<std::array<double, 3>, int> index_;
};

// a 1-based or negative OBJ index among `count` records so far, made 0-based into *out (may
// be out of range); false if it is not an index
bool obj_index(const std::string& text, long count, long* out) {
  char* end = nullptr;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || end != text.c_str() + text.size() || v == 0) return false;
  *out = v > 0 ? v - 1 : count + v;
  return true;
}

TriangleMesh read_obj(const std::string& path) {
  std::ifstream in(path);
  if (!in) bad(path, "cannot open for reading");
  TriangleMesh m;
  std::vector<Vec2> vt;             // the "vt" records
  std::vector<std::array<int, 3>> face_vt;  // each face's corners' "vt" index, -1: none
  std::string line;
  int lineno = 0;
  long max_index = -1;  // largest 0-based vertex index used, and where
  int max_index_line = 0;
  std::string max_index_text;
  long max_vt = -1;     // the same for the "vt" indices
  int max_vt_line = 0;
  while (std::getline(in, line)) {
    ++lineno;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream s(line);
    std::string tag;
    if (!(s >> tag) || tag[0] == '#') continue;
    if (tag == "v") {
      Vec3 p;
      std::string tok;
      for (int k = 0; k < 3; ++k) {
        if (!(s >> tok)) bad(path, "vertex needs 3 coordinates", lineno);
        if (!parse_double(tok, p[k]))
          bad(path, "vertex coordinate '" + tok + "' is not a finite number", lineno);
      }
      m.vertices.push_back(p);
    } else if (tag == "vt") {
      Vec2 t;
      std::string tok;
      for (int k = 0; k < 2; ++k) {
        if (!(s >> tok)) bad(path, "texture coordinate (vt) needs u and v", lineno);
        if (!parse_double(tok, t[k]))
          bad(path, "texture coordinate '" + tok + "' is not a finite number", lineno);
      }
      vt.push_back(t);
    } else if (tag == "f") {
      std::vector<int> poly, poly_vt;
      std::string tok;
      while (s >> tok) {
        const size_t slash = tok.find('/');
        const std::string idx = tok.substr(0, slash);
        // negative: relative to the vertices so far; positive: may refer forward, checked at
        // the end of the file
        long zero_based = 0;
        if (!obj_index(idx, static_cast<long>(m.vertices.size()), &zero_based))
          bad(path, "face index '" + tok + "' is not a vertex number (1-based or negative)",
              lineno);
        if (zero_based < 0 || zero_based > std::numeric_limits<int>::max())
          bad(path, "face index " + idx + " is out of range", lineno);
        if (zero_based >= max_index) {
          max_index = zero_based;
          max_index_line = lineno;
          max_index_text = tok;
        }
        poly.push_back(static_cast<int>(zero_based));
        // "i/t" or "i/t/n": the corner's texture coordinate
        const std::string t =
            slash == std::string::npos ? "" : tok.substr(slash + 1, tok.find('/', slash + 1) - slash - 1);
        long ti = -1;
        if (!t.empty()) {
          if (!obj_index(t, static_cast<long>(vt.size()), &ti) || ti < 0 || ti > std::numeric_limits<int>::max())
            bad(path, "texture index '" + t + "' in '" + tok + "' is out of range", lineno);
          if (ti >= max_vt) max_vt = ti, max_vt_line = lineno;
        }
        poly_vt.push_back(static_cast<int>(ti));
      }
      if (poly.size() < 3) bad(path, "face needs at least 3 vertices", lineno);
      for (size_t k = 1; k + 1 < poly.size(); ++k) {
        m.faces.push_back({poly[0], poly[k], poly[k + 1]});
        face_vt.push_back({poly_vt[0], poly_vt[k], poly_vt[k + 1]});
      }
    }
    // vn, o, g, s, usemtl, mtllib, l, ...: not needed
  }
  if (m.faces.empty()) bad(path, "no faces ('f' lines) found");
  if (max_index >= static_cast<long>(m.vertices.size()))
    bad(path,
        "face index " + max_index_text + " refers to vertex " + std::to_string(max_index + 1) +
            " but the file has " + std::to_string(m.vertices.size()) + " vertices",
        max_index_line);
  if (max_vt >= static_cast<long>(vt.size()))
    bad(path,
        "texture index " + std::to_string(max_vt + 1) + " but the file has " +
            std::to_string(vt.size()) + " texture coordinates (vt)",
        max_vt_line);
  // texture coordinates when every corner has one (a file that leaves some out has none)
  const bool all = std::all_of(face_vt.begin(), face_vt.end(), [](const std::array<int, 3>& f) {
    return f[0] >= 0 && f[1] >= 0 && f[2] >= 0;
  });
  if (all) {
    m.uv.reserve(face_vt.size());
    for (const auto& f : face_vt) m.uv.push_back({vt[f[0]], vt[f[1]], vt[f[2]]});
  }
  return m;
}

TriangleMesh read_stl_binary(const std::string& path, const std::vector<char>& data) {
  uint32_t count = 0;
  std::memcpy(&count, data.data() + 80, 4);  // little-endian on all supported hosts
  TriangleMesh m;
  VertexWelder weld(m);
  for (uint32_t t = 0; t < count; ++t) {
    const char* rec = data.data() + 84 + 50 * static_cast<size_t>(t);
    std::array<int, 3> f;
    for (int k = 0; k < 3; ++k) {
      float xyz[3];
      std::memcpy(xyz, rec + 12 + 12 * k, 12);
      const Vec3 p(xyz[0], xyz[1], xyz[2]);
      if (!p.allFinite()) bad(path, "triangle " + std::to_string(t) + " has a non-finite vertex");
      f[k] = weld.add(p);
    }
    m.faces.push_back(f);
  }
  if (m.faces.empty()) bad(path, "binary STL with no triangles");
  return m;
}

TriangleMesh read_stl_ascii(const std::string& path, const std::vector<char>& data) {
  std::istringstream in(std::string(data.begin(), data.end()));
  TriangleMesh m;
  VertexWelder weld(m);
  std::string line;
  int lineno = 0;
  std::vector<int> corners;
  bool in_loop = false, seen_solid = false, seen_end = false;
  while (std::getline(in, line)) {
    ++lineno;
    std::istringstream s(line);
    std::string tag;
    if (!(s >> tag)) continue;
    tag = lower(tag);
    if (tag == "solid") {
      seen_solid = true;
    } else if (tag == "facet") {
      if (!seen_solid) bad(path, "'facet' before 'solid'", lineno);
    } else if (tag == "outer") {
      in_loop = true;
      corners.clear();
    } else if (tag == "vertex") {
      if (!in_loop) bad(path, "'vertex' outside 'outer loop'", lineno);
      Vec3 p;
      std::string tok;
      for (int k = 0; k < 3; ++k) {
        if (!(s >> tok)) bad(path, "vertex needs 3 coordinates", lineno);
        if (!parse_double(tok, p[k]))
          bad(path, "vertex coordinate '" + tok + "' is not a finite number", lineno);
      }
      corners.push_back(weld.add(p));
    } else if (tag == "endloop") {
      if (corners.size() != 3)
        bad(path, "facet has " + std::to_string(corners.size()) + " vertices, expected 3", lineno);
      m.faces.push_back({corners[0], corners[1], corners[2]});
      in_loop = false;
    } else if (tag == "endfacet") {
    } else if (tag == "endsolid") {
      seen_end = true;
      break;
    } else {
      bad(path, "unexpected '" + tag + "' in ASCII STL", lineno);
    }
  }
  if (in_loop) bad(path, "file ends inside a facet", lineno);
  if (!seen_end) bad(path, "no 'endsolid' (file truncated?)", lineno);
  if (m.faces.empty()) bad(path, "ASCII STL with no facets");
  return m;
}

TriangleMesh read_stl(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) bad(path, "cannot open for reading");
  std::vector<char> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (data.size() >= 84) {
    uint32_t count = 0;
    std::memcpy(&count, data.data() + 80, 4);
    if (data.size() == 84 + 50 * static_cast<uint64_t>(count)) return read_stl_binary(path, data);
  }
  // ASCII STL starts with "solid" (binary headers may too, so the size test comes first)
  size_t i = 0;
  while (i < data.size() && std::isspace(static_cast<unsigned char>(data[i]))) ++i;
  if (data.size() - i >= 5 && lower(std::string(data.data() + i, 5)) == "solid")
    return read_stl_ascii(path, data);
  bad(path, "not an STL file: size " + std::to_string(data.size()) +
                " bytes does not match a binary STL and it does not start with 'solid'");
}

}  // namespace

TriangleMesh read_mesh(const std::string& path) {
  const std::string ext = lower(std::filesystem::path(path).extension().string());
  // with error codes: a name too long for the file system throws otherwise (exit 1)
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec && ec != std::errc::no_such_file_or_directory)
    bad(path, "cannot be read: " + ec.message());
  if (!std::filesystem::exists(status)) bad(path, "file does not exist");
  if (std::filesystem::is_directory(status)) bad(path, "is a directory, not a mesh file");
  if (ext != ".obj" && ext != ".stl")
    bad(path, "unknown mesh format '" + ext + "' (expected .obj or .stl)");
  TriangleMesh mesh = ext == ".obj" ? read_obj(path) : read_stl(path);
  // beyond 1e15 the squares of edges and areas overflow and every later check says the wrong thing
  constexpr double kMaxCoordinate = 1e15;
  for (size_t i = 0; i < mesh.vertices.size(); ++i)
    if (!(mesh.vertices[i].cwiseAbs().maxCoeff() <= kMaxCoordinate)) {
      std::ostringstream m;
      m << "vertex " << i << " (" << mesh.vertices[i].x() << ", "
        << mesh.vertices[i].y() << ", " << mesh.vertices[i].z()
        << "): coordinates must be in [-1e15, 1e15]";
      bad(path, m.str());
    }
  return mesh;
}

void write_stl_ascii(const std::string& path, const TriangleMesh& mesh, const std::string& name) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << std::setprecision(17) << "solid " << name << "\n";
    for (const auto& f : mesh.faces) {
      const Vec3& a = mesh.vertices[f[0]];
      const Vec3& b = mesh.vertices[f[1]];
      const Vec3& c = mesh.vertices[f[2]];
      const Vec3 n = (b - a).cross(c - a).normalized();
      out << "  facet normal " << n.x() << " " << n.y() << " " << n.z() << "\n    outer loop\n";
      for (const Vec3* p : {&a, &b, &c})
        out << "      vertex " << p->x() << " " << p->y() << " " << p->z() << "\n";
      out << "    endloop\n  endfacet\n";
    }
    out << "endsolid " << name << "\n";
  });
}

void write_stl_binary(const std::string& path, const TriangleMesh& mesh) {
  write_file_atomically(path, [&](std::ostream& out) {
    char header[80] = {};
    std::snprintf(header, sizeof header, "lrigid binary STL");
    out.write(header, 80);
    const uint32_t count = static_cast<uint32_t>(mesh.faces.size());
    out.write(reinterpret_cast<const char*>(&count), 4);
    for (const auto& f : mesh.faces) {
      const Vec3& a = mesh.vertices[f[0]];
      const Vec3& b = mesh.vertices[f[1]];
      const Vec3& c = mesh.vertices[f[2]];
      const Vec3 n = (b - a).cross(c - a).normalized();
      float rec[12];
      for (int k = 0; k < 3; ++k) {
        rec[k] = static_cast<float>(n[k]);
        rec[3 + k] = static_cast<float>(a[k]);
        rec[6 + k] = static_cast<float>(b[k]);
        rec[9 + k] = static_cast<float>(c[k]);
      }
      out.write(reinterpret_cast<const char*>(rec), sizeof rec);
      const uint16_t attr = 0;
      out.write(reinterpret_cast<const char*>(&attr), 2);
    }
  });
}

void write_obj(const std::string& path, const TriangleMesh& mesh) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << std::setprecision(17);
    for (const Vec3& v : mesh.vertices)
      out << "v " << v.x() << " " << v.y() << " " << v.z() << "\n";
    for (const auto& f : mesh.faces)
      out << "f " << f[0] + 1 << " " << f[1] + 1 << " " << f[2] + 1 << "\n";
  });
}

}  // namespace lrigid
