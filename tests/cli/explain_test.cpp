// lrigid explain: on the scenes in scenes/ it prints, per body type, the dimensionless
// numbers, the effects "auto" keeps and why it skips the others, and a cost estimate that follows
// bench/effects_bench (a sphere's closed-form step is cheaper than a flat body's). A scene it
// cannot read is an error that names the file.
#include <gtest/gtest.h>

#include <unistd.h>

#include <array>
#include <cmath>
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

// explain of a scene given as text, written to a temporary folder removed afterwards
Result explain_text(const std::string& scene) {
  char tmpl[] = "/tmp/lrigid_explain_XXXXXX";
  if (!mkdtemp(tmpl)) return Result{};
  const std::string dir = tmpl, path = dir + "/scene.json";
  FILE* f = fopen(path.c_str(), "w");
  if (!f) return Result{};
  fputs(scene.c_str(), f);
  fclose(f);
  const Result r = explain(path);
  std::remove(path.c_str());
  rmdir(dir.c_str());
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
  EXPECT_LT(t[1].cost_ns, t[0].cost_ns) << "closed-form sphere flow vs iterated plate flow";
  // each takes its batched step, and the output says so
  const size_t card = r.out.find("step: batched (diagonal M), 32 bodies per block");
  const size_t bead = r.out.find("step: batched (isotropic M), 32 bodies per block");
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

// each body type says when its entry's bodies are released: all at t = 0, by rate, or in bursts
TEST(CliExplain, SaysWhenEachEntrysBodiesAreReleased) {
  const std::string ball = R"("shape": {"type": "sphere", "radius": 0.005}, "density": 2500,
      "position": [0, 0, 1])";
  const Result r = explain_text(R"({"version": 1,
    "fluid": {"density": 1.2, "kinematic_viscosity": 1.5e-5,
              "uniform": {"U": [1, 0, 0], "k": 0.1, "epsilon": 0.01}},
    "gravity": [0, 0, -9.81], "effects": "auto", "integrator": {"scheme": "strang", "dt": 0.002},
    "duration": 10, "seed": 1, "bodies": [
      {"name": "now", )" + ball + R"(, "count": 3},
      {"name": "rate", )" + ball + R"(, "count": 10, "release": {"rate": 4, "start": 0.5}},
      {"name": "bursts", )" + ball + R"(, "count": 10, "release": {"times": [1, 2, 3]}}]})");
  ASSERT_EQ(r.rc, 0) << r.out;
  EXPECT_NE(r.out.find("released: all at t = 0\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("released: 4 bodies per second from t = 0.5 s: body k of the entry at "
                       "0.5 + k / 4 s, the last (k = 9) at 2.75 s\n"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("released: in 3 bursts from t = 1 s to 3 s: 3 bodies each, 4 in the "
                       "first 1 of them\n"),
            std::string::npos)
      << r.out;
}

// each body type starts with one plain sentence, and the sentence agrees with the
// numbers printed under it: the settling speed, falls or rises, the turbulence response
TEST(CliExplain, EachBodyTypeStartsWithAPlainSentenceThatMatchesItsNumbers) {
  char tmpl[] = "/tmp/lrigid_explain_XXXXXX";
  ASSERT_NE(mkdtemp(tmpl), nullptr);
  const std::string dir = tmpl, path = dir + "/scene.json";
  // a steel ball in short-lived turbulence (k/eps = 0.01 s), and a bubble in water
  FILE* f = fopen(path.c_str(), "w");
  ASSERT_NE(f, nullptr);
  fputs(R"({"version": 1, "fluid": {"density": 1000, "kinematic_viscosity": 1e-6,
    "uniform": {"U": [0.01, 0, 0], "k": 1e-3, "epsilon": 0.1}}, "gravity": [0, 0, -9.81],
    "effects": ["gravity", "buoyancy", "added_mass", "drag", "mean_flow", "turbulence"], "integrator": {"scheme": "splitting", "dt": 0.001}, "duration": 0.1, "seed": 1,
    "bodies": [
      {"name": "steel", "shape": {"type": "sphere", "radius": 0.01}, "density": 7800,
       "count": 1, "position": [0, 0, 1]},
      {"name": "bubble", "shape": {"type": "sphere", "radius": 0.001}, "density": 1.2,
       "count": 1, "position": [0, 0, 1]}]})",
        f);
  fclose(f);
  const Result r = explain(path);
  std::remove(path.c_str());
  rmdir(dir.c_str());
  ASSERT_EQ(r.rc, 0) << r.out;
  const std::regex block(
      "body type [0-9]+ \"([a-z_]+)\"[^\n]*\n  In plain words: ([^\n]*)\n[^\n]*\n"
      "  size d = [^ ]+ m   settling speed = ([0-9.e+-]+) m/s[^\n]*\n"
      "  tau_p = [^ ]+ s   St\\(k/eps\\) = ([0-9.e+-]+)");
  std::vector<std::vector<std::string>> seen;
  for (std::sregex_iterator i(r.out.begin(), r.out.end(), block), e; i != e; ++i)
    seen.push_back({(*i)[1].str(), (*i)[2].str(), (*i)[3].str(), (*i)[4].str()});
  ASSERT_EQ(seen.size(), 2u) << r.out;
  char speed[32];
  // steel: falls, at the settling speed printed below (2 digits), turbulence barely moves it
  EXPECT_EQ(seen[0][0], "steel");
  std::snprintf(speed, sizeof speed, "%.2g m/s", std::stod(seen[0][2]));
  EXPECT_NE(seen[0][1].find(std::string("falls at about ") + speed), std::string::npos)
      << seen[0][1];
  ASSERT_GT(std::stod(seen[0][3]), 3.0) << "St(k/eps) of the steel ball";
  EXPECT_EQ(seen[0][1].find("Heavy enough that turbulence barely moves it;"), 0u)
      << seen[0][1];
  EXPECT_NE(seen[0][1].find("round, so it does not flutter"), std::string::npos);
  // bubble: rises
  EXPECT_EQ(seen[1][0], "bubble");
  std::snprintf(speed, sizeof speed, "%.2g m/s", std::stod(seen[1][2]));
  EXPECT_NE(seen[1][1].find(std::string("rises at about ") + speed + " (lighter than the water)"),
            std::string::npos)
      << seen[1][1];
  EXPECT_NE(r.out.find("docs/effects.md, \"Glossary\""), std::string::npos);
  // the flat leaf of the wind scene flutters
  const Result leaves = explain(kScenes + "plate_flutter.json");
  EXPECT_NE(leaves.out.find("In plain words: No turbulence moves it (the flow has none); falls "
                            "at about"),
            std::string::npos)
      << leaves.out;
  EXPECT_NE(leaves.out.find("its flat shape makes it flutter and tumble."), std::string::npos);
}

// crossing trajectories: a glass bead settling through air turbulence at about u' gets Csanady's
// factors b = (1 + 0.64 r^2)^1/2 along its drift and b' = (1 + 2.56 r^2)^1/2 across it, r = v_d / u'
// as printed, and a sentence saying it spreads sideways b' times less; a neutral tracer and the
// scene key false turn it off, each with its reason
TEST(CliExplain, CrossingTrajectoriesPrintTheDriftAndCsanadysFactors) {
  char tmpl[] = "/tmp/lrigid_explain_XXXXXX";
  ASSERT_NE(mkdtemp(tmpl), nullptr);
  const std::string dir = tmpl, path = dir + "/scene.json";
  auto write = [&](const char* turbulence) {
    FILE* f = fopen(path.c_str(), "w");
    ASSERT_NE(f, nullptr);
    fprintf(f, R"({"version": 1, "fluid": {"density": 1.2, "kinematic_viscosity": 1.5e-5,
      "uniform": {"U": [0, 0, 0], "k": 0.015, "epsilon": 0.005}}, "gravity": [0, 0, -9.81],
      "effects": ["gravity", "buoyancy", "drag", "turbulence"], "duration": 0.1, "seed": 1,
      "integrator": {"scheme": "strang", "dt": 0.001},
      "turbulence": %s,
      "bodies": [
        {"name": "bead", "shape": {"type": "sphere", "radius": 2e-5}, "density": 2500,
         "count": 1, "position": [0, 0, 1]},
        {"name": "tracer", "shape": {"type": "sphere", "radius": 2e-5}, "density": 1.2,
         "count": 1, "position": [0, 0, 1]}]})",
            turbulence);
    fclose(f);
  };
  write(R"({"model": "seen"})");
  const Result on = explain(path);
  write(R"({"model": "seen", "crossing_trajectories": false})");
  const Result off = explain(path);
  std::remove(path.c_str());
  rmdir(dir.c_str());
  ASSERT_EQ(on.rc, 0) << on.out;
  ASSERT_EQ(off.rc, 0) << off.out;
  std::smatch m;
  const std::regex line(
      "crossing trajectories: drift ([0-9.e+-]+) m/s = ([0-9.e+-]+) u'; time scale of the "
      "velocity it sees / ([0-9.e+-]+) along the drift, / ([0-9.e+-]+) across it");
  ASSERT_TRUE(std::regex_search(on.out, m, line)) << on.out;
  const double r = std::stod(m[2].str()), along = std::stod(m[3].str()),
               across = std::stod(m[4].str());
  EXPECT_GT(r, 0.8);  // a 20 um glass bead settles at about u' = 0.1 m/s
  EXPECT_LT(r, 1.5);
  // to the printing (three digits of r)
  EXPECT_NEAR(along, std::sqrt(1 + 0.64 * r * r), 1e-2 * along);
  EXPECT_NEAR(across, std::sqrt(1 + 2.56 * r * r), 1e-2 * across);
  EXPECT_NE(on.out.find("so they spread it sideways about"), std::string::npos) << on.out;
  // the tracer (as dense as the air) has no drift; the key false turns it off for both
  EXPECT_NE(on.out.find("crossing trajectories: off (no drift"), std::string::npos) << on.out;
  EXPECT_EQ(off.out.find("crossing trajectories: drift"), std::string::npos) << off.out;
  EXPECT_NE(off.out.find("crossing trajectories: off (turbulence.crossing_trajectories is "
                         "false)"),
            std::string::npos)
      << off.out;
}

// an artist's leaf from an OBJ (curled and turned: a full 6 x 6 generalized mass) takes the
// batched step, as the box leaf does, with every scheme: explain says neither "not batched: the
// generalized mass is not diagonal" nor "no batched kernels yet"
TEST(CliExplain, MeshLeafTakesTheBatchedStep) {
  for (const std::string scheme : {"splitting", "strang", "euler", "rk4"}) {
    const std::string mesh = std::string(LRIGID_SOURCE_DIR) + "/tests/data/meshes/bent_leaf.obj";
    const Result r = explain_text(R"({"version": 1, "fluid": {"density": 1.204, "kinematic_viscosity": 1.5e-5,
      "uniform": {"U": [2, 0, 0], "k": 0.05, "epsilon": 0.02}}, "gravity": [0, 0, -9.81],
      "effects": ["gravity", "buoyancy", "added_mass", "drag", "lift", "mean_flow", "turbulence"],
      "integrator": {"scheme": ")" + scheme + R"(", "dt": 0.002}, "duration": 0.1, "seed": 1,
      "bodies": [{"name": "curled_leaf", "shape": {"type": "mesh", "file": ")" + mesh +
                                  R"("}, "density": 600, "count": 10, "position": [0, 0, 5]}]})");
    ASSERT_EQ(r.rc, 0) << scheme << ": " << r.out;
    // a curved leaf: its generalized mass couples every direction
    EXPECT_NE(r.out.find("step: batched (full M)"), std::string::npos)
        << scheme << ": " << r.out;
    EXPECT_EQ(r.out.find("not batched"), std::string::npos) << scheme << ": " << r.out;
  }
}

// an artist's single-sided leaf (open, quads, UVs) with a thickness: the thin leaf it stands
// for, flat, on the batched step, with the mass of the closed leaf of the same thickness
TEST(CliExplain, AnOpenLeafSurfaceWithItsThicknessIsTheClosedLeaf) {
  const std::string meshes = std::string(LRIGID_SOURCE_DIR) + "/tests/data/meshes/";
  auto explain_leaf = [&](const std::string& shape) {
    return explain_text(R"({"version": 1, "fluid": {"density": 1.204, "kinematic_viscosity": 1.5e-5,
      "uniform": {"U": [2, 0, 0], "k": 0.05, "epsilon": 0.02}}, "gravity": [0, 0, -9.81],
      "effects": "auto", "integrator": {"scheme": "strang", "dt": 0.002}, "duration": 0.1,
      "seed": 1, "bodies": [{"name": "leaf", "shape": )" +
                        shape + R"(, "density": 600, "count": 10, "position": [0, 0, 5]}]})");
  };
  const Result open = explain_leaf(R"({"type": "mesh", "file": ")" + meshes +
                                   R"(leaf_surface.obj", "thickness": 0.0004})");
  ASSERT_EQ(open.rc, 0) << open.out;
  EXPECT_NE(open.out.find("flat: yes"), std::string::npos) << open.out;
  EXPECT_NE(open.out.find("step: batched (full M)"), std::string::npos) << open.out;
  const Result closed =
      explain_leaf(R"({"type": "mesh", "file": ")" + meshes + R"(bent_leaf.obj"})");
  ASSERT_EQ(closed.rc, 0) << closed.out;
  const std::regex mass("mass ([0-9.e+-]+) kg");
  std::smatch a, b;
  ASSERT_TRUE(std::regex_search(open.out, a, mass)) << open.out;
  ASSERT_TRUE(std::regex_search(closed.out, b, mass)) << closed.out;
  EXPECT_EQ(a[1].str(), b[1].str());  // to the digits printed
  EXPECT_GT(std::stod(a[1].str()), 0.0);
}

// spheres take the batched step on every scheme, euler and rk4 too, and the estimate follows the schemes' measured costs: euler a little cheaper than
// splitting, rk4 (four force evaluations, three more samples) about 2.3 times it
TEST(CliExplain, SpheresTakeTheBatchedStepOnEveryScheme) {
  char tmpl[] = "/tmp/lrigid_explain_XXXXXX";
  ASSERT_NE(mkdtemp(tmpl), nullptr);
  const std::string dir = tmpl, path = dir + "/scene.json";
  double cost[3] = {0, 0, 0};
  const char* schemes[3] = {"euler", "splitting", "rk4"};
  for (int k = 0; k < 3; ++k) {
    FILE* f = fopen(path.c_str(), "w");
    ASSERT_NE(f, nullptr);
    fputs((R"({"version": 1, "fluid": {"density": 1.204, "kinematic_viscosity": 1.5e-5,
      "uniform": {"U": [2, 0, 0], "k": 0.05, "epsilon": 0.02}}, "gravity": [0, 0, -9.81],
      "effects": ["gravity", "buoyancy", "added_mass", "drag", "mean_flow", "turbulence"],
      "integrator": {"scheme": ")" + std::string(schemes[k]) + R"(", "dt": 0.002},
      "duration": 0.1, "seed": 1,
      "bodies": [{"name": "glass_bead", "shape": {"type": "sphere", "radius": 0.00025},
        "density": 2500, "count": 10, "position": [0, 0, 5]}]})")
              .c_str(),
          f);
    fclose(f);
    const Result r = explain(path);
    ASSERT_EQ(r.rc, 0) << r.out;
    EXPECT_NE(r.out.find("step: batched (isotropic M)"), std::string::npos) << schemes[k] << r.out;
    EXPECT_EQ(r.out.find("not batched"), std::string::npos) << schemes[k] << r.out;
    const auto t = types(r.out);
    ASSERT_EQ(t.size(), 1u) << r.out;
    cost[k] = t[0].cost_ns;
  }
  std::remove(path.c_str());
  rmdir(dir.c_str());
  EXPECT_LT(cost[0], cost[1]) << "euler against splitting";
  EXPECT_GT(cost[2], 2 * cost[1]) << "rk4 against splitting";
}

TEST(CliExplain, MissingSceneIsAnErrorNamingTheFile) {
  const Result r = explain("/nonexistent/scene.json");
  EXPECT_NE(r.rc, 0);
  EXPECT_NE(r.out.find("/nonexistent/scene.json"), std::string::npos) << r.out;
}

}  // namespace
