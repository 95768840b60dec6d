// The grid reader loads foam2grid's format and rejects grids the runtime cannot trust, naming
// the file, the array and the point.
#include "io/grid_reader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "io/field_loader.h"
#include "support/vti_writer.h"
#include "util/error.h"

namespace lrigid {
namespace {

namespace fs = std::filesystem;

std::string tmpdir() {
  const fs::path d = fs::temp_directory_path() / ("lrigid_grid_test_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d.string();
}

// writes a 4 x 3 x 2 grid with U = (x, 0, 0), k = k_value, eps = 0.01; one value may be spoilt
void write_grid(const std::string& path, double time, float k_value = 0.1f, int bad_point = -1,
                float bad_value = 0, const char* bad_array = "k", bool with_epsilon = true) {
  test::VtiGrid g;
  g.dims = {4, 3, 2};
  g.origin = {1, 2, 3};
  g.spacing = {0.5, 0.5, 1};
  g.time = time;
  g.with_epsilon = with_epsilon;
  const std::string bad = bad_array;
  ASSERT_TRUE(test::write_vti(path, g, [&](int p, const std::array<double, 3>& x, float U[3],
                                           float* k, float* eps) {
    U[0] = float(x[0]);
    *k = k_value;
    *eps = 0.01f;
    if (p != bad_point) return;
    if (bad == "k") *k = bad_value;
    if (bad == "epsilon") *eps = bad_value;
    if (bad == "U") U[0] = bad_value;
  }));
}

std::string error_of(const std::string& path) {
  try {
    read_grid(path);
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::BadInput);
    return e.what();
  }
  return "";
}

TEST(GridReader, ReadsGeometryFieldsAndViscosity) {
  const std::string f = tmpdir() + "/ok.vti";
  write_grid(f, 0);
  const GridFile g = read_grid(f);
  EXPECT_EQ(g.geometry.n[0], 4);
  EXPECT_EQ(g.geometry.n[2], 2);
  EXPECT_EQ(g.geometry.origin, Vec3(1, 2, 3));
  EXPECT_EQ(g.geometry.spacing, Vec3(0.5, 0.5, 1));
  EXPECT_DOUBLE_EQ(g.kinematic_viscosity, 1.5e-5);
  ASSERT_EQ(g.frames.size(), 1u);
  EXPECT_FLOAT_EQ(g.frames[0].U[3 * 3], 2.5f);  // point (3,0,0): x = 2.5
}

TEST(GridReader, ReadsAPvdSeriesInTimeOrder) {
  const std::string d = tmpdir();
  fs::create_directories(d + "/s_vti");
  write_grid(d + "/s_vti/a.vti", 0.0, 0.1f);
  write_grid(d + "/s_vti/b.vti", 0.5, 0.2f);
  std::ofstream(d + "/s.pvd") << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\">\n"
                                 "<Collection>\n<DataSet timestep=\"0.5\" file=\"s_vti/b.vti\"/>\n"
                                 "<DataSet file=\"s_vti/a.vti\" timestep=\"0\"/>\n"
                                 "</Collection></VTKFile>\n";
  const GridFile g = read_grid(d + "/s.pvd");
  ASSERT_EQ(g.frames.size(), 2u);
  EXPECT_EQ(g.frames[0].time, 0.0);
  EXPECT_EQ(g.frames[1].time, 0.5);
  EXPECT_FLOAT_EQ(g.frames[1].k[0], 0.2f);
}

TEST(GridReader, RejectsNaNNegativeMissingAndEmpty) {
  const std::string d = tmpdir();
  write_grid(d + "/nan.vti", 0, 0.1f, 7, std::nanf(""), "k");
  EXPECT_NE(error_of(d + "/nan.vti").find("nan.vti: k: non-finite value at point 7"),
            std::string::npos)
      << error_of(d + "/nan.vti");
  write_grid(d + "/negk.vti", 0, 0.1f, 5, -0.3f, "k");
  EXPECT_NE(error_of(d + "/negk.vti").find("k: negative value -0.3 at point 5"), std::string::npos);
  write_grid(d + "/nege.vti", 0, 0.1f, 2, -1e-3f, "epsilon");
  EXPECT_NE(error_of(d + "/nege.vti").find("epsilon: negative value"), std::string::npos);
  write_grid(d + "/infu.vti", 0, 0.1f, 1, INFINITY, "U");
  EXPECT_NE(error_of(d + "/infu.vti").find("U: non-finite value at point 1"), std::string::npos);
  write_grid(d + "/noeps.vti", 0, 0.1f, -1, 0, "k", false);
  EXPECT_NE(error_of(d + "/noeps.vti").find("epsilon: point array missing"), std::string::npos);
  EXPECT_NE(error_of(d + "/none.vti").find("none.vti: grid file not found"), std::string::npos);
  std::ofstream(d + "/garbage.vti") << "not xml at all";
  EXPECT_NE(error_of(d + "/garbage.vti").find("garbage.vti"), std::string::npos);
  std::ofstream(d + "/empty.pvd")
      << "<VTKFile type=\"Collection\"><Collection></Collection></VTKFile>";
  EXPECT_NE(error_of(d + "/empty.pvd").find("the series is empty"), std::string::npos);
}

// the plane z = 3.4 m as the wall, solid below (as foam2grid writes it: negative in the solid)
test::VtiGrid walled_grid(double time) {
  test::VtiGrid g;
  g.dims = {4, 3, 3};
  g.origin = {1, 2, 3};
  g.spacing = {0.5, 0.5, 0.5};
  g.time = time;
  g.solid = [](const std::array<double, 3>& x) { return x[2] < 3.4; };
  g.wall_distance = [](const std::array<double, 3>& x) { return float(x[2] - 3.4); };
  return g;
}

void write_walled(const std::string& path, double time, bool with_wall = true,
                  float bad = 0) {
  test::VtiGrid g = walled_grid(time);
  if (!with_wall) g.wall_distance = nullptr;
  if (bad != 0) g.wall_distance = [bad](const std::array<double, 3>&) { return bad; };
  ASSERT_TRUE(test::write_vti(path, g, [](int, const std::array<double, 3>&, float U[3],
                                          float* k, float* eps) {
    U[0] = 1;
    *k = 0.1f;
    *eps = 0.01f;
  }));
}

TEST(GridReader, ReadsTheWallDistanceAndRejectsBadOnes) {
  const std::string d = tmpdir();
  write_walled(d + "/wall.vti", 0);
  const GridFile g = read_grid(d + "/wall.vti");
  ASSERT_EQ(g.frames[0].wall_distance.size(), g.geometry.points());
  // point (0, 0, 2) lies at z = 4: 0.6 m above the wall; (0, 0, 0) at z = 3, 0.4 m inside
  const size_t top = 2 * 4 * 3;
  EXPECT_FLOAT_EQ(g.frames[0].wall_distance[top], 0.6f);
  EXPECT_FLOAT_EQ(g.frames[0].wall_distance[0], -0.4f);
  write_walled(d + "/old.vti", 0, false);
  EXPECT_TRUE(read_grid(d + "/old.vti").frames[0].wall_distance.empty());
  write_walled(d + "/nan.vti", 0, true, std::nanf(""));
  EXPECT_NE(error_of(d + "/nan.vti").find("nan.vti: wall_distance: non-finite value at point 0"),
            std::string::npos)
      << error_of(d + "/nan.vti");
  // a series whose frames disagree names the frame and the array
  fs::create_directories(d + "/mix_vti");
  write_walled(d + "/mix_vti/a.vti", 0);
  write_walled(d + "/mix_vti/b.vti", 1, false);
  std::ofstream(d + "/mix.pvd") << "<VTKFile type=\"Collection\"><Collection>\n"
                                   "<DataSet timestep=\"0\" file=\"mix_vti/a.vti\"/>\n"
                                   "<DataSet timestep=\"1\" file=\"mix_vti/b.vti\"/>\n"
                                   "</Collection></VTKFile>\n";
  const std::string e = error_of(d + "/mix.pvd");
  EXPECT_NE(e.find("b.vti: wall_distance: point array missing"), std::string::npos) << e;
}

// lrigid says once, on stderr, that a grid without wall_distance falls back to the valid mask;
// a grid with it loads silently, and the sample carries it
TEST(FieldLoader, SaysOnceWhenTheGridHasNoWallDistance) {
  const std::string d = tmpdir();
  write_walled(d + "/old.vti", 0, false);
  write_walled(d + "/new.vti", 0);
  Scene s;
  s.file = d + "/scene.json";
  s.uniform_field = false;
  s.kinematic_viscosity = 1.5e-5;
  s.field_path = d + "/old.vti";
  testing::internal::CaptureStderr();
  const FluidField old = load_field(s);
  const std::string said = testing::internal::GetCapturedStderr();
  EXPECT_NE(said.find("old.vti has no point array wall_distance"), std::string::npos) << said;
  EXPECT_EQ(said.find("wall_distance"), said.rfind("wall_distance")) << "said more than once";
  EXPECT_FALSE(old.has_wall_distance());
  FluidSample a;
  ASSERT_TRUE(old.sample(Vec3(1.5, 2.5, 3.9), 0, false, &a));
  EXPECT_EQ(a.wall_distance, HUGE_VAL);  // today's behaviour: no wall but the valid mask

  s.field_path = d + "/new.vti";
  testing::internal::CaptureStderr();
  const FluidField now = load_field(s);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  EXPECT_TRUE(now.has_wall_distance());
  FluidSample b;
  ASSERT_TRUE(now.sample(Vec3(1.5, 2.5, 3.9), 0, false, &b));
  EXPECT_NEAR(b.wall_distance, 0.5, 1e-6);
}

}  // namespace
namespace {
// the grid written by write_grid with `from` in its header replaced by `to`
std::string with_header_edit(const std::string& d, const std::string& name, const std::string& from,
                             const std::string& to) {
  const std::string path = d + "/" + name;
  write_grid(path, 0);
  std::ifstream in(path, std::ios::binary);
  std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  std::ofstream(path, std::ios::binary) << s;
  return path;
}
}  // namespace

TEST(GridReader, RefusesEditedHeaders) {
  const std::string d = tmpdir();
  // VTK read the letter as 0 and sheared the grid; a shortened extent rescaled the data
  std::string p = with_header_edit(d, "letter.vti", "Spacing=\"0.5 0.5 1\"", "Spacing=\"0.5 0.x 1\"");
  EXPECT_NE(error_of(p).find("letter.vti: Spacing: expected 3 finite numbers, got \"0.5 0.x 1\""),
            std::string::npos)
      << error_of(p);
  p = with_header_edit(d, "short.vti", "WholeExtent=\"0 3 0 2 0 1\"", "WholeExtent=\"0 3 0 2 0\"");
  EXPECT_NE(error_of(p).find("short.vti: WholeExtent: expected 6 numbers"), std::string::npos)
      << error_of(p);
  p = with_header_edit(d, "piece.vti", "WholeExtent=\"0 3 0 2 0 1\"", "WholeExtent=\"0 2 0 2 0 1\"");
  EXPECT_NE(error_of(p).find("piece.vti: Extent: the piece's extent differs"), std::string::npos)
      << error_of(p);
}

TEST(GridReader, AHugeExtentIsAResourceLimitNotBadAlloc) {
  const std::string d = tmpdir();
  const std::string p = with_header_edit(d, "huge.vti", "WholeExtent=\"0 3 0 2 0 1\"",
                                         "WholeExtent=\"0 99999 0 99999 0 99999\"");
  // the piece keeps its small extent, so make it agree: only the point count is at fault
  std::ifstream in(p, std::ios::binary);
  std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  const size_t at = s.find("Extent=\"0 3 0 2 0 1\"");
  ASSERT_NE(at, std::string::npos);
  s.replace(at, 20, "Extent=\"0 99999 0 99999 0 99999\"");
  std::ofstream(p, std::ios::binary) << s;
  try {
    read_grid(p);
    ADD_FAILURE() << "read";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::Resource) << e.what();
    EXPECT_NE(std::string(e.what()).find("huge.vti: WholeExtent needs 1e+15 points"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace lrigid
