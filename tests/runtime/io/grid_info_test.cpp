// lrigid info's data (io/grid_info.cpp): the solids of a grid one by one, with their boxes and
// the flow around them, and the grid's own box and flow.
#include "io/grid_info.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "support/temp_dir.h"
#include "support/vti_writer.h"
#include "util/error.h"


namespace lrigid {
namespace {

struct GridInfo : test::TempDirTest {
  // 21 x 11 x 11 points 1 m apart from the origin; wind 2 m/s along x, 1 m/s within 2 m of the
  // ground; k 0.1
  std::string write(const std::string& name, std::function<bool(const std::array<double, 3>&)> solid) {
    test::VtiGrid g;
    g.dims = {21, 11, 11};
    g.spacing = {1, 1, 1};
    g.solid = std::move(solid);
    const std::string path = (dir / name).string();
    EXPECT_TRUE(test::write_vti(path, g,
                                [](int, const std::array<double, 3>& x, float U[3], float* k,
                                   float* e) { U[0] = x[2] < 2 ? 1 : 2, *k = 0.1f, *e = 0.01f; }));
    return path;
  }
};

TEST_F(GridInfo, ListsEachSolidWithItsBoxAndTheFlowAroundIt) {
  // a building (points x 2..5, y 2..8, z 0..4: 140) and a low wall (x 12..13, y 4..5, z 0..1: 8)
  const std::string path = write("two.vti", [](const std::array<double, 3>& x) {
    return (x[0] >= 2 && x[0] <= 5 && x[1] >= 2 && x[1] <= 8 && x[2] <= 4) ||
           (x[0] >= 12 && x[0] <= 13 && x[1] >= 4 && x[1] <= 5 && x[2] <= 1);
  });
  const nlohmann::json j = grid_info(path);
  EXPECT_EQ(j["points"], nlohmann::json({21, 11, 11}));
  EXPECT_EQ(j["upper"], nlohmann::json({20.0, 10.0, 10.0}));
  EXPECT_EQ(j["fluid_points"].get<size_t>(), 21u * 11 * 11 - 140 - 8);
  EXPECT_EQ(j["flow"]["U_median"].get<double>(), 2.0);
  ASSERT_EQ(j["solids_total"].get<size_t>(), 2u);
  const nlohmann::json& b = j["solids"][0];  // the larger first
  EXPECT_EQ(b["points"].get<size_t>(), 140u);
  // its points' box widened by half a spacing, cut at the grid's bottom
  EXPECT_EQ(b["lo"], nlohmann::json({1.5, 1.5, 0.0}));
  EXPECT_EQ(b["hi"], nlohmann::json({5.5, 8.5, 4.5}));
  // 3 m out from it most of the fluid is above 2 m: the 2 m/s wind, not the walls' no-slip
  EXPECT_EQ(b["around"]["U_median"].get<double>(), 2.0);
  EXPECT_GT(b["around"]["points"].get<size_t>(), 50u);
  const nlohmann::json& w = j["solids"][1];
  EXPECT_EQ(w["points"].get<size_t>(), 8u);
  EXPECT_EQ(w["lo"], nlohmann::json({11.5, 3.5, 0.0}));
  EXPECT_EQ(w["hi"], nlohmann::json({13.5, 5.5, 1.5}));
  // the wall is low: the flow 3 m around it is mostly the slower layer near the ground
  EXPECT_EQ(w["around"]["U_median"].get<double>(), 1.0);

  const nlohmann::json one = grid_info(path, 1);
  EXPECT_EQ(one["solids"].size(), 1u);
  EXPECT_EQ(one["solids_total"].get<size_t>(), 2u);
}

TEST_F(GridInfo, AGridWithoutSolidsAndAMissingFile) {
  const nlohmann::json j = grid_info(write("open.vti", nullptr));
  EXPECT_EQ(j["solids_total"].get<size_t>(), 0u);
  EXPECT_TRUE(j["solids"].empty());
  EXPECT_EQ(j["fluid_points"].get<size_t>(), 21u * 11 * 11);
  try {
    grid_info((dir / "none.vti").string());
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("none.vti"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lrigid
