// lrigid explain (issue 7): on the scenes in scenes/ it prints, per body type, the dimensionless
// numbers, the effects "auto" keeps and why it skips the others, and a cost estimate that follows
// bench/effects_bench (a sphere's closed-form step is cheaper than a flat body's). A scene it
// cannot read is an error that names the file.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <regex>
#include <string>
#include <vector>

namespace {

const std::string kLrigid = std::string(LRIGID_BINARY_DIR) + "/bin/lrigid";
const std::string kScenes = std::string(LRIGID_SOURCE_DIR) + "/scenes/";

struct Result {
  int rc = -1;
  std::string out;
};

Result explain(const std::string& scene) {
  Result r;
  FILE* p = popen((kLrigid + " explain " + scene + " 2>&1").c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  const int rc = pclose(p);
  r.rc = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  return r;
}

// the "auto chooses" line and the cost estimate of each body type, in order
struct TypeReport {
  std::string chooses;
  double cost_ns = 0;
};

std::vector<TypeReport> types(const std::string& out) {
  std::vector<TypeReport> t;
  const std::regex chooses("auto chooses: ([^\n]*)"), cost("estimated cost: ([0-9.]+) ns");
  for (std::sregex_iterator i(out.begin(), out.end(), chooses), e; i != e; ++i)
    t.push_back({(*i)[1].str(), 0});
  size_t k = 0;
  for (std::sregex_iterator i(out.begin(), out.end(), cost), e; i != e && k < t.size(); ++i)
    t[k++].cost_ns = std::stod((*i)[1].str());
  return t;
}

TEST(CliExplain, FlutterPlateKeepsLiftAndSaysWhyItSkipsTheRest) {
  const Result r = explain(kScenes + "plate_flutter.json");
  ASSERT_EQ(r.rc, 0) << r.out;
  const auto t = types(r.out);
  ASSERT_EQ(t.size(), 1u) << r.out;
  EXPECT_EQ(t[0].chooses, "gravity, buoyancy, added_mass, drag, lift");
  EXPECT_NE(r.out.find("flat: yes"), std::string::npos);
  EXPECT_NE(r.out.find("mean_flow   0          skip: the field's U is zero"), std::string::npos);
  EXPECT_NE(r.out.find("skip: Re = "), std::string::npos) << "Basset skipped for its Re";
  EXPECT_NE(r.out.find("estimated total:"), std::string::npos);
}

TEST(CliExplain, CardGetsLiftBeadDoesNotAndTheSphereIsCheaper) {
  const Result r = explain(kScenes + "uniform_box.json");
  ASSERT_EQ(r.rc, 0) << r.out;
  const auto t = types(r.out);
  ASSERT_EQ(t.size(), 2u) << r.out;
  EXPECT_NE(t[0].chooses.find("lift"), std::string::npos) << "paper card: " << t[0].chooses;
  EXPECT_NE(t[0].chooses.find("turbulence"), std::string::npos);
  EXPECT_EQ(t[1].chooses.find("lift"), std::string::npos) << "bead: " << t[1].chooses;
  EXPECT_NE(t[1].chooses.find("buoyancy"), std::string::npos) << "30 kg/m^3 bead in air";
  EXPECT_GT(t[0].cost_ns, 0.0);
  EXPECT_GT(t[1].cost_ns, 0.0);
  EXPECT_LT(t[1].cost_ns, t[0].cost_ns) << "closed-form sphere step vs iterated plate step";
  // each takes its batched step, and the output says so
  const size_t card = r.out.find("step: batched (plates and ellipsoids), 32 bodies per block");
  const size_t bead = r.out.find("step: batched (spheres), 32 bodies per block");
  EXPECT_NE(card, std::string::npos) << r.out;
  EXPECT_NE(bead, std::string::npos) << r.out;
  EXPECT_LT(card, bead) << "card first, as in the scene";
}

TEST(CliExplain, SpunBallGetsMagnus) {
  const Result r = explain(kScenes + "art_variation.json");
  ASSERT_EQ(r.rc, 0) << r.out;
  const auto t = types(r.out);
  ASSERT_FALSE(t.empty());
  EXPECT_NE(t.back().chooses.find("magnus"), std::string::npos) << t.back().chooses;
  for (size_t i = 0; i + 1 < t.size(); ++i)
    EXPECT_EQ(t[i].chooses.find("magnus"), std::string::npos) << "petal " << i;
}

TEST(CliExplain, MissingSceneIsAnErrorNamingTheFile) {
  const Result r = explain("/nonexistent/scene.json");
  EXPECT_NE(r.rc, 0);
  EXPECT_NE(r.out.find("/nonexistent/scene.json"), std::string::npos) << r.out;
}

}  // namespace
