// Sanity warnings at the command line (io/sanity.h): lrigid run prints them on stderr
// before the run with the scene key and the fix, records them in summary.json, --strict makes
// them errors (exit 3, no results), every body outside the grid is an error, and lrigid explain
// prints them too. Tiny scenes (a few spheres, 0.1 s).
#include <gtest/gtest.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "support/shell.h"
#include "support/vti_writer.h"

namespace fs = std::filesystem;

namespace {

const std::string kLrigid = std::string(LRIGID_BINARY_DIR) + "/bin/lrigid";

struct Result {
  int rc = -1;
  std::string err;
};

// runs lrigid with `args`, stderr captured (stdout dropped)
Result lrigid(const std::string& args) {
  Result r;
  r.rc = lrigid::test::sh("( " + kLrigid + " " + args + " 2>&1 >/dev/null )", &r.err);
  return r;
}

struct SanityCli : ::testing::Test {
  fs::path dir;
  void SetUp() override {
    dir = fs::temp_directory_path() /
          ("lrigid_sanity_cli_" + std::to_string(::getpid()) + "_" +
           ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }
  std::string scene(const std::string& fluid, const std::string& body) {
    const fs::path p = dir / "scene.json";
    std::ofstream(p) << R"({"version": 1, "fluid": )" << fluid
                     << R"(, "gravity": [0, 0, -9.81], "effects": "auto",
      "integrator": {"scheme": "strang", "dt": 0.01}, "duration": 0.1, "seed": 1,
      "bodies": [{"name": "ball", "shape": {"type": "sphere", "radius": )"
                     << body << R"(}], "output": {"every": 0.05, "formats": ["csv"]}})";
    return p.string();
  }
};

const std::string kAir = R"({"density": 1.2, "kinematic_viscosity": 1.5e-5,
  "uniform": {"U": [1, 0, 0], "k": 0.1, "epsilon": 0.01}})";

TEST_F(SanityCli, CentimetresAsMetresWarnBeforeTheRunAndLandInSummary) {
  // a 6 cm ball written as radius 3 (metres)
  const std::string s = scene(kAir, R"(3}, "density": 600, "count": 4,
      "spawn_box": [[0, 0, 5], [1, 1, 6]])");
  const fs::path out = dir / "out";
  const Result r = lrigid("run " + s + " -o " + out.string() + " --threads 1");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.err.find("lrigid: warning: " + s +
                       ": bodies[0].shape: body type \"ball\" is 6 m wide: sizes are in metres"),
            std::string::npos) << r.err;
  EXPECT_LT(r.err.find("warning"), r.err.find("results in")) << "the warning comes first";
  std::ifstream in(out / "summary.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  ASSERT_TRUE(j.contains("warnings"));
  ASSERT_GE(j["warnings"].size(), 1u);
  EXPECT_EQ(j["warnings"][0]["check"], "body_size");
  EXPECT_EQ(j["warnings"][0]["key"], "bodies[0].shape");
  EXPECT_EQ(j["warnings"][0]["error"], false);
  // --quiet: no warning printed, still recorded
  const Result q = lrigid("run " + s + " -o " + (dir / "q").string() + " --quiet");
  EXPECT_EQ(q.rc, 0);
  EXPECT_EQ(q.err.find("warning"), std::string::npos) << q.err;
  // lrigid explain prints it too
  const Result e = lrigid("explain " + s);
  EXPECT_EQ(e.rc, 0);
  EXPECT_NE(e.err.find("bodies[0].shape: body type \"ball\" is 6 m wide"), std::string::npos)
      << e.err;
}

TEST_F(SanityCli, StrictTurnsTheWarningIntoAnErrorWithoutResults) {
  const std::string s = scene(kAir, R"(3}, "density": 600, "count": 4,
      "spawn_box": [[0, 0, 5], [1, 1, 6]])");
  const fs::path out = dir / "out";
  const Result r = lrigid("run " + s + " -o " + out.string() + " --strict");
  EXPECT_EQ(r.rc, 3) << r.err;
  EXPECT_NE(r.err.find("lrigid: error: " + s + ": bodies[0].shape: body type \"ball\" is 6 m "
                       "wide: sizes are in metres"),
            std::string::npos) << r.err;
  EXPECT_NE(r.err.find("(a warning: --strict)"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out / "summary.json"));
  EXPECT_FALSE(fs::exists(out / "trajectories.csv"));
}

TEST_F(SanityCli, EveryBodyOutsideTheGridIsAnError) {
  lrigid::test::VtiGrid g;
  g.dims = {4, 4, 4};
  ASSERT_TRUE(lrigid::test::write_vti((dir / "g.vti").string(), g,
                                      [](int, const std::array<double, 3>&, float U[3], float* k,
                                         float* e) { U[0] = 1, *k = 0.1f, *e = 0.01f; }));
  // spawn box in centimetres: [100, 300] where the grid spans [0, 3] m
  const std::string s =
      scene(R"({"density": 1.2, "kinematic_viscosity": 1.5e-5, "field": "g.vti"})",
            R"(0.002}, "density": 600, "count": 4, "spawn_box": [[100, 100, 100], [300, 300, 300]])");
  const fs::path out = dir / "out";
  const Result r = lrigid("run " + s + " -o " + out.string());
  EXPECT_EQ(r.rc, 3) << r.err;
  EXPECT_NE(r.err.find("bodies[0].spawn_box: spawn_box [[100, 100, 100], [300, 300, 300]] lies "
                       "entirely outside the grid [[0, 0, 0], [3, 3, 3]]"),
            std::string::npos) << r.err;
  EXPECT_NE(r.err.find("lrigid: error: " + s + ": bodies: every body starts outside the grid"),
            std::string::npos) << r.err;
  EXPECT_NE(r.err.find("in metres in the grid's frame"), std::string::npos);
  EXPECT_FALSE(fs::exists(out / "summary.json"));
}

}  // namespace
