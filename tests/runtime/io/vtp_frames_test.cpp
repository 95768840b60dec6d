// The ParaView series' frames (io/vtp_frames.h): a box's series surface is its exact
// closed surface, outward (12 triangles); frames read back with VTK's reader hold the state;
// a frame's file depends only on the state written, not on how many frames the writer wrote
// before (VTK caches array ranges in kept arrays: the first frame of a process differed from the
// later ones, and a resumed run from an uninterrupted one).
#include <gtest/gtest.h>
#include <unistd.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "io/vtp_frames.h"
#include "support/fixture.h"

namespace fs = std::filesystem;

namespace lrigid {
namespace {

std::string slurp(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(VtpFrames, ABoxSeriesSurfaceIsItsExactClosedOutwardSurface) {
  BodyType t;
  t.shape = Shape::box(0.06, 0.04, 0.002);
  t.com = Vec3(0.001, 0, 0);
  const TriangleMesh m = series_surface(t, 320);
  ASSERT_EQ(m.faces.size(), 12u);
  ASSERT_EQ(m.vertices.size(), 8u);
  // volume by the divergence theorem: positive (outward) and the box's; every edge shared by
  // exactly two faces in opposite directions (closed)
  double v = 0;
  std::map<std::pair<int, int>, int> edges;
  for (const auto& f : m.faces) {
    v += m.vertices[f[0]].dot(m.vertices[f[1]].cross(m.vertices[f[2]])) / 6;
    for (int k = 0; k < 3; ++k) ++edges[{f[k], f[(k + 1) % 3]}];
  }
  EXPECT_NEAR(v, 0.06 * 0.04 * 0.002, 1e-12);
  for (const auto& [e, n] : edges) {
    EXPECT_EQ(n, 1);
    EXPECT_EQ(edges.count({e.second, e.first}), 1u) << e.first << "-" << e.second;
  }
  // the body frame: centred on the centre of mass
  Vec3 lo = Vec3::Constant(1e9), hi = -lo;
  for (const Vec3& p : m.vertices) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  EXPECT_NEAR(lo.x(), -0.03 - 0.001, 1e-12);
  EXPECT_NEAR(hi.x(), 0.03 - 0.001, 1e-12);
}

TEST(VtpFrames, AFrameDependsOnlyOnTheStateAndReadsBack) {
  const Scene scene = test::sphere_scene(0.01, 1000, 1.2, 1.5e-5, 5);
  const Model model = test::compile(scene);
  State st = initial_state(model, scene);
  for (size_t i = 0; i < st.size(); ++i) st.x[i] = Vec3(double(i), 2, 3), st.v[i] = Vec3(0, 0, -double(i));
  const fs::path dir = fs::temp_directory_path() / ("vtp_frames_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  // writer a: frames 1, 2, then 1 again; writer b: only 1. The files of state 1 are identical.
  BodiesFrames a(model), b(model);
  State st2 = st;
  st2.x[0] = Vec3(-1, -1, -1);
  a.write(st, (dir / "a1.vtp").string());
  a.write(st2, (dir / "a2.vtp").string());
  a.write(st, (dir / "a3.vtp").string());
  b.write(st, (dir / "b1.vtp").string());
  EXPECT_EQ(slurp((dir / "a1.vtp").string()), slurp((dir / "a3.vtp").string()));
  EXPECT_EQ(slurp((dir / "a1.vtp").string()), slurp((dir / "b1.vtp").string()));
  EXPECT_NE(slurp((dir / "a1.vtp").string()), slurp((dir / "a2.vtp").string()));
  vtkNew<vtkXMLPolyDataReader> r;
  r->SetFileName((dir / "a2.vtp").string().c_str());
  r->Update();
  vtkPolyData* p = r->GetOutput();
  ASSERT_EQ(p->GetNumberOfPoints(), 5);
  double x[3];
  p->GetPoint(0, x);
  EXPECT_EQ(x[0], -1.0);
  p->GetPoint(4, x);
  EXPECT_EQ(x[0], 4.0);
  vtkDataArray* v = p->GetPointData()->GetArray("velocity");
  ASSERT_NE(v, nullptr);
  EXPECT_EQ(v->GetComponent(3, 2), -3.0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lrigid
