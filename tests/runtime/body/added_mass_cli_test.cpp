// lrigid added-mass, run as a program (runtime/app/cmd_added_mass.cpp).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "body/added_mass.h"
#include "io/mesh_io.h"
#include "util/types.h"

namespace {

using lrigid::Mat6;
using lrigid::Vec3;

namespace fs = std::filesystem;

struct CmdResult {
  int status = -1;
  std::string out;  // stdout and stderr together
};

CmdResult run(const std::string& args, const std::string& env = "") {
  const std::string cmd =
      env + " " + std::string(LRIGID_BINARY_DIR) + "/bin/lrigid added-mass " + args + " 2>&1";
  CmdResult r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  const int st = pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

TEST(AddedMassCli, SphereJson) {
  const CmdResult r = run("--sphere 0.1 --json");
  ASSERT_EQ(r.status, 0) << r.out;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  const double v = 4.0 / 3.0 * M_PI * 1e-3;
  EXPECT_NEAR(j.at("volume").get<double>(), v, 1e-15);
  EXPECT_EQ(j.at("method"), "analytic");
  EXPECT_EQ(j.at("panels"), 0);
  EXPECT_EQ(j.at("fluid_density").get<double>(), 1000.0);
  const auto& k = j.at("added_mass");
  ASSERT_EQ(k.size(), 6u);
  for (int i = 0; i < 6; ++i) {
    ASSERT_EQ(k[i].size(), 6u);
    for (int c = 0; c < 6; ++c) {
      const double expect = (i == c && i < 3) ? 0.5 * 1000.0 * v : 0.0;  // 2.0944 kg
      EXPECT_NEAR(k[i][c].get<double>(), expect, 1e-12) << i << "," << c;
    }
  }
  EXPECT_NEAR(j.at("inertia_per_unit_density")[0][0].get<double>(), 0.4 * v * 0.01, 1e-18);
}

TEST(AddedMassCli, BoxBemUsesCacheAndDensity) {
  const fs::path dir =
      fs::temp_directory_path() / ("lrigid_cli_cache_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const std::string env = "LRIGID_CACHE_DIR=" + dir.string();
  const CmdResult a = run("--box 0.2 0.1 0.05 --panels 200 --fluid-density 1.2 --json", env);
  ASSERT_EQ(a.status, 0) << a.out;
  ASSERT_TRUE(fs::exists(dir));
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir)) files += e.path().extension() == ".json";
  EXPECT_EQ(files, 1);
  const CmdResult b = run("--box 0.2 0.1 0.05 --panels 200 --fluid-density 1.2 --json", env);
  ASSERT_EQ(b.status, 0) << b.out;
  EXPECT_EQ(a.out, b.out);  // second run from the cache, identical output
  const nlohmann::json j = nlohmann::json::parse(a.out);
  EXPECT_EQ(j.at("method"), "bem");
  EXPECT_GT(j.at("panels").get<int>(), 100);
  EXPECT_NEAR(j.at("volume").get<double>(), 1e-3, 1e-15);
  // flattest face normal to z: the largest translational entry, in kg for rho = 1.2
  const double kz = j.at("added_mass")[2][2].get<double>();
  EXPECT_GT(kz, j.at("added_mass")[1][1].get<double>());
  EXPECT_GT(kz, 1.2 * 1e-3);
  EXPECT_LT(kz, 1.2 * 1e-3 * 5);
  fs::remove_all(dir);
}

TEST(AddedMassCli, ReportAndErrors) {
  const CmdResult ok = run("--ellipsoid 0.2 0.1 0.1");
  EXPECT_EQ(ok.status, 0) << ok.out;
  EXPECT_NE(ok.out.find("analytic"), std::string::npos) << ok.out;
  EXPECT_NE(ok.out.find("volume"), std::string::npos);

  EXPECT_EQ(run("--box 1 0 1").status, 3);
  EXPECT_EQ(run("").status, 2);
  EXPECT_EQ(run("--sphere 1 --box 1 1 1").status, 2);
  EXPECT_EQ(run("--sphere 1 --fluid-density -3").status, 2);
  const CmdResult missing = run("--mesh /nonexistent/leaf.obj");
  EXPECT_EQ(missing.status, 3);
  EXPECT_NE(missing.out.find("leaf.obj"), std::string::npos) << missing.out;
  const CmdResult open =
      run(std::string("--mesh ") + LRIGID_SOURCE_DIR + "/tests/data/meshes/open.obj");
  EXPECT_EQ(open.status, 3);
  EXPECT_NE(open.out.find("open"), std::string::npos) << open.out;
}

TEST(AddedMassCli, MeshFromFile) {
  const fs::path dir =
      fs::temp_directory_path() / ("lrigid_cli_mesh_" + std::to_string(::getpid()));
  const CmdResult r = run(std::string("--mesh ") + LRIGID_SOURCE_DIR +
                              "/tests/data/meshes/box_binary.stl --panels 300 --json",
                          "LRIGID_CACHE_DIR=" + dir.string());
  ASSERT_EQ(r.status, 0) << r.out;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j.at("volume").get<double>(), 0.2 * 0.1 * 0.05, 1e-8);  // float32 coordinates
  EXPECT_NEAR(j.at("centroid")[1].get<double>(), 2.0, 1e-6);
  EXPECT_EQ(j.at("method"), "bem");
  fs::remove_all(dir);
}

// a closed square prism of half side r and thickness t turned by `deg` about z, as an OBJ
void write_square_obj(const fs::path& path, double r, double t, double deg) {
  const double c = std::cos(deg * M_PI / 180), s = std::sin(deg * M_PI / 180);
  std::ofstream o(path);
  o.precision(17);
  for (double z : {-t / 2, t / 2})
    for (const auto& [x, y] : {std::pair(-r, -r), std::pair(r, -r), std::pair(r, r), std::pair(-r, r)})
      o << "v " << c * x - s * y << " " << s * x + c * y << " " << z << "\n";
  o << "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\n";
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    o << "f " << i + 1 << " " << j + 1 << " " << j + 5 << "\nf " << i + 1 << " " << j + 5 << " "
      << i + 5 << "\n";
  }
}

Mat6 tensor_of(const nlohmann::json& j) {
  Mat6 k;
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) k(r, c) = j.at("added_mass")[r][c].get<double>();
  return k;
}

// --mesh reports the tensor a run takes: a flat, planar mesh (a paper square drawn turned by 45
// degrees) its planform's, the box of its tightest rectangle turned with it (T K T^T, T =
// diag(q, q)), with its rectangularity and weight; a cube its own panel solution
TEST(AddedMassCli, AFlatMeshReportsItsPlanformsTensor) {
  const fs::path dir = fs::temp_directory_path() / ("lrigid_cli_flat_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string env = "LRIGID_CACHE_DIR=" + (dir / "cache").string();
  const double r = 0.03, t = 1e-4, rho = 1.2;
  const fs::path obj = dir / "square45.obj";
  write_square_obj(obj, r, t, 45);
  const CmdResult a = run("--mesh " + obj.string() + " --panels 400 --fluid-density 1.2 --json", env);
  ASSERT_EQ(a.status, 0) << a.out;
  const nlohmann::json j = nlohmann::json::parse(a.out);
  EXPECT_EQ(j.at("added_mass_of"), "planform");
  EXPECT_EQ(j.at("flat"), true);
  EXPECT_EQ(j.at("method"), "bem");
  const auto& p = j.at("planform");
  EXPECT_EQ(p.at("normal_axis"), "z");
  EXPECT_NEAR(p.at("rectangularity").get<double>(), 1.0, 1e-12);
  EXPECT_NEAR(p.at("rectangle_weight").get<double>(), 1.0, 1e-12);
  EXPECT_NEAR(p.at("half_sides")[0].get<double>(), r, 1e-15);
  EXPECT_NEAR(std::abs(p.at("angle").get<double>()), M_PI / 4, 1e-12);
  // the box of its tightest rectangle (the square to an ulp) and its thickness, by the panel
  // method at the same target, turned by 45 degrees; the box of the exact square within 1e-7
  // (the panel method's tensor of a thin box jumps by up to 3e-8 between sizes an ulp apart)
  const double c1 = p.at("rectangle_half_sides")[0].get<double>(),
               c2 = p.at("rectangle_half_sides")[1].get<double>(),
               hz = j.at("shape").at("half_extents")[2].get<double>();
  EXPECT_NEAR(c1, r, 1e-15);
  EXPECT_NEAR(c2, r, 1e-15);
  EXPECT_NEAR(hz, t / 2, 1e-18);
  const lrigid::AddedMass own =
      lrigid::added_mass(lrigid::Shape::box(2 * c1, 2 * c2, 2 * hz), rho, 400);
  const lrigid::AddedMass box = lrigid::added_mass(lrigid::Shape::box(2 * r, 2 * r, t), rho, 400);
  EXPECT_EQ(j.at("panels").get<int>(), own.panels);
  Mat6 q6 = Mat6::Zero();
  const lrigid::Mat3 q = Eigen::AngleAxisd(M_PI / 4, Vec3::UnitZ()).toRotationMatrix();
  q6.block<3, 3>(0, 0) = q;
  q6.block<3, 3>(3, 3) = q;
  const Mat6 want = q6 * own.tensor * q6.transpose();
  const Mat6 got = tensor_of(j);
  EXPECT_LE((got - want).cwiseAbs().maxCoeff(), 1e-12 * want.cwiseAbs().maxCoeff()) << got;
  const Mat6 want_box = q6 * box.tensor * q6.transpose();
  EXPECT_LE((got - want_box).cwiseAbs().maxCoeff(), 1e-7 * want_box.cwiseAbs().maxCoeff());
  // turned by 45 degrees, the square's in-plane entries stay its own (isotropic in its plane)
  EXPECT_NEAR(got(0, 0), own.tensor(0, 0), 1e-9 * own.tensor(2, 2));
  EXPECT_GT(got(2, 2), 10 * got(0, 0));
  // the text says so too
  const CmdResult text = run("--mesh " + obj.string() + " --panels 400 --fluid-density 1.2", env);
  ASSERT_EQ(text.status, 0) << text.out;
  EXPECT_NE(text.out.find("of the planform"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("rectangularity R = 1"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("rectangle weight w = 1"), std::string::npos) << text.out;

  // a cube: not flat, its own panel solution
  const std::string cube = std::string(LRIGID_SOURCE_DIR) + "/tests/data/meshes/cube_quads.obj";
  const CmdResult c = run("--mesh " + cube + " --panels 200 --json", env);
  ASSERT_EQ(c.status, 0) << c.out;
  const nlohmann::json jc = nlohmann::json::parse(c.out);
  EXPECT_EQ(jc.at("added_mass_of"), "shape");
  EXPECT_EQ(jc.at("flat"), false);
  EXPECT_FALSE(jc.contains("planform"));
  EXPECT_EQ(jc.at("method"), "bem");
  // the panel solution of the cube's own triangles, as added_mass gives it
  const lrigid::Shape cs = lrigid::Shape::from_mesh(
      std::make_shared<const lrigid::TriangleMesh>(lrigid::read_mesh(cube)), cube);
  const lrigid::AddedMass panels = lrigid::added_mass(cs, 1000.0, 200);
  EXPECT_EQ(jc.at("panels").get<int>(), panels.panels);
  const Mat6 kc = tensor_of(jc);
  EXPECT_LE((kc - panels.tensor).cwiseAbs().maxCoeff(), 1e-9 * panels.tensor.cwiseAbs().maxCoeff());
  // the unit cube's k = K_vx / (rho V): 0.6386 in the limit, above it at 200 panels
  EXPECT_GT(kc(0, 0) / 1000.0, 0.6386);
  EXPECT_LT(kc(0, 0) / 1000.0, 0.8);
  const CmdResult ctext = run("--mesh " + cube + " --panels 200", env);
  EXPECT_EQ(ctext.out.find("planform"), std::string::npos) << ctext.out;
  fs::remove_all(dir);
}

TEST(AddedMassCli, LengthsPanelsAndDensityOutOfRange) {
  // each is refused at once (timeout: a box of 1e160 m kept the boundary elements busy without
  // end, 2e9 panels were tessellated first; a radius of 1e-200 m ended in exit 1)
  const std::string t = "timeout 60";
  for (const char* shape : {"--sphere 1e-200", "--sphere 1e300", "--ellipsoid 1e-200 1e-200 2e-200",
                            "--box 1e160 1 1", "--box 1e-300 1 1"}) {
    const CmdResult r = run(shape, t);
    EXPECT_EQ(r.status, 3) << shape << ": " << r.out;
    EXPECT_NE(r.out.find(std::string(shape).substr(0, std::string(shape).find(' '))),
              std::string::npos) << r.out;
    EXPECT_NE(r.out.find("[1e-9, 1e6] m"), std::string::npos) << shape << ": " << r.out;
  }
  // a sheet of 1e6:1: the solver's tensor was not positive (exit 1)
  const CmdResult sheet = run("--box 1 1 1e-6", t);
  EXPECT_EQ(sheet.status, 3) << sheet.out;
  EXPECT_NE(sheet.out.find("at most 1e5"), std::string::npos) << sheet.out;
  EXPECT_EQ(run("--box 1 1 1e-5", t).status, 0);
  const CmdResult panels = run("--box 1 1 1 --panels 2000000000", t);
  EXPECT_EQ(panels.status, 2) << panels.out;
  EXPECT_NE(panels.out.find("--panels must be in [0, 10000]"), std::string::npos) << panels.out;
  const CmdResult rho = run("--sphere 1 --fluid-density 1e308", t);
  EXPECT_EQ(rho.status, 2) << rho.out;
  EXPECT_NE(rho.out.find("--fluid-density"), std::string::npos) << rho.out;
  const CmdResult dir = run("--mesh " + fs::temp_directory_path().string(), t);
  EXPECT_EQ(dir.status, 3) << dir.out;
  EXPECT_NE(dir.out.find("is a directory"), std::string::npos) << dir.out;
}

}  // namespace
