#include "io/gltf_writer.h"

#include <tiny_gltf.h>

#include <cstring>
#include <limits>

#include "io/atomic_file.h"
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

// distinct, muted colours per body type
void type_colour(size_t i, double rgb[3]) {
  static const double kPalette[][3] = {{0.85, 0.55, 0.25}, {0.30, 0.55, 0.85},
                                       {0.45, 0.75, 0.35}, {0.80, 0.35, 0.45},
                                       {0.60, 0.45, 0.80}, {0.85, 0.80, 0.35}};
  for (int k = 0; k < 3; ++k) rgb[k] = kPalette[i % 6][k];
}

}  // namespace

void write_gltf(const std::string& path, const GltfAnimation& a) {
  const size_t nb = a.bodies(), nf = a.times.size();
  if (nf == 0) throw Error(ExitCode::Usage, where(path, "", "no output frames to animate"));
  if (a.x.size() != nf * nb || a.q.size() != nf * nb)
    throw Error(ExitCode::Usage, where(path, "", "frames hold fewer samples than bodies x times"));
  for (int t : a.body_type)
    if (t < 0 || size_t(t) >= a.types.size())
      throw Error(ExitCode::Usage, where(path, "", "body of unknown type " + std::to_string(t)));

  tinygltf::Model m;
  m.asset.version = "2.0";
  m.asset.generator = "lrigid " LRIGID_VERSION;
  std::vector<unsigned char> buf;
  constexpr int kArray = TINYGLTF_TARGET_ARRAY_BUFFER,
                kIndex = TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER;
  constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;

  // meshes, one per body type
  for (size_t ti = 0; ti < a.types.size(); ++ti) {
    const TriangleMesh& s = a.types[ti].surface;
    std::vector<float> p;
    p.reserve(3 * s.vertices.size());
    std::vector<double> lo(3, std::numeric_limits<double>::max()), hi(3, -lo[0]);
    for (const Vec3& v : s.vertices)
      for (int k = 0; k < 3; ++k) {
        p.push_back(float(v[k]));
        lo[k] = std::min(lo[k], double(float(v[k])));
        hi[k] = std::max(hi[k], double(float(v[k])));
      }
    std::vector<uint32_t> idx;
    idx.reserve(3 * s.faces.size());
    for (const auto& f : s.faces)
      for (int k = 0; k < 3; ++k) idx.push_back(uint32_t(f[k]));
    const size_t pbytes = p.size() * sizeof(float), ibytes = idx.size() * sizeof(uint32_t);
    const int pv = add_view(&m, append(&buf, p.data(), pbytes), pbytes, kArray);
    const int iv = add_view(&m, append(&buf, idx.data(), ibytes), ibytes, kIndex);
    const int pa = add_accessor(&m, pv, 0, s.vertices.size(), TINYGLTF_TYPE_VEC3, kFloat);
    m.accessors[pa].minValues = lo;
    m.accessors[pa].maxValues = hi;
    const int ia = add_accessor(&m, iv, 0, idx.size(), TINYGLTF_TYPE_SCALAR,
                                TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
    tinygltf::Material mat;
    mat.name = a.types[ti].name;
    double rgb[3];
    type_colour(ti, rgb);
    mat.pbrMetallicRoughness.baseColorFactor = {rgb[0], rgb[1], rgb[2], 1.0};
    mat.pbrMetallicRoughness.metallicFactor = 0.0;
    mat.pbrMetallicRoughness.roughnessFactor = 0.7;
    mat.doubleSided = true;  // thin cards are seen from both sides
    m.materials.push_back(mat);
    tinygltf::Primitive prim;
    prim.attributes["POSITION"] = pa;
    prim.indices = ia;
    prim.material = int(ti);
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    tinygltf::Mesh mesh;
    mesh.name = a.types[ti].name;
    mesh.primitives.push_back(prim);
    m.meshes.push_back(mesh);
  }

  // sample times, shared by every channel
  std::vector<float> times(nf);
  for (size_t f = 0; f < nf; ++f) times[f] = float(a.times[f]);
  const int tv = add_view(&m, append(&buf, times.data(), nf * 4), nf * 4, 0);
  const int ta = add_accessor(&m, tv, 0, nf, TINYGLTF_TYPE_SCALAR, kFloat);
  m.accessors[ta].minValues = {double(times.front())};
  m.accessors[ta].maxValues = {double(times.back())};

  // body-major translations and rotations (glTF quaternion order x, y, z, w)
  std::vector<float> tr(nb * nf * 3), rot(nb * nf * 4);
  for (size_t f = 0; f < nf; ++f)
    for (size_t b = 0; b < nb; ++b) {
      const Vec3& x = a.x[f * nb + b];
      Quat q = a.q[f * nb + b];
      q.normalize();
      // keep consecutive samples in one hemisphere so slerp takes the short way
      if (f > 0) {
        const float* p = &rot[(b * nf + f - 1) * 4];
        if (p[0] * q.x() + p[1] * q.y() + p[2] * q.z() + p[3] * q.w() < 0) q.coeffs() *= -1;
      }
      float* t = &tr[(b * nf + f) * 3];
      t[0] = float(x.x()), t[1] = float(x.y()), t[2] = float(x.z());
      float* r = &rot[(b * nf + f) * 4];
      r[0] = float(q.x()), r[1] = float(q.y()), r[2] = float(q.z()), r[3] = float(q.w());
    }
  const int trv = add_view(&m, append(&buf, tr.data(), tr.size() * 4), tr.size() * 4, 0);
  const int rov = add_view(&m, append(&buf, rot.data(), rot.size() * 4), rot.size() * 4, 0);

  // root node: Z-up -> Y-up
  tinygltf::Node root;
  root.name = "lrigid_world_z_up";
  root.rotation.assign(kGltfRootRotation, kGltfRootRotation + 4);
  m.nodes.push_back(root);
  tinygltf::Animation anim;
  anim.name = "trajectories";
  m.nodes.reserve(nb + 1);
  m.accessors.reserve(m.accessors.size() + 2 * nb);
  for (size_t b = 0; b < nb; ++b) {
    tinygltf::Node n;
    const int type = a.body_type[b];
    n.name = "body_" + std::to_string(b) + "_" + a.types[size_t(type)].name;
    n.mesh = type;
    const float* t = &tr[b * nf * 3];
    const float* r = &rot[b * nf * 4];
    n.translation = {t[0], t[1], t[2]};
    n.rotation = {r[0], r[1], r[2], r[3]};
    m.nodes.push_back(n);
    const int node = int(m.nodes.size()) - 1;
    m.nodes[0].children.push_back(node);
    const int ta_t = add_accessor(&m, trv, b * nf * 12, nf, TINYGLTF_TYPE_VEC3, kFloat);
    const int ta_r = add_accessor(&m, rov, b * nf * 16, nf, TINYGLTF_TYPE_VEC4, kFloat);
    for (const auto& [acc, prop] : {std::pair<int, const char*>{ta_t, "translation"},
                                    std::pair<int, const char*>{ta_r, "rotation"}}) {
      tinygltf::AnimationSampler s;
      s.input = ta;
      s.output = acc;
      s.interpolation = "LINEAR";
      anim.samplers.push_back(s);
      tinygltf::AnimationChannel c;
      c.sampler = int(anim.samplers.size()) - 1;
      c.target_node = node;
      c.target_path = prop;
      anim.channels.push_back(c);
    }
    // a body removed at the grid's edge: scale 0 from then on (a STEP channel)
    bool ever_hidden = false;
    for (size_t f = 0; f < nf && !ever_hidden; ++f) ever_hidden = a.hidden_at(f, b);
    if (ever_hidden) {
      std::vector<float> sc(3 * nf);
      for (size_t f = 0; f < nf; ++f)
        sc[3 * f] = sc[3 * f + 1] = sc[3 * f + 2] = a.hidden_at(f, b) ? 0.f : 1.f;
      const int sv = add_view(&m, append(&buf, sc.data(), sc.size() * 4), sc.size() * 4, 0);
      tinygltf::AnimationSampler s;
      s.input = ta;
      s.output = add_accessor(&m, sv, 0, nf, TINYGLTF_TYPE_VEC3, kFloat);
      s.interpolation = "STEP";
      anim.samplers.push_back(s);
      tinygltf::AnimationChannel c;
      c.sampler = int(anim.samplers.size()) - 1;
      c.target_node = node;
      c.target_path = "scale";
      anim.channels.push_back(c);
      if (a.hidden_at(0, b)) m.nodes[size_t(node)].scale = {0, 0, 0};
    }
  }
  if (nf > 1) m.animations.push_back(anim);
  tinygltf::Buffer buffer;
  buffer.data = std::move(buf);
  m.buffers.push_back(std::move(buffer));
  tinygltf::Scene scene;
  scene.name = "lrigid";
  scene.nodes = {0};
  m.scenes.push_back(scene);
  m.defaultScene = 0;

  write_file_atomically(path, [&](std::ostream& o) {
    tinygltf::TinyGLTF gltf;
    if (!gltf.WriteGltfSceneToStream(&m, o, false, true))
      throw Error(ExitCode::Output, where(path, "", "tinygltf could not serialize the scene"));
  });
}

}  // namespace lrigid
