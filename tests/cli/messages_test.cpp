// Messages that say what to do: a negative --seed or --checkpoint-every prints a readable
// bound (CLI11's own check would print the largest double in full, 309 digits), and
// `added-mass --help` states the panel counts that lrigid added-mass actually uses.
#include <gtest/gtest.h>

#include <algorithm>
#include <regex>
#include <string>

#include "support/shell.h"

namespace {

const std::string kLrigid = std::string(LRIGID_BINARY_DIR) + "/bin/lrigid";
const std::string kScene = std::string(LRIGID_SOURCE_DIR) + "/scenes/uniform_box.json";

struct Result {
  int rc = -1;
  std::string out;  // stdout and stderr
};

Result lrigid(const std::string& args) {
  Result r;
  r.rc = lrigid::test::sh(kLrigid + " " + args, &r.out);
  return r;
}

TEST(Messages, NegativeSeedSaysWhatToGiveInAFewWords) {
  for (const char* cmd : {"run", "view"}) {
    const Result r = lrigid(std::string(cmd) + " " + kScene + " --seed -1");
    EXPECT_EQ(r.rc, 2) << r.out;
    EXPECT_NE(r.out.find("--seed: -1 is negative: give a whole number, 0 or more (the random "
                         "seed)"),
              std::string::npos) << r.out;
    EXPECT_LT(r.out.size(), 200u) << "no 300-digit bound: " << r.out;
  }
  const Result c = lrigid("run " + kScene + " --checkpoint-every -2");
  EXPECT_EQ(c.rc, 2);
  EXPECT_NE(c.out.find("--checkpoint-every: -2 is negative: give seconds, 0 or more"),
            std::string::npos) << c.out;
}

// the panel count added-mass reports for a shape (its --json "panels")
int panels_of(const std::string& shape_args) {
  const Result r = lrigid("added-mass " + shape_args + " --json");
  std::smatch m;
  if (r.rc != 0 || !std::regex_search(r.out, m, std::regex("\"panels\": *([0-9]+)"))) return -1;
  return std::stoi(m[1].str());
}

TEST(Messages, AddedMassHelpStatesThePanelCountsUsed) {
  const Result h = lrigid("added-mass --help");
  ASSERT_EQ(h.rc, 0) << h.out;
  std::smatch cube, plate, mesh;
  ASSERT_TRUE(std::regex_search(h.out, cube, std::regex("a cube ([0-9]+)"))) << h.out;
  ASSERT_TRUE(std::regex_search(h.out, plate, std::regex("a thin plate ([0-9]+)"))) << h.out;
  ASSERT_TRUE(std::regex_search(h.out, mesh, std::regex("12 triangles give ([0-9]+)"))) << h.out;
  EXPECT_EQ(panels_of("--box 1 1 1"), std::stoi(cube[1].str()));
  EXPECT_EQ(panels_of("--box 1 1 0.01"), std::stoi(plate[1].str()));
  // a cube of 6 quads: 12 triangles
  EXPECT_EQ(panels_of("--mesh " + std::string(LRIGID_SOURCE_DIR) +
                      "/tests/data/meshes/cube_quads.obj"),
            std::stoi(mesh[1].str()));
}

// The progress line counts each body once: moving (flying or sliding), resting (or asleep),
// landed and stopped add up to the bodies of the scene, with some of them resting on the ground.
TEST(Messages, ProgressLineCountsEachBodyOnce) {
  const Result r = lrigid("run " + kScene + " -o \"$(mktemp -d)/out\"");
  ASSERT_EQ(r.rc, 0) << r.out;
  const std::regex line("moving ([0-9]+), resting ([0-9]+), landed ([0-9]+), stopped ([0-9]+)");
  int lines = 0, most_resting = 0;
  for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), line);
       it != std::sregex_iterator(); ++it, ++lines) {
    const int moving = std::stoi((*it)[1].str()), resting = std::stoi((*it)[2].str());
    EXPECT_EQ(moving + resting + std::stoi((*it)[3].str()) + std::stoi((*it)[4].str()), 400)
        << it->str();
    most_resting = std::max(most_resting, resting);
  }
  EXPECT_GE(lines, 5) << r.out;
  EXPECT_GT(most_resting, 0) << "no body rests on the ground: the check above checks nothing\n"
                             << r.out;
}

}  // namespace
