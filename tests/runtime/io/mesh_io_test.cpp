// Mesh readers and writers (runtime/src/io/mesh_io.cpp) on the files in tests/data/meshes/.
#include "io/mesh_io.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "body/mass_properties.h"
#include "body/mesh_check.h"
#include "body/tessellate.h"
#include "util/error.h"

namespace lrigid {
namespace {

namespace fs = std::filesystem;

std::string data(const std::string& name) {
  return std::string(LRIGID_SOURCE_DIR) + "/tests/data/meshes/" + name;
}

// error text of read_mesh + from_mesh, "" if both succeed
std::string load_error(const std::string& name, ExitCode* code = nullptr) {
  try {
    auto m = std::make_shared<const TriangleMesh>(read_mesh(data(name)));
    Shape::from_mesh(m, data(name));
  } catch (const Error& e) {
    if (code) *code = e.code();
    return e.what();
  }
  return "";
}

TEST(MeshIo, StlAsciiAndBinaryGiveTheSameClosedBox) {
  for (const char* name : {"box_ascii.stl", "box_binary.stl"}) {
    const TriangleMesh m = read_mesh(data(name));
    EXPECT_EQ(m.vertices.size(), 8u) << name << ": corners are merged";
    EXPECT_EQ(m.faces.size(), 12u) << name;
    EXPECT_TRUE(check_mesh(m).ok()) << name << ": " << check_mesh(m).message;
    const MassProperties mp = mass_properties(m);
    EXPECT_NEAR(mp.volume, 0.2 * 0.1 * 0.05, 1e-8) << name;  // float32 in the binary file
    EXPECT_LT((mp.centroid - Vec3(1, 2, 3)).norm(), 1e-6) << name;
    EXPECT_NEAR(mp.inertia(2, 2), 1e-3 * (0.04 + 0.01) / 12, 1e-10) << name;
  }
}

TEST(MeshIo, ObjQuadsAndSlashIndices) {
  const TriangleMesh m = read_mesh(data("cube_quads.obj"));
  EXPECT_EQ(m.vertices.size(), 8u);
  EXPECT_EQ(m.faces.size(), 12u);  // 6 quads fan-triangulated
  const MassProperties mp = mass_properties(m);
  EXPECT_NEAR(mp.volume, 1.0, 1e-14);
  EXPECT_LT((mp.centroid - Vec3::Constant(0.5)).norm(), 1e-14);
  const TriangleMesh t = read_mesh(data("tetra.obj"));
  EXPECT_NEAR(mass_properties(t).volume, 1.0 / 6.0, 1e-15);
}

TEST(MeshIo, InvalidMeshesAreRefusedSayingWhy) {
  struct Case {
    const char* file;
    const char* says;
  };
  for (const Case& c :
       {Case{"open.obj", "open"}, Case{"inverted.obj", "inverted"},
        Case{"inconsistent.obj", "inconsistent"}, Case{"nonmanifold_edge.obj", "non-manifold"},
        Case{"nonmanifold_vertex.obj", "non-manifold at vertex 0"},
        Case{"degenerate.obj", "zero area"}}) {
    ExitCode code = ExitCode::Ok;
    const std::string e = load_error(c.file, &code);
    EXPECT_EQ(code, ExitCode::BadInput) << c.file;
    EXPECT_NE(e.find(c.says), std::string::npos) << c.file << ": " << e;
    EXPECT_NE(e.find(c.file), std::string::npos) << "names the file: " << e;
  }
}

TEST(MeshIo, HugeCoordinatesNamedAsSuch) {
  // 1e200 squared overflowed and the mesh checks said "face 0 has zero area"
  ExitCode code = ExitCode::Ok;
  const std::string e = load_error("huge_coordinates.obj", &code);
  EXPECT_EQ(code, ExitCode::BadInput) << e;
  EXPECT_NE(e.find("huge_coordinates.obj: vertex 1 (1e+200, 0, 0): coordinates must be in "
                   "[-1e15, 1e15]"),
            std::string::npos)
      << e;
}

TEST(MeshIo, SyntaxErrorsNameFileAndLine) {
  const std::string num = load_error("bad_number.obj");
  EXPECT_NE(num.find("bad_number.obj: line 3"), std::string::npos) << num;
  EXPECT_NE(num.find("'x'"), std::string::npos) << num;
  const std::string idx = load_error("bad_index.obj");
  EXPECT_NE(idx.find("line 4"), std::string::npos) << idx;
  EXPECT_NE(idx.find("7"), std::string::npos) << idx;
  const std::string tr = load_error("truncated.stl");
  EXPECT_NE(tr.find("truncated.stl"), std::string::npos) << tr;
  EXPECT_NE(tr.find("facet"), std::string::npos) << tr;
  EXPECT_NE(load_error("does_not_exist.obj").find("does not exist"), std::string::npos);
  EXPECT_NE(load_error("make_meshes.py").find("unknown mesh format"), std::string::npos);
}

TEST(MeshIo, ObjForwardAndNegativeIndices) {
  const fs::path f =
      fs::temp_directory_path() / ("lrigid_fwd_" + std::to_string(::getpid()) + ".obj");
  {
    std::ofstream out(f);
    out << "f 1 3 2\nf 1 2 4\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf -4 -1 -2\nf 2 3 4\n";
  }
  const TriangleMesh m = read_mesh(f.string());
  fs::remove(f);
  ASSERT_EQ(m.faces.size(), 4u);
  EXPECT_EQ(m.faces[2], (std::array<int, 3>{0, 3, 2}));
  EXPECT_NEAR(mass_properties(m).volume, 1.0 / 6.0, 1e-15);
}

// "vt" texture coordinates become each face corner's uv, fan-triangulated with the faces; the
// physics' vertices and faces are those of the file without them
TEST(MeshIo, ObjTextureCoordinatesFollowTheFaces) {
  const fs::path f =
      fs::temp_directory_path() / ("lrigid_vt_" + std::to_string(::getpid()) + ".obj");
  const std::string quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  {
    std::ofstream out(f);
    out << quad << "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1 4/-1/1\n";
  }
  TriangleMesh m = read_mesh(f.string());
  ASSERT_EQ(m.faces.size(), 2u);
  ASSERT_TRUE(m.has_uv());
  EXPECT_EQ(m.uv[1][0], Vec2(0, 0));
  EXPECT_EQ(m.uv[1][1], Vec2(1, 1));
  EXPECT_EQ(m.uv[1][2], Vec2(0, 1));  // -1: the last vt so far
  // a face without texture coordinates: the mesh has none
  { std::ofstream(f) << quad << "vt 0 0\nf 1/1 2/1 3/1\nf 1 3 4\n"; }
  m = read_mesh(f.string());
  EXPECT_EQ(m.faces.size(), 2u);
  EXPECT_FALSE(m.has_uv());
  // an index past the vt records: refused, naming the file, the line and the count
  { std::ofstream(f) << quad << "vt 0 0\nf 1/1 2/1 3/5\n"; }
  std::string e;
  try {
    read_mesh(f.string());
  } catch (const Error& err) {
    e = err.what();
  }
  EXPECT_NE(e.find(f.string() + ": line 6: texture index 5 but the file has 1 texture "
                               "coordinates (vt)"), std::string::npos) << e;
  fs::remove(f);
  // the leaf of the tests, as Blender exports it: every corner has its coordinates, in [0, 1]
  const TriangleMesh leaf = read_mesh(std::string(LRIGID_SOURCE_DIR) +
                                      "/tests/data/meshes/leaf_surface.obj");
  ASSERT_TRUE(leaf.has_uv());
  for (const auto& face : leaf.uv)
    for (const Vec2& t : face) EXPECT_TRUE(t.minCoeff() >= 0 && t.maxCoeff() <= 1);
  // subdividing splits them with the faces
  const TriangleMesh fine = subdivide(leaf);
  ASSERT_TRUE(fine.has_uv());
  EXPECT_EQ(fine.uv[3][0], 0.5 * (leaf.uv[0][0] + leaf.uv[0][1]));
}

TEST(MeshIo, WriteAndReadBack) {
  const fs::path dir = fs::temp_directory_path() / ("lrigid_mesh_io_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const TriangleMesh m = tessellate(Shape::ellipsoid(0.3, 0.2, 0.1), 320);
  const double v = mass_properties(m).volume;
  write_obj((dir / "e.obj").string(), m);
  write_stl_ascii((dir / "e.stl").string(), m, "ellipsoid");
  write_stl_binary((dir / "eb.stl").string(), m);
  const TriangleMesh a = read_mesh((dir / "e.obj").string());
  const TriangleMesh b = read_mesh((dir / "e.stl").string());
  const TriangleMesh c = read_mesh((dir / "eb.stl").string());
  for (const TriangleMesh* r : {&a, &b, &c}) {
    EXPECT_EQ(r->faces.size(), m.faces.size());
    EXPECT_EQ(r->vertices.size(), m.vertices.size());
    EXPECT_TRUE(check_mesh(*r).ok());
  }
  EXPECT_NEAR(mass_properties(a).volume, v, 1e-14);
  EXPECT_NEAR(mass_properties(b).volume, v, 1e-14);
  EXPECT_NEAR(mass_properties(c).volume, v, 1e-7);  // float32
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lrigid
