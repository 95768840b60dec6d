// lrigid explain's data (io/explain.cpp): the flow where each body type starts, drawn at the
// positions initial_state gives its bodies, beside the grid's medians over the whole domain.
#include "io/explain.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "io/scene_json.h"
#include "support/temp_dir.h"
#include "support/vti_writer.h"


namespace lrigid {
namespace {

struct ExplainStartFlow : test::TempDirTest {
  void SetUp() override {
    TempDirTest::SetUp();
    // a 10 m cube, wind along x as fast as x (m/s), a solid block where x >= 8 and z <= 2
    test::VtiGrid g;
    g.dims = {11, 11, 11};
    g.spacing = {1, 1, 1};
    g.solid = [](const std::array<double, 3>& x) { return x[0] >= 8 && x[2] <= 2; };
    ASSERT_TRUE(test::write_vti((dir / "g.vti").string(), g,
                                [](int, const std::array<double, 3>& x, float U[3], float* k,
                                   float* e) { U[0] = float(x[0]), *k = 0.06f, *e = 0.01f; }));
  }

  nlohmann::json explain(const std::string& fluid, const std::string& spawn_box) {
    const std::string text =
        R"({"version": 1, "fluid": )" + fluid + R"(, "gravity": [0, 0, -9.81],
          "effects": "auto", "integrator": {"scheme": "strang", "dt": 0.002}, "duration": 1,
          "seed": 1, "bodies": [{"name": "ball", "shape": {"type": "sphere", "radius": 0.005},
          "density": 2500, "count": 200, "spawn_box": )" + spawn_box + "}]}";
    return explain_scene(parse_scene(text, (dir / "scene.json").string()));
  }
};

const std::string kGrid =
    R"({"density": 1.2, "kinematic_viscosity": 1.5e-5, "field": "g.vti"})";

TEST_F(ExplainStartFlow, IsTheFlowAtTheBodiesNotTheGridsMedian) {
  const nlohmann::json j = explain(kGrid, "[[1, 1, 4], [2, 9, 9]]");
  const double grid_U = j["flow"]["U"].get<double>();
  const nlohmann::json& sf = j["body_types"][0]["start_flow"];
  ASSERT_TRUE(sf.is_object()) << j.dump(1);
  EXPECT_EQ(sf["positions"].get<size_t>(), 200u);
  EXPECT_EQ(sf["in_fluid"].get<size_t>(), 200u);
  // |U| = x over x in [1, 2]: median 1.5, and the 10th and 90th percentiles near 1.1 and 1.9
  EXPECT_NEAR(sf["U_median"].get<double>(), 1.5, 0.1);
  EXPECT_GT(sf["U_p10"].get<double>(), 1.0);
  EXPECT_LT(sf["U_p90"].get<double>(), 2.0);
  EXPECT_LT(sf["U_p10"].get<double>(), sf["U_p90"].get<double>());
  EXPECT_GT(grid_U, 3.0) << "the grid's median is of the whole domain";
  EXPECT_NEAR(sf["u_turb_median"].get<double>(), std::sqrt(2.0 / 3.0 * 0.06), 1e-3);
  EXPECT_NEAR(sf["k_median"].get<double>(), 0.06, 1e-4);
}

TEST_F(ExplainStartFlow, CountsThePositionsInTheSolidsAndIsNullOnAUniformField) {
  // the box reaches into the block (x >= 8, z <= 2; its cells from x = 7 and z = 3 on)
  const nlohmann::json part = explain(kGrid, "[[5, 1, 0.5], [9.5, 9, 2]]");
  const nlohmann::json& sf = part["body_types"][0]["start_flow"];
  EXPECT_EQ(sf["positions"].get<size_t>(), 200u);
  EXPECT_LT(sf["in_fluid"].get<size_t>(), 200u);
  EXPECT_GT(sf["in_fluid"].get<size_t>(), 0u);
  const nlohmann::json solid = explain(kGrid, "[[8.2, 1, 0.5], [9.5, 9, 1.5]]");
  EXPECT_EQ(solid["body_types"][0]["start_flow"]["in_fluid"].get<size_t>(), 0u);
  EXPECT_FALSE(solid["body_types"][0]["start_flow"].contains("U_median"));
  const nlohmann::json uniform =
      explain(R"({"density": 1.2, "kinematic_viscosity": 1.5e-5,
                  "uniform": {"U": [1, 0, 0], "k": 0.1, "epsilon": 0.01}})",
              "[[1, 1, 4], [2, 9, 9]]");
  EXPECT_TRUE(uniform["body_types"][0]["start_flow"].is_null());
}

}  // namespace
}  // namespace lrigid
