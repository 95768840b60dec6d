// lrigid render's camera and colours (label render): a close-up at true scale draws a leaf over
// the pixel area its projection predicts, --frame ENTRY fills the picture with that entry's
// bodies, --color-by state puts the state colours where the bodies are, bad flags are refused.
// A short real run (a leaf and stones resting on the ground, beads still falling) drawn
// offscreen under xvfb-run.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "support/shell_png.h"

namespace {

namespace fs = std::filesystem;

const std::string kLrigid = std::string(LRIGID_BINARY_DIR) + "/bin/lrigid";
constexpr double kPi = 3.14159265358979323846;

using lrigid::test::Image;
using lrigid::test::read_png;
using lrigid::test::sh;

// the last frame of trajectories.csv: per body its position and state
struct Last {
  double x[3];
  double q[4];
  std::string type, state;
};

std::vector<Last> last_frame(const std::string& csv, size_t bodies) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<Last> all;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string cell;
    std::vector<std::string> c;
    while (std::getline(ss, cell, ',')) c.push_back(cell);
    if (c.size() < 17) continue;
    Last l;
    for (int k = 0; k < 3; ++k) l.x[k] = std::stod(c[size_t(3 + k)]);
    for (int k = 0; k < 4; ++k) l.q[k] = std::stod(c[size_t(6 + k)]);
    l.type = c[1];
    l.state = c.back();
    all.push_back(l);
  }
  if (all.size() < bodies) return {};
  return std::vector<Last>(all.end() - long(bodies), all.end());
}

// the palette of app/vtk_draw.cpp type_colour (entries 0 and 1) and app/draw_style.cpp
// state_colour, shaded by the lights: a pixel of that hue
bool orange(const unsigned char* p) { return p[0] > p[1] + 40 && p[1] > p[2] + 20; }
bool green(const unsigned char* p) { return p[1] > p[0] + 40 && p[1] > p[2] + 40; }
bool red(const unsigned char* p) { return p[0] > 120 && p[1] < 80 && p[2] < 90 && p[0] > 2 * p[1]; }

class RenderCamera : public ::testing::Test {
 protected:
  static constexpr size_t kBodies = 1 + 12 + 8;
  static void SetUpTestSuite() {
    dir_ = ::testing::TempDir() + "render_camera_" + std::to_string(::getpid());
    fs::create_directories(dir_);
    // still air: the leaf (8 x 5 cm) and the stones settle on the ground near z = 0 within a
    // fraction of a second; the beads start 2.5 to 3 m up and are still falling at the end
    std::ofstream(dir_ + "/scene.json") << R"({
  "version": 1,
  "fluid": { "density": 1.204, "kinematic_viscosity": 1.5e-5,
             "uniform": { "U": [0.0, 0.0, 0.0], "k": 0.0, "epsilon": 0.0 } },
  "gravity": [0, 0, -9.81],
  "effects": "auto",
  "integrator": { "scheme": "splitting", "dt": 0.002 },
  "duration": 0.5,
  "seed": 5,
  "ground": { "z": 0.0 },
  "bodies": [
    { "name": "leaf", "shape": { "type": "box", "size": [0.08, 0.05, 0.001] }, "density": 500,
      "count": 1, "spawn_box": [[2.0, 2.0, 0.01], [2.0, 2.0, 0.01]] },
    { "name": "stone", "shape": { "type": "sphere", "radius": 0.02 }, "density": 2500,
      "count": 12, "spawn_box": [[0, 0, 0.021], [1, 1, 0.03]] },
    { "name": "bead", "shape": { "type": "sphere", "radius": 0.03 }, "density": 200,
      "count": 8, "spawn_box": [[0, 0, 2.5], [1, 1, 3.0]] }
  ],
  "output": { "every": 0.05, "formats": ["csv"] }
})";
    run_status_ =
        sh(kLrigid + " run " + dir_ + "/scene.json -o " + dir_ + "/out --quiet", &run_log_);
    if (run_status_ == 0) last_ = last_frame(dir_ + "/out/trajectories.csv", kBodies);
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  // lrigid render of the run at 320 x 240 with `flags`; its exit status and output in *log
  static int render(const std::string& png, const std::string& flags, std::string* log,
                    const std::string& results = "out") {
    return sh("xvfb-run -a " + kLrigid + " render " + dir_ + "/" + results + " -o " + dir_ + "/" +
                  png + " --width 320 --height 240 " + flags,
              log);
  }

  static std::string dir_, run_log_;
  static int run_status_;
  static std::vector<Last> last_;
};
std::string RenderCamera::dir_, RenderCamera::run_log_;
int RenderCamera::run_status_ = -1;
std::vector<Last> RenderCamera::last_;

TEST_F(RenderCamera, CloseUpDrawsTheLeafAtTrueScale) {
  ASSERT_EQ(run_status_, 0) << run_log_;
  ASSERT_EQ(last_.size(), kBodies);
  const Last& leaf = last_[0];
  ASSERT_EQ(leaf.type, "leaf");
  // straight down from 0.5 m above the leaf, 30 degrees of view
  const double h = 0.5, fov = 30;
  char flags[256];
  std::snprintf(flags, sizeof flags,
                "--camera-position %.6f %.6f %.6f --camera-target %.6f %.6f %.6f --fov %g",
                leaf.x[0], leaf.x[1], leaf.x[2] + h, leaf.x[0], leaf.x[1], leaf.x[2], fov);
  std::string log;
  ASSERT_EQ(render("closeup.png", flags, &log), 0) << log;
  EXPECT_EQ(log.find("enlarged"), std::string::npos) << "a close-up is drawn at true size: " << log;
  const Image im = read_png(dir_ + "/closeup.png");
  ASSERT_EQ(im.w, 320);
  // the predicted area: the leaf's face, tilted by its normal's angle to the line of sight
  // (the body's z axis turned by q), in pixels at the leaf's depth
  const double x = leaf.q[1], y = leaf.q[2];
  const double nz = 1 - 2 * (x * x + y * y);  // R(2, 2)
  const double ppm = im.h / (2 * h * std::tan(0.5 * fov * kPi / 180));
  const double predicted = 0.08 * 0.05 * std::abs(nz) * ppm * ppm;
  ASSERT_GT(predicted, 1000) << "the leaf should face the camera";
  // leaf pixels around the picture's centre (the legend, top left, also has an orange swatch)
  size_t area = 0;
  for (int py = 30; py < 180; ++py)
    for (int px = 90; px < 230; ++px) area += orange(im.at(px, py));
  // within 25 %: the pixels along the leaf's outline (about 230 of them) are partly covered and
  // partly counted; a leaf drawn 1.5 times larger would cover 2.25 times the area
  EXPECT_GT(double(area), predicted / 1.25) << "predicted " << predicted;
  EXPECT_LT(double(area), predicted * 1.25) << "predicted " << predicted;
}

TEST_F(RenderCamera, FrameEntryFillsThePictureWithItsBodies) {
  ASSERT_EQ(run_status_, 0) << run_log_;
  // the stones' extent in the picture, green pixels outside the legend (top left)
  auto extent = [](const Image& im, int* wide, int* tall) {
    int x0 = im.w, x1 = -1, y0 = im.h, y1 = -1;
    for (int py = 0; py < im.h; ++py)
      for (int px = 0; px < im.w; ++px) {
        if (px < im.w * 0.4 && py > im.h * 0.6) continue;
        if (!green(im.at(px, py))) continue;
        x0 = std::min(x0, px), x1 = std::max(x1, px), y0 = std::min(y0, py), y1 = std::max(y1, py);
      }
    *wide = x1 - x0, *tall = y1 - y0;
  };
  std::string log;
  ASSERT_EQ(render("whole.png", "--quiet", &log), 0) << log;
  ASSERT_EQ(render("stones.png", "--frame stone --quiet", &log), 0) << log;
  int w0 = 0, h0 = 0, w1 = 0, h1 = 0;
  extent(read_png(dir_ + "/whole.png"), &w0, &h0);
  extent(read_png(dir_ + "/stones.png"), &w1, &h1);
  // framed, the stones spread over at least 40 % of the picture's width or height (the fit puts
  // the bounding sphere of their box in view, and a flat box seen obliquely spans about half of
  // it), and over more of it than in the view of the whole run (the beads 3 m up, the leaf 2 m
  // away)
  EXPECT_TRUE(w1 >= 128 || h1 >= 96) << w1 << " x " << h1 << " pixels";
  EXPECT_GT(w1, 1.5 * w0) << w0 << " -> " << w1;
  // their spawn box given as numbers frames them too: the box spans about half the picture and
  // the 12 stones most of the box (their own box is smaller: framed it spreads them more)
  ASSERT_EQ(render("box.png", "--frame 0 1 0 1 0 0.05 --quiet", &log), 0) << log;
  int w2 = 0, h2 = 0;
  extent(read_png(dir_ + "/box.png"), &w2, &h2);
  EXPECT_TRUE(w2 >= 80 || h2 >= 60) << w2 << " x " << h2 << " pixels";
  EXPECT_LE(w2, w1 + 2) << "a box larger than the stones' own spreads them over more";
  EXPECT_GT(w2, 1.5 * w0) << w0 << " -> " << w2;
}

TEST_F(RenderCamera, StateColoursWhereTheBodiesAre) {
  ASSERT_EQ(run_status_, 0) << run_log_;
  ASSERT_EQ(last_.size(), kBodies);
  // the run's own states: the stones lie on the ground, the beads are in the air
  std::map<std::string, std::map<std::string, int>> states;
  for (const Last& l : last_) ++states[l.type][l.state];
  ASSERT_EQ(states["bead"]["flying"], 8) << "the beads should still be falling";
  ASSERT_GE(states["stone"]["resting"] + states["stone"]["sleeping"], 10)
      << "the stones should lie still";
  // from the side at 1 m, looking level: below the picture's middle is below 1 m
  std::string log;
  ASSERT_EQ(render("states.png",
                   "--color-by state --camera-position 0.5 -4 1 --camera-target 0.5 0.5 1 "
                   "--fov 50 --body-scale 3 --quiet",
                   &log),
            0)
      << log;
  const Image im = read_png(dir_ + "/states.png");
  ASSERT_EQ(im.w, 320);
  size_t flying_low = 0, flying_high = 0, still_low = 0, still_high = 0;
  for (int py = 0; py < im.h; ++py)
    for (int px = 0; px < im.w; ++px) {
      if (px < im.w * 0.4 && py > im.h * 0.55) continue;  // the legend
      const unsigned char* p = im.at(px, py);
      const bool high = py > im.h / 2;  // rows are bottom first
      if (orange(p)) (high ? flying_high : flying_low) += 1;
      // resting red or sleeping magenta: red with little green
      if (red(p) || (p[0] > 150 && p[2] > 150 && p[1] < 90)) (high ? still_high : still_low) += 1;
    }
  EXPECT_GT(flying_high, 20u) << "no flying (orange) bodies above";
  EXPECT_EQ(flying_low, 0u) << "flying colour below, where the bodies lie still";
  EXPECT_GT(still_low, 20u) << "no resting (red) bodies on the ground";
  EXPECT_EQ(still_high, 0u) << "resting colour up in the air";
}

TEST_F(RenderCamera, SpeedColoursFastBodiesWarmAndStillOnesBlue) {
  ASSERT_EQ(run_status_, 0) << run_log_;
  // the same side view: the beads fall at several m/s (the top of the scale: red to yellow), the
  // stones lie still (its bottom: blue)
  std::string log;
  ASSERT_EQ(render("speed.png",
                   "--color-by speed --camera-position 0.5 -4 1 --camera-target 0.5 0.5 1 "
                   "--fov 50 --body-scale 3 --quiet",
                   &log),
            0)
      << log;
  const Image im = read_png(dir_ + "/speed.png");
  ASSERT_EQ(im.w, 320);
  size_t warm_low = 0, warm_high = 0, cold_low = 0, cold_high = 0;
  for (int py = 0; py < im.h; ++py)
    for (int px = 0; px < im.w; ++px) {
      if (px < im.w * 0.4 && py > im.h * 0.55) continue;  // the legend
      if (px > im.w * 0.85) continue;                     // the colour bar
      const unsigned char* p = im.at(px, py);
      const bool high = py > im.h / 2;
      if (p[0] > p[2] + 60) (high ? warm_high : warm_low) += 1;
      if (p[2] > p[0] + 60) (high ? cold_high : cold_low) += 1;
    }
  EXPECT_GT(warm_high, 20u) << "no fast (warm) bodies in the air";
  EXPECT_EQ(cold_high, 0u) << "slow colour in the air";
  EXPECT_GT(cold_low, 20u) << "no still (blue) bodies on the ground";
  EXPECT_EQ(warm_low, 0u) << "fast colour on the ground";
}

TEST_F(RenderCamera, BadFlagsAreRefusedNamingFlagAndValue) {
  ASSERT_EQ(run_status_, 0) << run_log_;
  struct Case {
    std::string flags, says;
  };
  const Case cases[] = {
      {"--fov 0", "--fov 0"},
      {"--fov 180", "--fov 180"},
      {"--camera-position 1 2 3 --camera-target 1 2 3", "--camera-target 1 2 3"},
      {"--frame 1 0 0 1 0 1", "--frame 1 0 0 1 0 1: the box is empty"},
      {"--frame 0 1 0 1", "--frame 0 1 0 1"},
      {"--frame pebble", "the entries are: leaf, stone, bead"},
      {"--color-by colour", "--color-by"},
  };
  for (const Case& c : cases) {
    std::string log;
    EXPECT_EQ(render("bad.png", c.flags, &log), 2) << c.flags << "\n" << log;
    EXPECT_NE(log.find(c.says), std::string::npos) << c.flags << "\n" << log;
    EXPECT_FALSE(fs::exists(dir_ + "/bad.png")) << c.flags;
  }
  // results written without the bodies' states cannot be coloured by state
  fs::copy(dir_ + "/out", dir_ + "/nostate", fs::copy_options::recursive);
  {
    std::ifstream in(dir_ + "/out/trajectories.csv");
    std::ofstream out(dir_ + "/nostate/trajectories.csv");
    for (std::string line; std::getline(in, line);) out << line.substr(0, line.rfind(',')) << '\n';
  }
  std::string log;
  EXPECT_EQ(render("bad.png", "--color-by state", &log, "nostate"), 2) << log;
  EXPECT_NE(log.find("trajectories.csv: state"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir_ + "/bad.png"));
  // the same results draw by type
  EXPECT_EQ(render("nostate.png", "--quiet", &log, "nostate"), 0) << log;
}

}  // namespace
