#include "io/usd_writer.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "io/atomic_file.h"
#include "io/dcc_cache.h"

namespace lrigid {

std::string usd_identifier(const std::string& label) {
  std::string id;
  for (char c : label) id += std::isalnum(static_cast<unsigned char>(c)) || c == '_' ? c : '_';
  if (id.empty() || std::isdigit(static_cast<unsigned char>(id[0]))) id.insert(0, "_");
  return id;
}

std::vector<std::string> usd_identifiers(const std::vector<std::string>& labels) {
  std::vector<std::string> out;
  for (const std::string& l : labels) {
    const std::string id = usd_identifier(l);
    std::string unique = id;
    for (int k = 2; std::find(out.begin(), out.end(), unique) != out.end(); ++k)
      unique = id + "_" + std::to_string(k);
    out.push_back(unique);
  }
  return out;
}

namespace {

// "(a, b, c)" of a tuple value
void usd_tuple(std::string* s, std::initializer_list<double> v) {
  *s += '(';
  for (const double* c = v.begin(); c != v.end(); ++c) {
    if (c != v.begin()) *s += ", ";
    append_number(s, *c);
  }
  *s += ')';
}

// "[item, item, ...]" of n items, each appended by item(s, i)
template <typename Item>
void usd_array(std::string* s, size_t n, Item item) {
  *s += '[';
  for (size_t i = 0; i < n; ++i) {
    if (i) *s += ", ";
    item(s, i);
  }
  *s += ']';
}

void flush(std::ostream& o, std::string* s) {
  o.write(s->data(), std::streamsize(s->size()));
  s->clear();
}

// an attribute's time samples: "type name.timeSamples = {\n code: value,\n ...}", each
// frame's written out to `o` once built
template <typename Value>
void usd_samples(std::ostream& o, std::string* s, const char* decl,
                 const std::vector<double>& codes, Value value) {
  *s += "        ";
  *s += decl;
  *s += ".timeSamples = {\n";
  for (size_t f = 0; f < codes.size(); ++f) {
    *s += "            ";
    append_number(s, codes[f]);
    *s += ": ";
    value(s, f);
    *s += ",\n";
    flush(o, s);
  }
  *s += "        }\n";
}

void usd_mesh(std::string* s, const std::string& name, const TriangleMesh& m,
              const std::string& material) {
  const std::vector<Vec3> normals = corner_normals(m);
  Vec3 lo = Vec3::Constant(1e300), hi = -lo;
  for (const Vec3& v : m.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  *s += "            def Mesh \"" + name + "\" (\n";
  *s += "                prepend apiSchemas = [\"MaterialBindingAPI\"]\n            )\n";
  *s += "            {\n                float3[] extent = [";
  usd_tuple(s, {lo.x(), lo.y(), lo.z()});
  *s += ", ";
  usd_tuple(s, {hi.x(), hi.y(), hi.z()});
  *s += "]\n                int[] faceVertexCounts = ";
  usd_array(s, m.faces.size(), [](std::string* o, size_t) { *o += '3'; });
  *s += "\n                int[] faceVertexIndices = ";
  usd_array(s, 3 * m.faces.size(),
            [&](std::string* o, size_t i) { *o += std::to_string(m.faces[i / 3][i % 3]); });
  *s += "\n                point3f[] points = ";
  usd_array(s, m.vertices.size(), [&](std::string* o, size_t i) {
    usd_tuple(o, {m.vertices[i].x(), m.vertices[i].y(), m.vertices[i].z()});
  });
  *s += "\n                normal3f[] normals = ";
  usd_array(s, normals.size(), [&](std::string* o, size_t i) {
    usd_tuple(o, {normals[i].x(), normals[i].y(), normals[i].z()});
  });
  *s += " (\n                    interpolation = \"faceVarying\"\n                )\n";
  if (m.has_uv()) {
    *s += "                texCoord2f[] primvars:st = ";
    usd_array(s, 3 * m.faces.size(), [&](std::string* o, size_t i) {
      const Vec2& t = m.uv[i / 3][i % 3];
      usd_tuple(o, {t.x(), t.y()});
    });
    *s += " (\n                    interpolation = \"faceVarying\"\n                )\n";
  }
  *s += "                uniform token orientation = \"rightHanded\"\n";
  *s += "                uniform token subdivisionScheme = \"none\"\n";
  *s += "                rel material:binding = </lrigid/Materials/" + material + ">\n";
  *s += "            }\n";
}

}  // namespace

void write_usd(const std::string& path, const GltfAnimation& a) {
  check_animation(path, a, true);
  const size_t nb = a.bodies(), nf = a.times.size();
  // time codes: the frames' numbers when the frames are evenly spaced
  const double step = nf > 1 && a.times[1] > a.times[0] ? a.times[1] - a.times[0] : 1.0;
  std::vector<double> codes(nf);
  for (size_t f = 0; f < nf; ++f) {
    codes[f] = a.times[f] / step;
    if (std::abs(codes[f] - std::round(codes[f])) < 1e-6) codes[f] = std::round(codes[f]);
  }
  const DccEntries entries = dcc_entries(a);
  std::vector<std::string> labels, materials;
  for (size_t t = 0; t < a.types.size(); ++t) labels.push_back(type_label(a, t));
  labels = usd_identifiers(labels);
  materials = usd_identifiers(entries.names);
  const std::vector<Quat> q = continuous_orientations(a);
  constexpr double kDegrees = 180 / M_PI;

  write_file_atomically(path, [&](std::ostream& out) {
  std::string s = "#usda 1.0\n(\n    defaultPrim = \"lrigid\"\n";
  s += "    doc = \"lrigid " LRIGID_VERSION ": rigid bodies in a flow\"\n";
  s += "    endTimeCode = ";
  append_number(&s, codes.back());
  s += "\n    framesPerSecond = ";
  append_number(&s, 1 / step);
  s += "\n    metersPerUnit = 1\n    startTimeCode = ";
  append_number(&s, codes.front());
  s += "\n    timeCodesPerSecond = ";
  append_number(&s, 1 / step);
  s += "\n    upAxis = \"Z\"\n)\n\ndef Xform \"lrigid\"\n{\n";
  s += "    def PointInstancer \"bodies\"\n    {\n";
  s += "        rel prototypes = ";
  usd_array(&s, a.types.size(), [&](std::string* o, size_t t) {
    *o += "</lrigid/bodies/Prototypes/" + labels[t] + ">";
  });
  s += "\n        int[] protoIndices = ";
  usd_array(&s, nb, [&](std::string* o, size_t b) { *o += std::to_string(a.body_type[b]); });
  s += "\n        int64[] ids = ";
  usd_array(&s, nb, [&](std::string* o, size_t b) { *o += std::to_string(b); });
  s += "\n";
  usd_samples(out, &s, "point3f[] positions", codes, [&](std::string* o, size_t f) {
    usd_array(o, nb, [&](std::string* p, size_t b) {
      const Vec3& x = a.x[f * nb + b];
      usd_tuple(p, {x.x(), x.y(), x.z()});
    });
  });
  usd_samples(out, &s, "quath[] orientations", codes, [&](std::string* o, size_t f) {
    usd_array(o, nb, [&](std::string* p, size_t b) {
      const Quat& r = q[f * nb + b];
      usd_tuple(p, {r.w(), r.x(), r.y(), r.z()});
    });
  });
  usd_samples(out, &s, "vector3f[] velocities", codes, [&](std::string* o, size_t f) {
    usd_array(o, nb, [&](std::string* p, size_t b) {
      const Vec3& v = a.v[f * nb + b];
      usd_tuple(p, {v.x(), v.y(), v.z()});
    });
  });
  usd_samples(out, &s, "vector3f[] angularVelocities", codes, [&](std::string* o, size_t f) {
    usd_array(o, nb, [&](std::string* p, size_t b) {
      const Vec3 w = kDegrees * a.w[f * nb + b];
      usd_tuple(p, {w.x(), w.y(), w.z()});
    });
  });
  usd_samples(out, &s, "int64[] invisibleIds", codes, [&](std::string* o, size_t f) {
    std::vector<size_t> hidden;
    for (size_t b = 0; b < nb; ++b)
      if (a.hidden_at(f, b)) hidden.push_back(b);
    usd_array(o, hidden.size(),
              [&](std::string* p, size_t i) { *p += std::to_string(hidden[i]); });
  });
  s += "\n        def Scope \"Prototypes\"\n        {\n";
  for (size_t t = 0; t < a.types.size(); ++t)
    usd_mesh(&s, labels[t], a.types[t].surface, materials[entries.material[t]]);
  s += "        }\n    }\n\n    def Scope \"Materials\"\n    {\n";
  for (const std::string& e : materials) {
    const std::string m = "/lrigid/Materials/" + e;
    s += "        def Material \"" + e + "\"\n        {\n";
    s += "            token outputs:surface.connect = <" + m + "/Surface.outputs:surface>\n\n";
    s += "            def Shader \"Surface\"\n            {\n";
    s += "                uniform token info:id = \"UsdPreviewSurface\"\n";
    s += "                float inputs:roughness = 0.7\n";
    s += "                token outputs:surface\n            }\n        }\n";
  }
  s += "    }\n}\n";
  flush(out, &s);
  });
}

}  // namespace lrigid
