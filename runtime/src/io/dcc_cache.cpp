#include "io/dcc_cache.h"

#include <charconv>
#include <cmath>
#include <map>

#include "io/houdini_writer.h"
#include "io/usd_writer.h"
#include "util/error.h"

namespace lrigid {

namespace {
void write_gltf_animated(const std::string& path, const GltfAnimation& a) { write_gltf(path, a); }
void write_gltf_instanced(const std::string& path, const GltfAnimation& a) {
  write_gltf(path, a, GltfLayout::Instanced);
}
}  // namespace

const DccFormat kDccFormats[4] = {
    {"glb", "animation.glb", false, write_gltf_animated, &OutputSpec::glb},
    {"glb_instanced", "animation_instanced.glb", false, write_gltf_instanced,
     &OutputSpec::glb_instanced},
    {"houdini", "houdini_points.csv", true, write_houdini_csv, &OutputSpec::houdini},
    {"usd", "bodies.usda", true, write_usd, &OutputSpec::usd}};

void check_animation(const std::string& path, const GltfAnimation& a, bool velocities) {
  const size_t n = a.bodies() * a.times.size();
  if (a.times.empty()) throw Error(ExitCode::Usage, where(path, "", "no output frames to animate"));
  if (a.x.size() != n || a.q.size() != n)
    throw Error(ExitCode::Usage, where(path, "", "frames hold fewer samples than bodies x times"));
  if (velocities && (a.v.size() != n || a.w.size() != n))
    throw Error(ExitCode::Usage, where(path, "", "frames hold no velocities for every sample"));
  if (!a.state.empty() && a.state.size() != n)
    throw Error(ExitCode::Usage, where(path, "", "frames hold states for some samples only"));
  for (int t : a.body_type)
    if (t < 0 || size_t(t) >= a.types.size())
      throw Error(ExitCode::Usage, where(path, "", "body of unknown type " + std::to_string(t)));
}

std::string type_label(const GltfAnimation& a, size_t type) {
  const GltfBodyType& t = a.types[type];
  size_t variants = 0;
  for (const GltfBodyType& o : a.types) variants += o.entry == t.entry;
  return variants > 1 ? t.name + "." + std::to_string(t.variant) : t.name;
}

DccEntries dcc_entries(const GltfAnimation& a) {
  DccEntries e;
  std::map<size_t, size_t> index;  // entry -> material
  for (const GltfBodyType& t : a.types) {
    const auto [it, added] = index.emplace(t.entry, e.names.size());
    if (added) e.names.push_back(t.name);
    e.material.push_back(it->second);
  }
  return e;
}

std::vector<Vec3> corner_normals(const TriangleMesh& m) {
  // each face's normal times twice its area, and the faces around each vertex
  std::vector<Vec3> face(m.faces.size());
  std::vector<std::vector<size_t>> around(m.vertices.size());
  for (size_t i = 0; i < m.faces.size(); ++i) {
    const auto& f = m.faces[i];
    face[i] = (m.vertices[f[1]] - m.vertices[f[0]]).cross(m.vertices[f[2]] - m.vertices[f[0]]);
    for (int k = 0; k < 3; ++k) around[size_t(f[k])].push_back(i);
  }
  const double cos_smooth = std::cos(kSmoothAngleDeg * M_PI / 180);
  std::vector<Vec3> out(3 * m.faces.size());
  for (size_t i = 0; i < m.faces.size(); ++i) {
    const Vec3 own = face[i].normalized();
    for (int k = 0; k < 3; ++k) {
      Vec3 sum = Vec3::Zero();
      for (size_t j : around[size_t(m.faces[i][k])])
        if (face[j].normalized().dot(own) >= cos_smooth) sum += face[j];
      const double len = sum.norm();
      out[3 * i + size_t(k)] = len > 0 ? Vec3(sum / len) : own;
    }
  }
  return out;
}

std::vector<Quat> continuous_orientations(const GltfAnimation& a) {
  const size_t nb = a.bodies();
  std::vector<Quat> q(a.q.size());
  for (size_t k = 0; k < q.size(); ++k) {
    q[k] = a.q[k].normalized();
    if (k >= nb && q[k - nb].coeffs().dot(q[k].coeffs()) < 0) q[k].coeffs() *= -1;
  }
  return q;
}

std::vector<std::pair<double, uint8_t>> state_changes(const GltfAnimation& a, size_t b) {
  std::vector<std::pair<double, uint8_t>> out;
  if (a.state.empty()) return out;
  const size_t nb = a.bodies();
  for (size_t f = 0; f < a.times.size(); ++f) {
    const uint8_t s = a.state[f * nb + b];
    if (out.empty() || out.back().second != s) out.emplace_back(a.times[f], s);
  }
  return out;
}

void append_number(std::string* out, double x) {
  char b[32];
  const auto r = std::to_chars(b, b + sizeof b, x, std::chars_format::general, 9);
  out->append(b, r.ptr);
}

}  // namespace lrigid
