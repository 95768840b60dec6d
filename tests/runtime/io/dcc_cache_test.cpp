// The caches for DCC tools (io/dcc_cache.h): animation.glb's normals, texture coordinates,
// materials, mesh names and body attributes; animation_instanced.glb's frames of instances; the
// hidden bodies in each cache; the split normals of a thin body.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "body/solidify.h"
#include "io/dcc_cache.h"
#include "io/houdini_writer.h"
#include "io/mesh_io.h"
#include "io/usd_writer.h"
#include "model/state.h"
#include "support/dcc_run.h"
#include "support/gltf_read.h"
#include "support/temp_dir.h"
#include "util/error.h"

namespace lrigid {
namespace {

namespace fs = std::filesystem;
using test::TrajectoryRow;

using test::accessor_data;

tinygltf::Model load(const std::string& path) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model m;
  std::string err, warn;
  EXPECT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, path)) << err;
  return m;
}

// the OBJ's "vt" records
std::set<std::pair<long, long>> obj_uvs(const std::string& path) {
  std::ifstream in(path);
  std::string tag;
  std::set<std::pair<long, long>> out;
  for (std::string line; std::getline(in, line);) {
    std::istringstream s(line);
    double u, v;
    if (s >> tag && tag == "vt" && s >> u >> v) out.insert({std::lround(u * 1e5), std::lround(v * 1e5)});
  }
  return out;
}

struct DccCaches : test::TempDirTest {
  std::vector<TrajectoryRow> rows;
  size_t nb = 5, nf = 0;
  void SetUp() override {
    test::TempDirTest::SetUp();
    test::run_dcc_scene(dir.string(), R"(["csv", "glb", "glb_instanced", "houdini", "usd"])");
    rows = test::read_trajectories((dir / "trajectories.csv").string());
    nf = rows.size() / nb;
  }
  const TrajectoryRow& row(size_t f, size_t b) const { return rows[f * nb + b]; }
};

TEST_F(DccCaches, GltfMeshesHaveSplitNormalsTextureCoordinatesAndAMaterialPerEntry) {
  ASSERT_EQ(nf, 5u);
  const tinygltf::Model m = load((dir / "animation.glb").string());
  std::vector<std::string> meshes, materials;
  for (const auto& x : m.meshes) meshes.push_back(x.name);
  for (const auto& x : m.materials) materials.push_back(x.name);
  EXPECT_EQ(meshes, (std::vector<std::string>{"leaf.0", "leaf.1", "pebble"}));
  EXPECT_EQ(materials, (std::vector<std::string>{"leaf", "pebble"}));
  const auto want_uv = obj_uvs(test::leaf_obj());
  ASSERT_FALSE(want_uv.empty());
  for (const auto& mesh : m.meshes) {
    const auto& prim = mesh.primitives.at(0);
    EXPECT_EQ(m.materials[size_t(prim.material)].name, mesh.name.substr(0, mesh.name.find('.')));
    const auto p = accessor_data<float>(m, prim.attributes.at("POSITION"), 3);
    const auto n = accessor_data<float>(m, prim.attributes.at("NORMAL"), 3);
    const auto idx = accessor_data<uint32_t>(m, prim.indices, 1);
    ASSERT_EQ(n.size(), p.size());
    // unit normals on the side the triangle faces, within the smoothing angle of its own
    size_t corners = 0;
    for (size_t i = 0; i < idx.size(); i += 3) {
      Vec3 c[3], nn[3];
      for (int k = 0; k < 3; ++k) {
        const size_t v = idx[i + size_t(k)];
        c[k] = Vec3(p[3 * v], p[3 * v + 1], p[3 * v + 2]);
        nn[k] = Vec3(n[3 * v], n[3 * v + 1], n[3 * v + 2]);
      }
      const Vec3 face = (c[1] - c[0]).cross(c[2] - c[0]);
      if (face.norm() < 1e-14) continue;
      for (const Vec3& x : nn) {
        EXPECT_NEAR(x.norm(), 1.0, 1e-5);
        EXPECT_GT(x.dot(face.normalized()), std::cos(kSmoothAngleDeg * M_PI / 180) - 1e-5);
        ++corners;
      }
    }
    EXPECT_GT(corners, 0u);
    if (mesh.name == "pebble") {
      EXPECT_EQ(prim.attributes.count("TEXCOORD_0"), 0u) << "a sphere has no texture coordinates";
      continue;
    }
    // the OBJ's coordinates, all of them (both sides of the leaf), with glTF's t = 1 - v
    const auto t = accessor_data<float>(m, prim.attributes.at("TEXCOORD_0"), 2);
    ASSERT_EQ(t.size() / 2, p.size() / 3);
    std::set<std::pair<long, long>> got;
    for (size_t i = 0; i < t.size(); i += 2)
      got.insert({std::lround(t[i] * 1e5), std::lround((1 - t[i + 1]) * 1e5)});
    for (const auto& g : got) EXPECT_TRUE(want_uv.count(g)) << g.first << " " << g.second;
    EXPECT_EQ(got.size(), want_uv.size());
  }
}

TEST_F(DccCaches, GltfBodyNodesCarryTheirAttributesAndStates) {
  const tinygltf::Model m = load((dir / "animation.glb").string());
  ASSERT_EQ(m.nodes.size(), nb + 1);
  for (size_t b = 0; b < nb; ++b) {
    const tinygltf::Node& n = m.nodes[b + 1];
    ASSERT_TRUE(n.extras.IsObject()) << n.name;
    EXPECT_EQ(n.extras.Get("id").GetNumberAsInt(), int(b));
    EXPECT_EQ(n.extras.Get("entry").Get<std::string>(), row(0, b).type);
    const std::string mesh = m.meshes[size_t(n.mesh)].name;
    const int variant = n.extras.Get("variant").GetNumberAsInt();
    EXPECT_EQ(mesh, row(0, b).type == "pebble" ? "pebble" : "leaf." + std::to_string(variant));
    EXPECT_EQ(n.name, "body_" + std::to_string(b) + "_" + mesh);
    // [t, state] at the first frame and at each change, as trajectories.csv has them
    std::vector<std::pair<double, std::string>> want;
    for (size_t f = 0; f < nf; ++f)
      if (want.empty() || want.back().second != row(f, b).state)
        want.emplace_back(row(f, b).t, row(f, b).state);
    const tinygltf::Value& s = n.extras.Get("states");
    ASSERT_EQ(s.ArrayLen(), want.size());
    for (size_t i = 0; i < want.size(); ++i) {
      EXPECT_NEAR(s.Get(int(i)).Get(0).GetNumberAsDouble(), want[i].first, 1e-9);
      EXPECT_EQ(s.Get(int(i)).Get(1).Get<std::string>(), want[i].second);
    }
  }
}

TEST_F(DccCaches, InstancedGltfHoldsEachFramesBodiesAndShowsOneFrameAtATime) {
  const tinygltf::Model m = load((dir / "animation_instanced.glb").string());
  EXPECT_EQ(m.extensionsRequired, std::vector<std::string>{"EXT_mesh_gpu_instancing"});
  const tinygltf::Node& root = m.nodes[0];
  ASSERT_EQ(root.children.size(), nf);
  std::map<int, const tinygltf::AnimationSampler*> scale_of;
  for (const auto& c : m.animations.at(0).channels) {
    ASSERT_EQ(c.target_path, "scale");
    scale_of[c.target_node] = &m.animations[0].samplers[size_t(c.sampler)];
  }
  for (size_t f = 0; f < nf; ++f) {
    const int fn = root.children[f];
    // shown (1) from its own time, hidden (0) from the next frame's and before
    const auto* s = scale_of.at(fn);
    EXPECT_EQ(s->interpolation, "STEP");
    const auto t = accessor_data<float>(m, s->input, 1);
    const auto v = accessor_data<float>(m, s->output, 3);
    for (size_t k = 0; k < t.size(); ++k)
      EXPECT_EQ(v[3 * k], std::abs(t[k] - row(f, 0).t) < 1e-6 ? 1.f : 0.f) << f << " " << k;
    std::set<size_t> seen;
    for (int child : m.nodes[size_t(fn)].children) {
      const tinygltf::Node& n = m.nodes[size_t(child)];
      const tinygltf::Value& a = n.extensions.at("EXT_mesh_gpu_instancing").Get("attributes");
      const auto x = accessor_data<float>(m, a.Get("TRANSLATION").GetNumberAsInt(), 3);
      const auto q = accessor_data<float>(m, a.Get("ROTATION").GetNumberAsInt(), 4);
      const auto id = accessor_data<float>(m, a.Get("_ID").GetNumberAsInt(), 1);
      for (size_t i = 0; i < id.size(); ++i) {
        const TrajectoryRow& r = row(f, size_t(id[i]));
        seen.insert(size_t(id[i]));
        EXPECT_TRUE(test::near(Vec3(x[3 * i], x[3 * i + 1], x[3 * i + 2]), r.x, 1e-6));
        const Quat g(q[4 * i + 3], q[4 * i], q[4 * i + 1], q[4 * i + 2]);
        EXPECT_TRUE(test::near(g.toRotationMatrix(), r.q.toRotationMatrix(), 2e-6));
      }
    }
    EXPECT_EQ(seen.size(), nb) << "frame " << f;
  }
}

// two bodies, three frames, the second hidden from frame 1 on
GltfAnimation hidden_animation() {
  GltfAnimation a;
  TriangleMesh box = read_mesh(std::string(LRIGID_SOURCE_DIR) + "/tests/data/meshes/tetra.obj");
  a.types.push_back({"chip", box, 0, 0});
  a.body_type = {0, 0};
  a.times = {0, 0.5, 1};
  for (size_t f = 0; f < 3; ++f)
    for (size_t b = 0; b < 2; ++b) {
      a.x.emplace_back(double(f), double(b), 0);
      a.q.push_back(Quat(Eigen::AngleAxisd(0.3 * double(f + b), Vec3::UnitZ())));
      a.v.emplace_back(1, 0, 0);
      a.w.emplace_back(0, 0, 0.3);
      a.hidden.push_back(b == 1 && f >= 1);
      a.state.push_back(uint8_t(b == 1 && f >= 1 ? state_code_from_name("exited") : 0));
    }
  return a;
}

struct DccFiles : test::TempDirTest {};

TEST_F(DccFiles, HiddenBodiesStayHiddenInEveryCache) {
  const GltfAnimation a = hidden_animation();
  const std::string d = dir.string();
  write_gltf(d + "/a.glb", a);
  write_gltf(d + "/i.glb", a, GltfLayout::Instanced);
  write_houdini_csv(d + "/h.csv", a);
  write_usd(d + "/b.usda", a);
  // animated: the hidden body's scale 0 from frame 1 on (a STEP channel), the other's none
  const tinygltf::Model m = load(d + "/a.glb");
  size_t scales = 0;
  for (const auto& c : m.animations.at(0).channels)
    if (c.target_path == "scale") {
      ++scales;
      EXPECT_EQ(c.target_node, 2);
      const auto v = accessor_data<float>(m, m.animations[0].samplers[size_t(c.sampler)].output, 3);
      EXPECT_EQ(v, (std::vector<float>{1, 1, 1, 0, 0, 0, 0, 0, 0}));
    }
  EXPECT_EQ(scales, 1u);
  // instanced: frames 1 and 2 hold body 0 only
  const tinygltf::Model mi = load(d + "/i.glb");
  for (size_t f = 0; f < 3; ++f) {
    const auto& fn = mi.nodes[size_t(mi.nodes[0].children[f])];
    ASSERT_EQ(fn.children.size(), 1u);
    const auto& n = mi.nodes[size_t(fn.children[0])];
    const auto id = accessor_data<float>(
        mi, n.extensions.at("EXT_mesh_gpu_instancing").Get("attributes").Get("_ID").GetNumberAsInt(),
        1);
    EXPECT_EQ(id, (f == 0 ? std::vector<float>{0, 1} : std::vector<float>{0}));
  }
  // Houdini: the hidden body's rows are left out
  std::ifstream h(d + "/h.csv");
  std::string line;
  std::getline(h, line);
  EXPECT_EQ(line, kHoudiniHeader);
  std::vector<std::string> frame_id;  // "frame,time,id" of each row, less the time
  while (std::getline(h, line)) {
    const size_t c1 = line.find(','), c2 = line.find(',', c1 + 1), c3 = line.find(',', c2 + 1);
    frame_id.push_back(line.substr(0, c1) + "," + line.substr(c2 + 1, c3 - c2 - 1));
  }
  EXPECT_EQ(frame_id, (std::vector<std::string>{"1,0", "1,1", "2,0", "3,0"}));
  // USD: invisibleIds names it at times 1 and 2 (frames 0.5 s apart)
  std::ifstream u(d + "/b.usda");
  std::stringstream all;
  all << u.rdbuf();
  const std::string usda = all.str();
  const size_t at = usda.find("int64[] invisibleIds.timeSamples = {");
  ASSERT_NE(at, std::string::npos);
  EXPECT_NE(usda.find("0: [],\n            1: [1],\n            2: [1],", at), std::string::npos)
      << usda.substr(at, 200);
}

TEST_F(DccFiles, CachesRefuseAnimationsWithoutVelocities) {
  GltfAnimation a = hidden_animation();
  a.v.clear();
  for (auto* write : {write_houdini_csv, write_usd}) {
    try {
      write((dir / "x").string(), a);
      FAIL() << "no error";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ExitCode::Usage);
      EXPECT_NE(std::string(e.what()).find("velocities"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(dir / "x"));
  }
  write_gltf((dir / "x.glb").string(), a);  // the glTF needs none
  EXPECT_TRUE(fs::exists(dir / "x.glb"));
}

TEST(DccMesh, CornerNormalsAreSmoothOnACurvedSideAndSplitBetweenTheSides) {
  TriangleMesh leaf = read_mesh(test::leaf_obj());
  ASSERT_TRUE(leaf.has_uv());
  const TriangleMesh body = solidify_surface(leaf, 0.001, "leaf");
  ASSERT_TRUE(body.has_uv());
  const std::vector<Vec3> n = corner_normals(body);
  ASSERT_EQ(n.size(), 3 * body.faces.size());
  const size_t nf = leaf.faces.size();
  // face i of the surface (+ side) and its copy nf + i (- side) share their vertices' positions
  // but not their normals: each side's normals point its own way
  size_t smooth = 0;
  for (size_t i = 0; i < nf; ++i)
    for (int k = 0; k < 3; ++k) {
      EXPECT_LT(n[3 * i + size_t(k)].dot(n[3 * (nf + i) + size_t(k == 0 ? 0 : 3 - k)]), -0.5);
      const auto& f = body.faces[i];
      const Vec3 own = (body.vertices[f[1]] - body.vertices[f[0]])
                           .cross(body.vertices[f[2]] - body.vertices[f[0]])
                           .normalized();
      smooth += n[3 * i + size_t(k)].dot(own) < 1 - 1e-9;  // averaged with its neighbours
    }
  EXPECT_GT(smooth, nf);  // the bent leaf is shaded smoothly, not face by face
  // the - side's texture coordinates are the surface's (the texture seen from below)
  for (size_t i = 0; i < nf; ++i) {
    EXPECT_EQ(body.uv[nf + i][0], leaf.uv[i][0]);
    EXPECT_EQ(body.uv[nf + i][1], leaf.uv[i][2]);
  }
}

}  // namespace
}  // namespace lrigid
