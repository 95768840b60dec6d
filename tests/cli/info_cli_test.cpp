// lrigid info GRID at the command line (app/cmd_info.cpp over io/grid_info.h): the grid's box
// and flow, each solid's box and the flow around it, --json, and a missing file named.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "support/shell.h"
#include "support/vti_writer.h"

namespace fs = std::filesystem;

namespace {

const std::string kLrigidInfo = std::string(LRIGID_BINARY_DIR) + "/bin/lrigid info ";

TEST(InfoCli, PrintsTheSolidsBoxesAndWritesJson) {
  const fs::path dir = fs::temp_directory_path() / ("lrigid_info_cli_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  lrigid::test::VtiGrid g;
  g.dims = {11, 11, 6};
  g.spacing = {1, 1, 1};
  g.solid = [](const std::array<double, 3>& x) { return x[0] >= 3 && x[0] <= 6 && x[2] <= 2; };
  const std::string grid = (dir / "g.vti").string();
  ASSERT_TRUE(lrigid::test::write_vti(grid, g,
                                      [](int, const std::array<double, 3>&, float U[3], float* k,
                                         float* e) { U[0] = 3, *k = 0.2f, *e = 0.05f; }));
  std::string out;
  ASSERT_EQ(lrigid::test::sh(kLrigidInfo + grid + " --json " + (dir / "i.json").string(), &out),
            0)
      << out;
  EXPECT_NE(out.find("box [[0, 0, 0], [10, 10, 5]] m, spacing 1 x 1 x 1 m, 11 x 11 x 6 points"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("  1. [[2.5, 0, 0], [6.5, 10, 2.5]] m, 132 points; around it |U| median 3 "
                     "m/s"),
            std::string::npos)
      << out;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(dir / "i.json"));
  EXPECT_EQ(j["solids_total"].get<size_t>(), 1u);
  EXPECT_EQ(j["solids"][0]["points"].get<size_t>(), 4u * 11 * 3);

  const int rc = lrigid::test::sh(kLrigidInfo + (dir / "none.vti").string() + " 2>&1", &out);
  EXPECT_NE(rc, 0);
  EXPECT_NE(out.find("none.vti"), std::string::npos) << out;
  fs::remove_all(dir);
}

}  // namespace
