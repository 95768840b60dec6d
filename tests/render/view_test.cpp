// lrigid view (label render): the live window, run by script under xvfb-run. The window opens and
// draws bodies that move between frames, the heads-up text is drawn, the keys act on the
// simulation (through --press and the --log of the heads-up line), the grid's solids and slice
// are drawn, and a bad scene is reported exactly as `lrigid run` reports it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "support/shell_png.h"
#include "support/vti_writer.h"

namespace {

namespace fs = std::filesystem;
using lrigid::test::Image;
using lrigid::test::read_png;
using lrigid::test::sh;

const std::string kLrigid = std::string(LRIGID_BINARY_DIR) + "/bin/lrigid";

// cards and beads dropped in a light wind; they land within about a second
std::string scene_json(const std::string& fluid, int count = 12) {
  const std::string n = std::to_string(count);
  return R"({
  "version": 1,
  "fluid": { "density": 1.204, "kinematic_viscosity": 1.5e-5, )" +
         fluid + R"( },
  "gravity": [0, 0, -9.81],
  "effects": "auto",
  "integrator": { "scheme": "splitting", "dt": 0.002 },
  "duration": 3.0,
  "seed": 3,
  "ground": { "z": 0.0 },
  "bodies": [
    { "name": "card", "shape": { "type": "box", "size": [0.09, 0.05, 0.002] }, "density": 700,
      "count": )" + n + R"(, "spawn_box": [[0.2, 0.5, 0.8], [1.0, 1.5, 1.6]], "orientation": "random" },
    { "name": "bead", "shape": { "type": "sphere", "radius": 0.02 }, "density": 100,
      "count": )" + n + R"(, "spawn_box": [[0.2, 0.5, 0.8], [1.0, 1.5, 1.6]] }
  ],
  "output": { "every": 0.05, "formats": ["csv"] }
})";
}

const char* kUniform = R"("uniform": { "U": [1.0, 0.0, 0.0], "k": 0.1, "epsilon": 0.05 })";

class View : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = ::testing::TempDir() + "view_test_" + std::to_string(::getpid());
    fs::create_directories(dir_);
    std::ofstream(dir_ + "/scene.json") << scene_json(kUniform);
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static std::string view(const std::string& scene, const std::string& flags) {
    return "xvfb-run -a " + kLrigid + " view " + scene + " --threads 1 --width 320 --height 240 " +
           flags;
  }
  static std::string dir_;
};
std::string View::dir_;

// pixels whose colour differs by more than 30 (sum over r, g, b) in rows [y0, y1)
size_t differing(const Image& a, const Image& b, int y0, int y1) {
  size_t n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = 0; x < a.w; ++x) {
      const unsigned char *p = a.at(x, y), *q = b.at(x, y);
      n += std::abs(p[0] - q[0]) + std::abs(p[1] - q[1]) + std::abs(p[2] - q[2]) > 30;
    }
  return n;
}

// pixels in a body type's colour (shaded): cards orange, beads green (the background is
// grey-blue; no body type is blue, the colour of the k slices), outside the legend (top left)
void count_bodies(const Image& im, size_t* orange, size_t* green) {
  *orange = *green = 0;
  for (int y = 0; y < im.h; ++y)
    for (int x = 0; x < im.w; ++x) {
      if (x < im.w * 0.35 && y > im.h / 2) continue;  // the legend's swatches, top left
      const unsigned char* p = im.at(x, y);
      *orange += p[0] > p[1] + 40 && p[1] > p[2] + 20;
      *green += p[1] > p[0] + 40 && p[1] > p[2] + 40;
    }
}

TEST_F(View, HelpListsTheControls) {
  std::string out;
  ASSERT_EQ(sh(kLrigid + " view --help", &out), 0) << out;
  for (const char* s : {"space", "pause", "+ / -", "mean flow", "] / [", "turbulence",
                        "restart", "screenshot", "start / stop writing", "--frames",
                        "--screenshot", "--write-frames", "--pace"})
    EXPECT_NE(out.find(s), std::string::npos) << "--help lacks \"" << s << "\":\n" << out;
}

TEST_F(View, TakesRendersCameraAndColourFlags) {
  // the flags are render's (app/draw_style.cpp, tests/render/render_camera_test.cpp): at the
  // start every body flies, so coloured by state the picture shows the flying colour (orange)
  // and none of the entry colour of the beads (green)
  const std::string png = dir_ + "/state.png";
  std::string log;
  ASSERT_EQ(sh(view(dir_ + "/scene.json", "--frames 1 --pace fixed --no-hud --frame bead "
                                          "--color-by state --fov 40 --screenshot " + png),
               &log),
            0)
      << log;
  const Image im = read_png(png);
  ASSERT_EQ(im.w, 320);
  size_t orange = 0, green = 0;
  count_bodies(im, &orange, &green);
  EXPECT_GT(orange, 40u) << "no flying bodies";
  EXPECT_LT(green, 5u) << "bodies in their entry's colour";
  for (const auto& [flags, says] :
       {std::pair<std::string, std::string>{"--fov 0", "--fov 0"},
        {"--frame pebble", "the entries are: card, bead"}}) {
    EXPECT_EQ(sh(view(dir_ + "/scene.json", "--frames 1 " + flags), &log), 2) << flags << log;
    EXPECT_NE(log.find(says), std::string::npos) << flags << "\n" << log;
  }
}

TEST_F(View, WindowOpensAndBodiesMoveInRealTime) {
  const std::string frames = dir_ + "/frames";
  std::string log;
  // realtime pace: 10 frames at 10 frames/s are about a second of falling
  ASSERT_EQ(sh(view(dir_ + "/scene.json", "--frames 10 --fps 10 --no-hud --write-frames " + frames),
               &log),
            0)
      << log;
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(frames)) files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  ASSERT_EQ(files.size(), 11u) << log;  // the first frame (t = 0) and 10 more
  EXPECT_EQ(fs::path(files.front()).filename(), "frame_000000.png");
  const Image first = read_png(files.front()), last = read_png(files.back());
  ASSERT_EQ(first.w, 320);
  ASSERT_EQ(first.h, 240);
  ASSERT_EQ(last.w, 320);
  size_t orange = 0, green = 0;
  count_bodies(first, &orange, &green);
  EXPECT_GT(orange, 10u) << "no card pixels";
  EXPECT_GT(green, 10u) << "no bead pixels";
  // the bodies fell: the two frames differ (there is nothing else that moves)
  EXPECT_GT(differing(first, last, 0, first.h), 50u);
}

TEST_F(View, HeadsUpTextIsDrawn) {
  // fixed pace: 3 frames are 0.3 s of simulated time whatever the machine, so the bodies are
  // drawn at the same places in both runs and only the text differs
  const std::string with = dir_ + "/hud.png", without = dir_ + "/nohud.png";
  std::string log;
  ASSERT_EQ(sh(view(dir_ + "/scene.json", "--pace fixed --fps 10 --frames 3 --screenshot " + with),
               &log),
            0)
      << log;
  ASSERT_EQ(sh(view(dir_ + "/scene.json",
                    "--pace fixed --fps 10 --frames 3 --no-hud --screenshot " + without),
               &log),
            0)
      << log;
  const Image a = read_png(with), b = read_png(without);
  ASSERT_EQ(a.w, 320);
  ASSERT_EQ(b.w, 320);
  // three lines of text at the bottom (rows from the bottom: VTK's order)
  const size_t text = differing(a, b, 0, 50), rest = differing(a, b, 50, a.h);
  EXPECT_GT(text, 150u) << "no heads-up text";
  EXPECT_LT(rest, 10u) << "the runs differ away from the text";
  // the text is dark on the light background
  size_t dark = 0;
  for (int y = 0; y < 50; ++y)
    for (int x = 0; x < a.w; ++x) dark += a.at(x, y)[0] < 90 && a.at(x, y)[2] < 110;
  EXPECT_GT(dark, 100u);
}

struct LogLine {
  double t = -1;
  std::string text;
};

// "frame N: t = T / D s ..." and the next line, by frame
std::vector<LogLine> parse_log(const std::string& out) {
  std::vector<LogLine> lines;
  std::istringstream in(out);
  std::string l;
  const std::regex re("^frame ([0-9]+): t = ([0-9.]+) / ");
  while (std::getline(in, l)) {
    std::smatch m;
    if (!std::regex_search(l, m, re)) continue;
    const size_t f = std::stoul(m[1].str());
    std::string second;
    std::getline(in, second);
    if (lines.size() <= f) lines.resize(f + 1);
    lines[f] = {std::stod(m[2].str()), l + "\n" + second};
  }
  return lines;
}

TEST_F(View, KeysActOnTheSimulation) {
  std::string out;
  ASSERT_EQ(sh(view(dir_ + "/scene.json",
                    "--pace fixed --fps 10 --frames 12 --log --press 2:+ --press 3:] "
                    "--press 3:] --press 5:space --press 8:space --press 10:r --press 11:-"),
               &out),
            0)
      << out;
  const std::vector<LogLine> f = parse_log(out);
  ASSERT_EQ(f.size(), 13u) << out;
  EXPECT_NEAR(f[0].t, 0.0, 1e-9);
  EXPECT_NEAR(f[1].t, 0.1, 1e-9) << f[1].text;  // fixed pace: 1/fps of simulated time per frame
  EXPECT_NE(f[1].text.find("mean flow x1 "), std::string::npos) << f[1].text;
  EXPECT_NE(f[1].text.find("fixed"), std::string::npos) << f[1].text;  // the pace is shown
  // + before frame 2: the worker's model has the scaled mean flow
  EXPECT_NE(f[2].text.find("mean flow x1.25"), std::string::npos) << f[2].text;
  EXPECT_NE(f[3].text.find("turbulence x1.56"), std::string::npos) << f[3].text;
  // paused before frame 5, resumed before frame 8: simulated time stands still in between
  for (int i = 5; i < 8; ++i) {
    EXPECT_NE(f[i].text.find("PAUSED"), std::string::npos) << f[i].text;
    EXPECT_DOUBLE_EQ(f[i].t, f[4].t) << f[i].text;
  }
  EXPECT_EQ(f[8].text.find("PAUSED"), std::string::npos) << f[8].text;
  EXPECT_GT(f[8].t, f[7].t);
  // r before frame 10: the next seed, time back to 0 (plus the frame's 0.1 s); the scales stay
  EXPECT_NE(f[9].text.find("seed 3"), std::string::npos) << f[9].text;
  EXPECT_NE(f[10].text.find("seed 4"), std::string::npos) << f[10].text;
  EXPECT_NEAR(f[10].t, 0.1, 1e-9) << f[10].text;
  EXPECT_NE(f[12].text.find("mean flow x1 "), std::string::npos) << f[12].text;  // - undid +
}

TEST_F(View, GridSolidsAndSliceAreDrawn) {
  // a 4 x 2 x 2 m grid with wind along x; the second has a solid block downwind of the bodies
  for (const bool block : {false, true}) {
    lrigid::test::VtiGrid g;
    g.dims = {17, 9, 9};
    g.spacing = {0.25, 0.25, 0.25};
    if (block)
      g.solid = [](const std::array<double, 3>& x) {
        return x[0] >= 2.25 && x[0] <= 3.0 && x[1] >= 0.5 && x[1] <= 1.5 && x[2] <= 1.0;
      };
    ASSERT_TRUE(lrigid::test::write_vti(
        dir_ + (block ? "/block.vti" : "/open.vti"), g,
        [](int, const std::array<double, 3>& x, float U[3], float* k, float* eps) {
          U[0] = float(0.5 + 0.5 * x[2]);
          U[1] = U[2] = 0;
          *k = float(0.05 + 0.02 * x[0]);
          *eps = 0.02f;
        }));
    std::ofstream(dir_ + (block ? "/block.json" : "/open.json"))
        << scene_json(std::string("\"field\": \"") + (block ? "block.vti" : "open.vti") + "\"", 4);
  }
  std::string log;
  for (const char* s : {"open", "block"})
    ASSERT_EQ(sh(view(dir_ + "/" + s + ".json", std::string("--pace fixed --frames 1 --no-hud "
                                                            "--screenshot ") +
                                                   dir_ + "/" + s + ".png"),
                 &log),
              0)
        << log;
  ASSERT_EQ(sh(view(dir_ + "/open.json",
                    "--pace fixed --frames 1 --no-hud --slice U --screenshot " + dir_ + "/U.png"),
               &log),
            0)
      << log;
  const Image open = read_png(dir_ + "/open.png"), block = read_png(dir_ + "/block.png"),
              slice = read_png(dir_ + "/U.png");
  ASSERT_EQ(open.w, 320);
  ASSERT_EQ(block.w, 320);
  ASSERT_EQ(slice.w, 320);
  EXPECT_GT(differing(open, block, 0, open.h), 300u) << "the solid block is not drawn";
  EXPECT_GT(differing(open, slice, 0, open.h), 1000u) << "the |U| slice is not drawn";
  // a slice needs a grid
  ASSERT_EQ(sh(view(dir_ + "/scene.json", "--frames 1 --slice k"), &log), 2) << log;
  EXPECT_NE(log.find("needs a grid"), std::string::npos) << log;
}

TEST_F(View, SceneErrorsReadAsInRun) {
  std::string good = scene_json(kUniform);
  const std::string bad = std::regex_replace(good, std::regex("\"density\": 700"),
                                             "\"density\": -700");
  ASSERT_NE(bad, good);
  std::ofstream(dir_ + "/bad.json") << bad;
  std::string run_out, view_out, nodisplay_out;
  const int run_rc = sh(kLrigid + " run " + dir_ + "/bad.json -o " + dir_ + "/bad_out", &run_out);
  const int view_rc = sh(view(dir_ + "/bad.json", "--frames 1"), &view_out);
  EXPECT_EQ(run_rc, 3) << run_out;  // bad input
  EXPECT_EQ(view_rc, run_rc) << view_out;
  EXPECT_EQ(view_out, run_out);
  EXPECT_NE(view_out.find("density"), std::string::npos) << view_out;
  // the scene is read before the display is needed: the same message without X
  const int nodisplay_rc =
      sh("env -u DISPLAY " + kLrigid + " view " + dir_ + "/bad.json --frames 1", &nodisplay_out);
  EXPECT_EQ(nodisplay_rc, run_rc);
  EXPECT_EQ(nodisplay_out, run_out);
  // a good scene without X: a clear error that says how to run it
  const int rc = sh("env -u DISPLAY " + kLrigid + " view " + dir_ + "/scene.json --frames 1",
                    &nodisplay_out);
  EXPECT_EQ(rc, 1) << nodisplay_out;
  EXPECT_NE(nodisplay_out.find("xvfb-run"), std::string::npos) << nodisplay_out;
}

}  // namespace
