#include "io/gltf_writer.h"

#include <tiny_gltf.h>

#include <array>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>

#include "io/atomic_file.h"
#include "io/dcc_cache.h"
#include "model/state.h"
#include "util/error.h"

namespace lrigid {

namespace {

// appends raw bytes, padded to 4 bytes so every view stays aligned
size_t append(std::vector<unsigned char>* buf, const void* data, size_t bytes) {
  const size_t at = buf->size();
  buf->resize(at + ((bytes + 3) & ~size_t(3)), 0);
  if (bytes) std::memcpy(buf->data() + at, data, bytes);
  return at;
}

int add_view(tinygltf::Model* m, size_t offset, size_t length, int target) {
  tinygltf::BufferView v;
  v.buffer = 0;
  v.byteOffset = offset;
  v.byteLength = length;
  v.target = target;
  m->bufferViews.push_back(v);
  return int(m->bufferViews.size()) - 1;
}

int add_accessor(tinygltf::Model* m, int view, size_t offset, size_t count, int type,
                 int component) {
  tinygltf::Accessor a;
  a.bufferView = view;
  a.byteOffset = offset;
  a.count = count;
  a.type = type;
  a.componentType = component;
  m->accessors.push_back(a);
  return int(m->accessors.size()) - 1;
}

// distinct, muted colours per body entry
void entry_colour(size_t i, double rgb[3]) {
  static const double kPalette[][3] = {{0.85, 0.55, 0.25}, {0.30, 0.55, 0.85},
                                       {0.45, 0.75, 0.35}, {0.80, 0.35, 0.45},
                                       {0.60, 0.45, 0.80}, {0.85, 0.80, 0.35}};
  for (int k = 0; k < 3; ++k) rgb[k] = kPalette[i % 6][k];
}

// builds the model's buffer, views and accessors
struct Builder {
  tinygltf::Model m;
  std::vector<unsigned char> buf;

  // float data as one accessor of `count` elements of `type` (a view of its own)
  int floats(const std::vector<float>& data, size_t count, int type, int target = 0) {
    const size_t bytes = data.size() * sizeof(float);
    const int view = add_view(&m, append(&buf, data.data(), bytes), bytes, target);
    return add_accessor(&m, view, 0, count, type, TINYGLTF_COMPONENT_TYPE_FLOAT);
  }
  // the bounds glTF requires of positions and animation inputs
  void bounds(int accessor, const std::vector<float>& data, int comps) {
    std::vector<double> lo(size_t(comps), std::numeric_limits<double>::max()), hi(lo.size());
    for (double& h : hi) h = -std::numeric_limits<double>::max();
    for (size_t i = 0; i < data.size(); ++i) {
      lo[i % size_t(comps)] = std::min(lo[i % size_t(comps)], double(data[i]));
      hi[i % size_t(comps)] = std::max(hi[i % size_t(comps)], double(data[i]));
    }
    m.accessors[size_t(accessor)].minValues = lo;
    m.accessors[size_t(accessor)].maxValues = hi;
  }
  // a channel of `node`'s `path` sampled at the accessors `input` (times) and `output`
  void channel(tinygltf::Animation* anim, int node, const char* path, int input, int output,
               const char* interpolation) {
    tinygltf::AnimationSampler s;
    s.input = input;
    s.output = output;
    s.interpolation = interpolation;
    anim->samplers.push_back(s);
    tinygltf::AnimationChannel c;
    c.sampler = int(anim->samplers.size()) - 1;
    c.target_node = node;
    c.target_path = path;
    anim->channels.push_back(c);
  }
  int add_node(tinygltf::Node n, int parent) {
    m.nodes.push_back(std::move(n));
    const int i = int(m.nodes.size()) - 1;
    if (parent >= 0) m.nodes[size_t(parent)].children.push_back(i);
    return i;
  }
};

// one mesh per body type: a vertex per distinct (vertex, corner normal, texture coordinate),
// glTF's texture origin at the top left (t = 1 - v)
void add_meshes(Builder* g, const GltfAnimation& a) {
  const DccEntries entries = dcc_entries(a);
  for (size_t e = 0; e < entries.names.size(); ++e) {
    tinygltf::Material mat;
    mat.name = entries.names[e];
    double rgb[3];
    entry_colour(e, rgb);
    mat.pbrMetallicRoughness.baseColorFactor = {rgb[0], rgb[1], rgb[2], 1.0};
    mat.pbrMetallicRoughness.metallicFactor = 0.0;
    mat.pbrMetallicRoughness.roughnessFactor = 0.7;
    mat.doubleSided = true;  // thin cards are seen from both sides
    g->m.materials.push_back(mat);
  }
  for (size_t ti = 0; ti < a.types.size(); ++ti) {
    const TriangleMesh& s = a.types[ti].surface;
    const bool uv = s.has_uv();
    const std::vector<Vec3> normals = corner_normals(s);
    std::vector<float> p, n, t;
    std::vector<uint32_t> idx;
    std::map<std::array<float, 6>, uint32_t> seen;  // (vertex, normal, uv) -> index
    for (size_t f = 0; f < s.faces.size(); ++f)
      for (int k = 0; k < 3; ++k) {
        const Vec3& nk = normals[3 * f + size_t(k)];
        const Vec2 tk = uv ? s.uv[f][size_t(k)] : Vec2::Zero();
        const std::array<float, 6> key = {float(s.faces[f][size_t(k)]), float(nk.x()),
                                          float(nk.y()),  float(nk.z()),
                                          float(tk.x()),  float(1 - tk.y())};
        const auto [it, added] = seen.emplace(key, uint32_t(seen.size()));
        idx.push_back(it->second);
        if (!added) continue;
        const Vec3& v = s.vertices[size_t(s.faces[f][size_t(k)])];
        p.insert(p.end(), {float(v.x()), float(v.y()), float(v.z())});
        n.insert(n.end(), {key[1], key[2], key[3]});
        if (uv) t.insert(t.end(), {key[4], key[5]});
      }
    tinygltf::Primitive prim;
    prim.attributes["POSITION"] =
        g->floats(p, p.size() / 3, TINYGLTF_TYPE_VEC3, TINYGLTF_TARGET_ARRAY_BUFFER);
    g->bounds(prim.attributes["POSITION"], p, 3);
    prim.attributes["NORMAL"] =
        g->floats(n, n.size() / 3, TINYGLTF_TYPE_VEC3, TINYGLTF_TARGET_ARRAY_BUFFER);
    if (uv)
      prim.attributes["TEXCOORD_0"] =
          g->floats(t, t.size() / 2, TINYGLTF_TYPE_VEC2, TINYGLTF_TARGET_ARRAY_BUFFER);
    const size_t ibytes = idx.size() * sizeof(uint32_t);
    const int iv = add_view(&g->m, append(&g->buf, idx.data(), ibytes), ibytes,
                            TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    prim.indices = add_accessor(&g->m, iv, 0, idx.size(), TINYGLTF_TYPE_SCALAR,
                                TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
    prim.material = int(entries.material[ti]);
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    tinygltf::Mesh mesh;
    mesh.name = type_label(a, ti);
    mesh.primitives.push_back(prim);
    g->m.meshes.push_back(mesh);
  }
}

// body b's attributes: id, entry, variant, its states at each change
tinygltf::Value body_extras(const GltfAnimation& a, size_t b) {
  const GltfBodyType& t = a.types[size_t(a.body_type[b])];
  tinygltf::Value::Object o;
  o["id"] = tinygltf::Value(int(b));
  o["entry"] = tinygltf::Value(t.name);
  o["variant"] = tinygltf::Value(t.variant);
  tinygltf::Value::Array states;
  for (const auto& [time, code] : state_changes(a, b))
    states.push_back(tinygltf::Value(
        tinygltf::Value::Array{tinygltf::Value(time), tinygltf::Value(std::string(kStateNames[code]))}));
  if (!states.empty()) o["states"] = tinygltf::Value(std::move(states));
  return tinygltf::Value(std::move(o));
}

// GltfLayout::Animated: one node per body, its translation and rotation sampled at the times
void add_body_nodes(Builder* g, const GltfAnimation& a, int root, int times,
                    tinygltf::Animation* anim) {
  const size_t nb = a.bodies(), nf = a.times.size();
  const std::vector<Quat> q = continuous_orientations(a);
  // body-major translations and rotations (glTF quaternion order x, y, z, w)
  std::vector<float> tr(nb * nf * 3), rot(nb * nf * 4);
  for (size_t f = 0; f < nf; ++f)
    for (size_t b = 0; b < nb; ++b) {
      const Vec3& x = a.x[f * nb + b];
      const Quat& r = q[f * nb + b];
      float* t = &tr[(b * nf + f) * 3];
      t[0] = float(x.x()), t[1] = float(x.y()), t[2] = float(x.z());
      float* o = &rot[(b * nf + f) * 4];
      o[0] = float(r.x()), o[1] = float(r.y()), o[2] = float(r.z()), o[3] = float(r.w());
    }
  const int trv = add_view(&g->m, append(&g->buf, tr.data(), tr.size() * 4), tr.size() * 4, 0);
  const int rov = add_view(&g->m, append(&g->buf, rot.data(), rot.size() * 4), rot.size() * 4, 0);
  g->m.nodes.reserve(g->m.nodes.size() + nb);
  g->m.accessors.reserve(g->m.accessors.size() + 2 * nb);
  for (size_t b = 0; b < nb; ++b) {
    tinygltf::Node n;
    const int type = a.body_type[b];
    n.name = "body_" + std::to_string(b) + "_" + type_label(a, size_t(type));
    n.mesh = type;
    const float* t = &tr[b * nf * 3];
    const float* r = &rot[b * nf * 4];
    n.translation = {t[0], t[1], t[2]};
    n.rotation = {r[0], r[1], r[2], r[3]};
    n.extras = body_extras(a, b);
    if (a.hidden_at(0, b)) n.scale = {0, 0, 0};
    const int node = g->add_node(std::move(n), root);
    constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;
    g->channel(anim, node, "translation", times,
               add_accessor(&g->m, trv, b * nf * 12, nf, TINYGLTF_TYPE_VEC3, kFloat), "LINEAR");
    g->channel(anim, node, "rotation", times,
               add_accessor(&g->m, rov, b * nf * 16, nf, TINYGLTF_TYPE_VEC4, kFloat), "LINEAR");
    // a hidden body (removed at the grid's edge, not yet released): scale 0 (a STEP channel)
    bool ever_hidden = false;
    for (size_t f = 0; f < nf && !ever_hidden; ++f) ever_hidden = a.hidden_at(f, b);
    if (ever_hidden) {
      std::vector<float> sc(3 * nf);
      for (size_t f = 0; f < nf; ++f)
        sc[3 * f] = sc[3 * f + 1] = sc[3 * f + 2] = a.hidden_at(f, b) ? 0.f : 1.f;
      g->channel(anim, node, "scale", times, g->floats(sc, nf, TINYGLTF_TYPE_VEC3), "STEP");
    }
  }
}

// GltfLayout::Instanced: a node per frame, shown from its time to the next one's, holding one
// instanced node per body type (the frame's visible bodies)
void add_frame_nodes(Builder* g, const GltfAnimation& a, int root, tinygltf::Animation* anim) {
  const size_t nb = a.bodies(), nf = a.times.size();
  const std::vector<Quat> q = continuous_orientations(a);
  for (size_t f = 0; f < nf; ++f) {
    tinygltf::Node frame;
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06zu", f);
    frame.name = name;
    frame.scale = f == 0 ? std::vector<double>{1, 1, 1} : std::vector<double>{0, 0, 0};
    tinygltf::Value::Object extras;
    extras["t"] = tinygltf::Value(a.times[f]);
    frame.extras = tinygltf::Value(std::move(extras));
    const int fn = g->add_node(std::move(frame), root);
    for (size_t ti = 0; ti < a.types.size(); ++ti) {
      std::vector<float> tr, rot, id;
      for (size_t b = 0; b < nb; ++b) {
        if (size_t(a.body_type[b]) != ti || a.hidden_at(f, b)) continue;
        const Vec3& x = a.x[f * nb + b];
        const Quat& r = q[f * nb + b];
        tr.insert(tr.end(), {float(x.x()), float(x.y()), float(x.z())});
        rot.insert(rot.end(), {float(r.x()), float(r.y()), float(r.z()), float(r.w())});
        id.push_back(float(b));
      }
      if (id.empty()) continue;
      tinygltf::Node n;
      n.name = std::string(name) + "_" + type_label(a, ti);
      n.mesh = int(ti);
      tinygltf::Value::Object attributes;
      attributes["TRANSLATION"] = tinygltf::Value(g->floats(tr, id.size(), TINYGLTF_TYPE_VEC3));
      attributes["ROTATION"] = tinygltf::Value(g->floats(rot, id.size(), TINYGLTF_TYPE_VEC4));
      attributes["_ID"] = tinygltf::Value(g->floats(id, id.size(), TINYGLTF_TYPE_SCALAR));
      tinygltf::Value::Object ext;
      ext["attributes"] = tinygltf::Value(std::move(attributes));
      n.extensions["EXT_mesh_gpu_instancing"] = tinygltf::Value(std::move(ext));
      g->add_node(std::move(n), fn);
    }
    if (nf < 2) continue;
    // shown from t_f to t_f+1 (STEP holds a key's value until the next key)
    std::vector<float> t, s;
    auto key = [&](size_t at, float scale) {
      t.push_back(float(a.times[at]));
      s.insert(s.end(), {scale, scale, scale});
    };
    if (f > 0) key(0, 0);
    key(f, 1);
    if (f + 1 < nf) key(f + 1, 0);
    const int input = g->floats(t, t.size(), TINYGLTF_TYPE_SCALAR);
    g->bounds(input, t, 1);
    g->channel(anim, fn, "scale", input, g->floats(s, t.size(), TINYGLTF_TYPE_VEC3), "STEP");
  }
}

}  // namespace

void write_gltf(const std::string& path, const GltfAnimation& a, GltfLayout layout) {
  check_animation(path, a, false);
  const size_t nf = a.times.size();
  Builder g;
  g.m.asset.version = "2.0";
  g.m.asset.generator = "lrigid " LRIGID_VERSION;
  add_meshes(&g, a);

  // root node: Z-up -> Y-up
  tinygltf::Node root;
  root.name = "lrigid_world_z_up";
  root.rotation.assign(kGltfRootRotation, kGltfRootRotation + 4);
  g.add_node(std::move(root), -1);
  tinygltf::Animation anim;
  anim.name = "trajectories";
  if (layout == GltfLayout::Animated) {
    // sample times, shared by every channel
    std::vector<float> times(nf);
    for (size_t f = 0; f < nf; ++f) times[f] = float(a.times[f]);
    const int ta = g.floats(times, nf, TINYGLTF_TYPE_SCALAR);
    g.bounds(ta, times, 1);
    add_body_nodes(&g, a, 0, ta, &anim);
  } else {
    add_frame_nodes(&g, a, 0, &anim);
    g.m.extensionsUsed.push_back("EXT_mesh_gpu_instancing");
    g.m.extensionsRequired.push_back("EXT_mesh_gpu_instancing");
  }
  if (nf > 1) g.m.animations.push_back(anim);
  tinygltf::Buffer buffer;
  buffer.data = std::move(g.buf);
  g.m.buffers.push_back(std::move(buffer));
  tinygltf::Scene scene;
  scene.name = "lrigid";
  scene.nodes = {0};
  g.m.scenes.push_back(scene);
  g.m.defaultScene = 0;

  write_file_atomically(path, [&](std::ostream& o) {
    tinygltf::TinyGLTF gltf;
    if (!gltf.WriteGltfSceneToStream(&g.m, o, false, true))
      throw Error(ExitCode::Output, where(path, "", "tinygltf could not serialize the scene"));
  });
}

}  // namespace lrigid
