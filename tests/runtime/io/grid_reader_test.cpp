// The grid reader loads foam2grid's format and rejects grids the runtime cannot trust, naming
// the file, the array and the point.
#include "io/grid_reader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

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

}  // namespace
}  // namespace lrigid
