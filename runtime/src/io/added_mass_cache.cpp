#include "io/added_mass_cache.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "io/atomic_file.h"
#include "io/durable.h"
#include "util/error.h"

namespace lrigid {

namespace {

// bump when the BEM or the file layout changes: old entries are then recomputed
// 2: box tensors are diagonal (their symmetry; format 1 kept the panel solution's round-off)
constexpr int kCacheFormat = 2;

// 64-bit FNV-1a over the raw bytes of values (io/durable.h)
class Hasher {
 public:
  template <typename T>
  void value(const T& v) {
    f_.add(&v, sizeof v);
  }
  void bytes(const void* p, size_t n) { f_.add(p, n); }
  uint64_t get() const { return f_.h; }

 private:
  Fnv64 f_;
};

uint64_t geometry_hash(const Shape& shape) {
  Hasher h;
  h.value(static_cast<int>(shape.type));
  for (int k = 0; k < 3; ++k) h.value(shape.half_extents[k]);
  if (shape.type == ShapeType::Mesh && shape.mesh) {
    h.value(shape.mesh->vertices.size());
    for (const Vec3& v : shape.mesh->vertices)
      for (int k = 0; k < 3; ++k) h.value(v[k]);
    h.value(shape.mesh->faces.size());
    for (const auto& f : shape.mesh->faces)
      for (int k = 0; k < 3; ++k) h.value(f[k]);
  }
  return h.get();
}

std::string hex16(uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

bool analytic(const Shape& s) {
  return s.type == ShapeType::Sphere || s.type == ShapeType::Ellipsoid;
}

// nullopt-like: returns false if the file is missing, unreadable or not a valid entry for `key`
bool load(const std::string& file, const std::string& key, AddedMass& out) {
  std::ifstream in(file);
  if (!in) return false;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    if (j.at("format").get<int>() != kCacheFormat || j.at("key").get<std::string>() != key)
      return false;
    const auto& t = j.at("tensor_per_unit_density");
    if (!t.is_array() || t.size() != 6) return false;
    Mat6 k;
    for (int r = 0; r < 6; ++r) {
      if (!t[r].is_array() || t[r].size() != 6) return false;
      for (int c = 0; c < 6; ++c) k(r, c) = t[r][c].get<double>();
    }
    if (!k.allFinite() ||
        (k - k.transpose()).cwiseAbs().maxCoeff() > 1e-12 * k.cwiseAbs().maxCoeff())
      return false;
    out.tensor = k;
    out.method = j.at("method").get<std::string>();
    out.panels = j.at("panels").get<int>();
    return out.method == "bem" && out.panels > 0;
  } catch (const std::exception&) {
    return false;  // corrupt: recompute and overwrite
  }
}

void store(const std::string& dir, const std::string& file, const std::string& key,
           const AddedMass& per_unit) {
  nlohmann::json j;
  j["format"] = kCacheFormat;
  j["key"] = key;
  j["method"] = per_unit.method;
  j["panels"] = per_unit.panels;
  nlohmann::json t = nlohmann::json::array();
  for (int r = 0; r < 6; ++r) {
    nlohmann::json row = nlohmann::json::array();
    for (int c = 0; c < 6; ++c) row.push_back(per_unit.tensor(r, c));
    t.push_back(row);
  }
  j["tensor_per_unit_density"] = t;
  ensure_writable_directory(dir);
  write_file_atomically(file, [&](std::ostream& out) { out << j.dump(1) << "\n"; });
}

}  // namespace

std::string added_mass_cache_dir() {
  const char* dir = std::getenv("LRIGID_CACHE_DIR");
  if (dir && *dir) return dir;
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  if (xdg && *xdg) return std::string(xdg) + "/lrigid";
  const char* home = std::getenv("HOME");
  if (home && *home) return std::string(home) + "/.cache/lrigid";
  return ".lrigid-cache";
}

std::string added_mass_cache_key(const Shape& shape, int panels) {
  std::ostringstream s;
  s << "format " << kCacheFormat << "; " << shape_type_name(shape.type) << "; geometry "
    << hex16(geometry_hash(shape)) << "; panels " << (panels == 0 ? kDefaultPanels : panels);
  if (shape.type == ShapeType::Mesh && shape.mesh)
    s << "; vertices " << shape.mesh->vertices.size() << "; faces " << shape.mesh->faces.size();
  return s.str();
}

std::string added_mass_cache_file(const Shape& shape, int panels) {
  Hasher h;
  const std::string key = added_mass_cache_key(shape, panels);
  h.bytes(key.data(), key.size());
  return added_mass_cache_dir() + "/added_mass-" + hex16(h.get()) + ".json";
}

AddedMass cached_added_mass(const Shape& shape, double fluid_density, int panels) {
  if (analytic(shape)) return added_mass(shape, fluid_density, panels);
  if (!(fluid_density >= 0) || !std::isfinite(fluid_density) || panels < 0)
    return added_mass(shape, fluid_density, panels);  // throws the usual message
  const std::string key = added_mass_cache_key(shape, panels);
  const std::string file = added_mass_cache_file(shape, panels);
  AddedMass am;
  if (!load(file, key, am)) {
    am = added_mass(shape, 1.0, panels);
    try {
      store(added_mass_cache_dir(), file, key, am);
    } catch (const Error& e) {
      std::cerr << "lrigid: warning: added-mass cache not written: " << e.what() << "\n";
    }
  }
  am.tensor *= fluid_density;
  return am;
}

}  // namespace lrigid
