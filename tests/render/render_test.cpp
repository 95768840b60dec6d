// lrigid render (label render): a real run drawn offscreen under xvfb-run; the PNG must have the
// requested size, not be blank, and show body pixels in the body types' colours.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "support/shell_png.h"

namespace {

namespace fs = std::filesystem;

const std::string kLrigid = std::string(LRIGID_BINARY_DIR) + "/bin/lrigid";

using lrigid::test::Image;
using lrigid::test::read_png;
using lrigid::test::sh;

class Render : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = ::testing::TempDir() + "render_test_" + std::to_string(::getpid());
    fs::create_directories(dir_);
    std::ofstream(dir_ + "/scene.json") << R"({
  "version": 1,
  "fluid": { "density": 1.204, "kinematic_viscosity": 1.5e-5,
             "uniform": { "U": [1.0, 0.0, 0.0], "k": 0.1, "epsilon": 0.05 } },
  "gravity": [0, 0, -9.81],
  "effects": "auto",
  "integrator": { "scheme": "splitting", "dt": 0.002 },
  "duration": 0.6,
  "seed": 3,
  "ground": { "z": 0.0 },
  "bodies": [
    { "name": "card", "shape": { "type": "box", "size": [0.09, 0.05, 0.002] }, "density": 700,
      "count": 12, "spawn_box": [[0, 0, 0.6], [1, 1, 1.2]], "orientation": "random" },
    { "name": "bead", "shape": { "type": "sphere", "radius": 0.02 }, "density": 100,
      "count": 12, "spawn_box": [[0, 0, 0.6], [1, 1, 1.2]] }
  ],
  "output": { "every": 0.05, "formats": ["csv"] }
})";
    std::string log;
    run_status_ = sh(kLrigid + " run " + dir_ + "/scene.json -o " + dir_ + "/out --quiet", &log);
    run_log_ = log;
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  static std::string dir_, run_log_;
  static int run_status_;
};
std::string Render::dir_, Render::run_log_;
int Render::run_status_ = -1;

TEST_F(Render, PreviewHasSizeContentAndBodies) {
  ASSERT_EQ(run_status_, 0) << run_log_;
  const std::string png = dir_ + "/preview.png";
  std::string log;
  ASSERT_EQ(sh("xvfb-run -a " + kLrigid + " render " + dir_ + "/out -o " + png +
                   " --width 320 --height 240 --quiet",
               &log),
            0)
      << log;
  const Image im = read_png(png);
  ASSERT_EQ(im.w, 320);
  ASSERT_EQ(im.h, 240);
  ASSERT_GE(im.comps, 3);
  // not blank: the grey levels vary
  double sum = 0, sum2 = 0;
  size_t orange = 0, green = 0;
  const size_t n = size_t(im.w) * size_t(im.h);
  for (size_t i = 0; i < n; ++i) {
    const int r = im.px[i * im.comps], g = im.px[i * im.comps + 1], b = im.px[i * im.comps + 2];
    const double y = 0.3 * r + 0.6 * g + 0.1 * b;
    sum += y, sum2 += y * y;
    // the body types' colours (shaded): cards orange, beads green (no body type is blue, the
    // colour of the k slices); the background is grey-blue
    orange += r > g + 40 && g > b + 20;
    green += g > r + 40 && g > b + 40;
  }
  const double mean = sum / double(n);
  EXPECT_GT(std::sqrt(sum2 / double(n) - mean * mean), 5.0);
  EXPECT_GT(orange, 10u) << "no card pixels";
  EXPECT_GT(green, 10u) << "no bead pixels";
}

TEST_F(Render, GifHasTheRequestedFrames) {
  ASSERT_EQ(run_status_, 0) << run_log_;
  const std::string gif = dir_ + "/anim.gif";
  std::string log;
  ASSERT_EQ(sh("xvfb-run -a " + kLrigid + " render " + dir_ + "/out --frames 5 --gif " + gif +
                   " --width 160 --height 120 --quiet",
               &log),
            0)
      << log;
  std::ifstream in(gif, std::ios::binary);
  char magic[6] = {};
  in.read(magic, 6);
  EXPECT_EQ(std::string(magic, 6), "GIF89a");
  std::string frames;
  ASSERT_EQ(sh("identify " + gif + " | wc -l", &frames), 0);
  EXPECT_EQ(std::stoi(frames), 5);
  for (const auto& e : fs::directory_iterator(dir_))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

TEST_F(Render, WithoutDisplaySaysUseXvfb) {
  ASSERT_EQ(run_status_, 0) << run_log_;
  std::string log;
  const int st = sh("env -u DISPLAY " + kLrigid + " render " + dir_ + "/out -o " + dir_ +
                        "/nodisplay.png",
                    &log);
  EXPECT_EQ(st, 1) << log;
  EXPECT_NE(log.find("xvfb-run"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir_ + "/nodisplay.png"));
}

}  // namespace
