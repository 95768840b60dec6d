// lrigid render explains its picture (label render): a legend of the body types in
// their colours, a caption that fits a narrow image, and the domain: the grid's outline and, in
// water, the tank (walls, floor, water surface). A run on a small synthetic tank grid written
// here (the shipped tank scene needs the slow tankJet case), drawn offscreen under xvfb-run.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "support/shell_png.h"
#include "support/vti_writer.h"

namespace {

namespace fs = std::filesystem;

const std::string kLrigid = std::string(LRIGID_BINARY_DIR) + "/bin/lrigid";

using lrigid::test::Image;
using lrigid::test::read_png;
using lrigid::test::sh;

// the palette of app/vtk_draw.cpp type_colour: types 0 and 1
const int kType0[3] = {230, 140, 50}, kType1[3] = {70, 170, 70};

bool near(const unsigned char* p, const int c[3], int tol) {
  return std::abs(p[0] - c[0]) <= tol && std::abs(p[1] - c[1]) <= tol &&
         std::abs(p[2] - c[2]) <= tol;
}

class RenderAnnotate : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = ::testing::TempDir() + "render_annotate_" + std::to_string(::getpid());
    fs::create_directories(dir_);
    // a 1 x 0.6 x 0.8 m tank of still water, 5 cm cells, slight turbulence
    lrigid::test::VtiGrid g;
    g.dims = {21, 13, 17};
    g.spacing = {0.05, 0.05, 0.05};
    g.nu = 1e-6;
    grid_ok_ = lrigid::test::write_vti(
        dir_ + "/tank.vti", g,
        [](int, const std::array<double, 3>& x, float U[3], float* k, float* e) {
          U[0] = U[1] = U[2] = 0;
          *k = float(1e-4 * (1 + x[2])), *e = 1e-5f;
        });
    std::ofstream(dir_ + "/scene.json") << R"({
  "version": 1,
  "fluid": { "density": 998.2, "kinematic_viscosity": 1e-6, "field": "tank.vti" },
  "gravity": [0, 0, -9.81],
  "effects": "auto",
  "integrator": { "scheme": "splitting", "dt": 0.002 },
  "duration": 0.2,
  "seed": 3,
  "ground": { "z": 0.0 },
  "bodies": [
    { "name": "a_rather_long_name_for_plastic_flakes", "shape": { "type": "box",
      "size": [0.03, 0.02, 0.002] }, "density": 1100, "count": 20,
      "spawn_box": [[0.2, 0.1, 0.3], [0.8, 0.5, 0.6]], "orientation": "random" },
    { "name": "bubble", "shape": { "type": "sphere", "radius": 0.01 }, "density": 1.2,
      "count": 20, "spawn_box": [[0.2, 0.1, 0.1], [0.8, 0.5, 0.4]] }
  ],
  "output": { "every": 0.1, "formats": ["csv"] }
})";
    std::string log;
    run_status_ = sh(kLrigid + " run " + dir_ + "/scene.json -o " + dir_ + "/water --quiet", &log);
    run_log_ = log;
    // the same run as if in air: only the summary's fluid density differs
    if (run_status_ == 0) {
      fs::copy(dir_ + "/water", dir_ + "/air", fs::copy_options::recursive);
      std::ifstream in(dir_ + "/air/summary.json");
      nlohmann::json j = nlohmann::json::parse(in);
      in.close();
      j["fluid_density"] = 1.2;
      std::ofstream(dir_ + "/air/summary.json") << j.dump(1);
    }
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  // the picture of results `results` at w x h (drawn once, then read again)
  static Image render(const std::string& results, int w, int h) {
    const std::string png = dir_ + "/" + results + "_" + std::to_string(w) + "x" +
                            std::to_string(h) + ".png";
    std::string log;
    if (!fs::exists(png) &&
        sh("xvfb-run -a " + kLrigid + " render " + dir_ + "/" + results + " -o " + png +
               " --width " + std::to_string(w) + " --height " + std::to_string(h) + " --quiet",
           &log) != 0) {
      ADD_FAILURE() << log;
      return {};
    }
    return read_png(png);
  }

  static std::string dir_, run_log_;
  static int run_status_;
  static bool grid_ok_;
};
std::string RenderAnnotate::dir_, RenderAnnotate::run_log_;
int RenderAnnotate::run_status_ = -1;
bool RenderAnnotate::grid_ok_ = false;

TEST_F(RenderAnnotate, LegendShowsEachTypeInItsColourTopLeft) {
  ASSERT_TRUE(grid_ok_);
  ASSERT_EQ(run_status_, 0) << run_log_;
  const Image im = render("water", 480, 300);
  ASSERT_EQ(im.w, 480);
  // the top-left quarter (rows are bottom first): the legend's swatches and names, drawn flat
  // in exactly the type colours; the bodies themselves are shaded
  size_t c0 = 0, c1 = 0;
  for (int y = im.h * 3 / 4; y < im.h; ++y)
    for (int x = 0; x < im.w / 2; ++x) {
      c0 += near(im.at(x, y), kType0, 6);
      c1 += near(im.at(x, y), kType1, 6);
    }
  EXPECT_GT(c0, 20u) << "no legend entry in type 0's colour";
  EXPECT_GT(c1, 20u) << "no legend entry in type 1's colour";
}

TEST_F(RenderAnnotate, CaptionFitsA480PixelImage) {
  ASSERT_TRUE(grid_ok_);
  ASSERT_EQ(run_status_, 0) << run_log_;
  // the caption (dark text, bottom left) must end before the right edge; at 160 px it is put on
  // several lines: dark pixels reach higher than one line
  for (const int w : {480, 160}) {
    const Image im = render("water", w, w * 5 / 8);  // 480 x 300 as in the other tests
    ASSERT_EQ(im.w, w);
    int right = -1, top = -1;
    for (int y = 0; y < im.h / 3; ++y)
      for (int x = 0; x < im.w; ++x) {
        const unsigned char* p = im.at(x, y);
        if (p[0] < 60 && p[1] < 60 && p[2] < 70 && y < 60) right = std::max(right, x), top = std::max(top, y);
      }
    ASSERT_GE(right, 0) << "no caption at " << w << " px";
    EXPECT_LT(right, w - 4) << "the caption runs off a " << w << " px image";
    if (w == 160) {
      EXPECT_GT(top, 20) << "one line at 160 px: it cannot fit";
    }
  }
}

TEST_F(RenderAnnotate, TheTankShowsWallsAndWaterSurfaceAndTheGridItsOutline) {
  ASSERT_TRUE(grid_ok_);
  ASSERT_EQ(run_status_, 0) << run_log_;
  const Image water = render("water", 480, 300), air = render("air", 480, 300);
  ASSERT_EQ(water.w, 480);
  ASSERT_EQ(air.w, 480);
  // the outline of the grid in both: dark grey lines (0.2, 0.2, 0.25), flat
  const int outline[3] = {51, 51, 64};
  size_t ow = 0, oa = 0;
  // the tank's panels in water only: pixels of the same run that differ
  size_t differ = 0, bluer = 0;
  for (int y = 0; y < water.h; ++y)
    for (int x = 0; x < water.w; ++x) {
      const unsigned char *p = water.at(x, y), *q = air.at(x, y);
      ow += near(p, outline, 12);
      oa += near(q, outline, 12);
      const int d = std::abs(p[0] - q[0]) + std::abs(p[1] - q[1]) + std::abs(p[2] - q[2]);
      differ += d > 30;
      bluer += (p[2] - p[0]) > (q[2] - q[0]) + 15;  // the surface is blue
    }
  EXPECT_GT(oa, 200u) << "no grid outline in air";
  EXPECT_GT(ow, 200u) << "no grid outline in water";
  EXPECT_GT(differ, size_t(water.w * water.h / 20)) << "the tank draws nothing over 5 % of it";
  EXPECT_GT(bluer, size_t(water.w * water.h / 50)) << "no water surface";
}

}  // namespace
