// Sanity warnings (io/sanity.h): each check fires on the mistake it is meant for, its
// message names the scene key, the value and the fix, and a sane scene gives none. Small
// scenes with spheres and ellipsoids (analytic added mass: no BEM), a 5x5x5 grid on disk.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "io/added_mass_cache.h"
#include "io/field_loader.h"
#include "io/sanity.h"
#include "io/scene_json.h"
#include "support/temp_dir.h"
#include "support/vti_writer.h"
#include "util/error.h"

namespace fs = std::filesystem;

namespace lrigid {
namespace {

// a scene in `dir`; `fluid` and `bodies` are JSON fragments
std::string scene_text(const std::string& fluid, const std::string& bodies,
                       const std::string& integrator = R"({"scheme": "strang", "dt": 0.002})",
                       const std::string& ground = R"({"z": 0})") {
  return R"({"version": 1, "fluid": )" + fluid + R"(, "gravity": [0, 0, -9.81],
    "effects": "auto", "integrator": )" + integrator + R"(, "duration": 1, "seed": 1,
    "ground": )" + ground + R"(, "bodies": )" + bodies + "}";
}

const std::string kUniformAir =
    R"({"density": 1.2, "kinematic_viscosity": 1.5e-5,
        "uniform": {"U": [1, 0, 0], "k": 0.1, "epsilon": 0.01}})";

std::string sphere(double radius, double density, const std::string& where,
                   int count = 10) {
  return R"({"name": "ball", "shape": {"type": "sphere", "radius": )" + std::to_string(radius) +
         R"(}, "density": )" + std::to_string(density) + R"(, "count": )" +
         std::to_string(count) + ", " + where + "}";
}

struct SanityChecks : test::TempDirTest {
  void SetUp() override {
    TempDirTest::SetUp();
    // a 10 m cube of air, 5 points per axis (2.5 m cells), wind 1 m/s along x
    test::VtiGrid g;
    g.dims = {5, 5, 5};
    g.spacing = {2.5, 2.5, 2.5};
    ASSERT_TRUE(test::write_vti((dir / "g.vti").string(), g,
                                [](int, const std::array<double, 3>&, float U[3], float* k,
                                   float* e) { U[0] = 1, *k = 0.1f, *e = 0.01f; }));
    test::VtiGrid coarse = g;
    coarse.dims = {5, 5, 3};
    coarse.spacing = {2.5, 2.5, 5};
    ASSERT_TRUE(test::write_vti((dir / "coarse.vti").string(), coarse,
                                [](int, const std::array<double, 3>&, float U[3], float* k,
                                   float* e) { U[0] = 1, *k = 0.1f, *e = 0.01f; }));
    // the same cube with a solid block (a building: valid = 0) where x <= 5 and z <= 5
    test::VtiGrid built = g;
    built.solid = [](const std::array<double, 3>& x) { return x[0] <= 5 && x[2] <= 5; };
    ASSERT_TRUE(test::write_vti((dir / "built.vti").string(), built,
                                [](int, const std::array<double, 3>&, float U[3], float* k,
                                   float* e) { U[0] = 1, *k = 0.1f, *e = 0.01f; }));
  }

  std::vector<SanityFinding> check(const std::string& text) {
    const Scene s = parse_scene(text, (dir / "scene.json").string());
    const Model m = compile_model(s, load_field(s, StreamMode::Off, true), cached_added_mass);
    return check_scene(s, m);
  }
  std::string grid(const char* name = "g.vti") {
    return R"({"density": 1.2, "kinematic_viscosity": 1.5e-5, "field": ")" + std::string(name) +
           "\"}";
  }
};

const SanityFinding* find(const std::vector<SanityFinding>& f, const std::string& check) {
  for (const auto& x : f)
    if (x.check == check) return &x;
  return nullptr;
}

std::string all(const std::vector<SanityFinding>& f) {
  std::string s;
  for (const auto& x : f) s += x.check + " " + x.key + ": " + x.message + "\n";
  return s;
}

TEST_F(SanityChecks, SaneScenesGiveNoFinding) {
  // a 1 cm glass bead in the wind, in the grid and in a uniform flow
  const std::string b = "[" + sphere(0.005, 2500, R"("spawn_box": [[2, 2, 6], [8, 8, 9]])") + "]";
  EXPECT_TRUE(check(scene_text(grid(), b)).empty()) << all(check(scene_text(grid(), b)));
  EXPECT_TRUE(check(scene_text(kUniformAir, b)).empty()) << all(check(scene_text(kUniformAir, b)));
}

TEST_F(SanityChecks, CentimetresWrittenAsMetresAreCaughtBySizeAndMass) {
  // a 1.2 cm bead written as radius 0.6 "m" (centimetres read as metres): 1.2 m wide, 10 m grid
  const auto f = check(scene_text(
      grid(), "[" + sphere(0.6, 2500, R"("spawn_box": [[2, 2, 6], [8, 8, 9]])") + "]"));
  const SanityFinding* size = find(f, "body_size");
  ASSERT_NE(size, nullptr) << all(f);
  EXPECT_EQ(size->key, "bodies[0].shape");
  EXPECT_NE(size->message.find("is 1.2 m wide, 12 % of the grid's extent"), std::string::npos)
      << size->message;
  EXPECT_NE(size->message.find("centimetres written as metres is 100 times too large"),
            std::string::npos);
  EXPECT_FALSE(size->error);
  const SanityFinding* mass = find(f, "body_mass");
  ASSERT_NE(mass, nullptr) << all(f);
  EXPECT_EQ(mass->key, "bodies[0].density");
  EXPECT_NE(mass->message.find("weighs 2.26e+03 kg per body"), std::string::npos)
      << mass->message;
  EXPECT_NE(mass->message.find("(metres)"), std::string::npos);
  // without a grid: wider than 5 m
  const auto u = check(scene_text(
      kUniformAir, "[" + sphere(3, 2500, R"("spawn_box": [[0, 0, 6], [1, 1, 9]])") + "]"));
  ASSERT_NE(find(u, "body_size"), nullptr) << all(u);
  EXPECT_NE(find(u, "body_size")->message.find("is 6 m wide: sizes are in metres"),
            std::string::npos);
}

TEST_F(SanityChecks, ADensityNoMaterialHasIsNamed) {
  const auto f = check(scene_text(
      kUniformAir, "[" + sphere(0.005, 78000, R"("spawn_box": [[0, 0, 6], [1, 1, 9]])") + "]"));
  const SanityFinding* d = find(f, "density");
  ASSERT_NE(d, nullptr) << all(f);
  EXPECT_EQ(d->key, "bodies[0].density");
  EXPECT_NE(d->message.find("density 7.8e+04 kg/m^3, denser than any material"),
            std::string::npos) << d->message;
  EXPECT_NE(d->message.find("densities are in kg/m^3"), std::string::npos);
}

TEST_F(SanityChecks, SpawnBoxesOutsideOrPartlyOutsideTheGrid) {
  const std::string bodies =
      "[" + sphere(0.005, 2500, R"("spawn_box": [[20, 20, 20], [30, 30, 30]])") + ", " +
      sphere(0.005, 2500, R"("spawn_box": [[5, 5, 5], [15, 9, 9]])") + "]";
  const auto f = check(scene_text(grid(), bodies));
  const SanityFinding* out = find(f, "spawn_outside_grid");
  ASSERT_NE(out, nullptr) << all(f);
  EXPECT_EQ(out->key, "bodies[0].spawn_box");
  EXPECT_NE(out->message.find("spawn_box [[20, 20, 20], [30, 30, 30]] lies entirely outside the "
                              "grid [[0, 0, 0], [10, 10, 10]]"),
            std::string::npos) << out->message;
  EXPECT_NE(out->message.find("check the units and the box"), std::string::npos);
  EXPECT_FALSE(out->error) << "some bodies start inside: a warning";
  const SanityFinding* part = find(f, "spawn_partly_outside_grid");
  ASSERT_NE(part, nullptr) << all(f);
  EXPECT_EQ(part->key, "bodies[1].spawn_box");
  EXPECT_NE(part->message.find("50 % of it lies outside the grid"), std::string::npos)
      << part->message;
  EXPECT_NE(part->message.find("shrink it to the grid's bounds"), std::string::npos);
  EXPECT_EQ(find(f, "all_outside_grid"), nullptr);
}

TEST_F(SanityChecks, EveryBodyOutsideTheGridIsAnErrorEvenWithoutStrict) {
  const auto f = check(scene_text(
      grid(), "[" + sphere(0.005, 2500, R"("position": [100, 100, 500])", 1) + "]"));
  const SanityFinding* all_out = find(f, "all_outside_grid");
  ASSERT_NE(all_out, nullptr) << all(f);
  EXPECT_TRUE(all_out->error);
  EXPECT_EQ(all_out->key, "bodies");
  ASSERT_NE(find(f, "spawn_outside_grid"), nullptr);
  EXPECT_EQ(find(f, "spawn_outside_grid")->key, "bodies[0].position");
  try {
    report_findings(f, "s.json", false, true);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::BadInput);
    EXPECT_NE(std::string(e.what()).find("s.json: bodies: every body starts outside the grid"),
              std::string::npos) << e.what();
  }
}

TEST_F(SanityChecks, BodiesStartingInsideTheFlowsSolidsAreNamed) {
  // a spawn box inside the building (its cells reach z = 7.5 where x < 7.5): all its bodies
  // would stop at t = 0; one above it starts in the fluid; one across its edge:
  // those inside are counted (the positions initial_state draws, not an estimate)
  const std::string bodies =
      "[" + sphere(0.005, 2500, R"("spawn_box": [[0.5, 0.5, 0.5], [3, 9, 3]])") + ", " +
      sphere(0.005, 2500, R"("spawn_box": [[0.5, 0.5, 8], [9.5, 9.5, 9.5]])") + ", " +
      sphere(0.005, 2500, R"("spawn_box": [[0.5, 0.5, 0.5], [9.5, 9.5, 3]])", 40) + "]";
  const auto f = check(scene_text(grid("built.vti"), bodies));
  const SanityFinding* inside = find(f, "spawn_inside_solid");
  ASSERT_NE(inside, nullptr) << all(f);
  EXPECT_EQ(inside->key, "bodies[0].spawn_box");
  EXPECT_NE(inside->message.find("spawn_box [[0.5, 0.5, 0.5], [3, 9, 3]] lies inside the flow's "
                                 "solids"),
            std::string::npos)
      << inside->message;
  EXPECT_NE(inside->message.find("all its 10 bodies would stop (\"exited\") at t = 0"),
            std::string::npos)
      << inside->message;
  EXPECT_FALSE(inside->error) << "other bodies start in the fluid: a warning";
  const SanityFinding* part = find(f, "spawn_partly_inside_solid");
  ASSERT_NE(part, nullptr) << all(f);
  EXPECT_EQ(part->key, "bodies[2].spawn_box");
  // the count is of the drawn positions: between the solid's share of the box, about 0.6, and
  // the whole box
  const size_t at = part->message.find(" of its 40 bodies start inside the flow's solids");
  ASSERT_NE(at, std::string::npos) << part->message;
  const int n = std::stoi(part->message.substr(part->message.rfind(' ', at - 1) + 1));
  EXPECT_GT(n, 10) << part->message;
  EXPECT_LT(n, 40) << part->message;
  for (const auto& x : f) EXPECT_NE(x.key, "bodies[1].spawn_box") << x.message;  // in the fluid
  EXPECT_EQ(find(f, "all_outside_fluid"), nullptr);

  // only the box inside the building: the run would end at t = 0, an error without --strict
  const auto g = check(scene_text(
      grid("built.vti"), "[" + sphere(0.005, 2500, R"("spawn_box": [[0.5, 0.5, 0.5], [3, 9, 3]])") +
                             "]"));
  const SanityFinding* none = find(g, "all_outside_fluid");
  ASSERT_NE(none, nullptr) << all(g);
  EXPECT_TRUE(none->error);
  try {
    report_findings(g, "s.json", false, true);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("s.json: bodies: every body starts inside the flow's "
                                         "solids or outside the grid"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(SanityChecks, StrictMakesAWarningAnErrorNamingKeyAndFix) {
  const auto f = check(scene_text(
      kUniformAir, "[" + sphere(3, 2500, R"("spawn_box": [[0, 0, 6], [1, 1, 9]])") + "]"));
  ASSERT_FALSE(f.empty());
  EXPECT_NO_THROW(report_findings(f, "s.json", false, true));
  try {
    report_findings(f, "s.json", true, true);
    FAIL() << "--strict did not make it an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::BadInput);
    const std::string w = e.what();
    EXPECT_NE(w.find("s.json: bodies[0].shape: body type \"ball\" is 6 m wide"), std::string::npos)
        << w;
    EXPECT_NE(w.find("(a warning: --strict)"), std::string::npos) << w;
  }
}

TEST_F(SanityChecks, SpawnBoxUnderTheGround) {
  const auto f = check(scene_text(
      kUniformAir, "[" + sphere(0.005, 2500, R"("spawn_box": [[0, 0, -3], [1, 1, -1]])") + "]"));
  const SanityFinding* g = find(f, "spawn_below_ground");
  ASSERT_NE(g, nullptr) << all(f);
  EXPECT_EQ(g->key, "bodies[0].spawn_box");
  EXPECT_NE(g->message.find("lies below the ground (ground.z = 0 m)"), std::string::npos);
  EXPECT_NE(g->message.find("check ground.z and the box's z"), std::string::npos);
}

// bodies released after the run's end (duration 1 s) are named with their count; a release
// within the run is not
TEST_F(SanityChecks, ABodyReleasedAfterTheEndIsNamed) {
  const std::string where = R"("position": [5, 5, 5], "release": )";
  auto f = check(scene_text(grid(), "[" + sphere(0.005, 2500, where + R"({"rate": 4})") + "]"));
  const SanityFinding* late = find(f, "release_after_end");
  ASSERT_NE(late, nullptr) << all(f);  // bodies 5 to 9 at 1.25 to 2.25 s
  EXPECT_EQ(late->key, "bodies[0].release");
  EXPECT_FALSE(late->error);
  EXPECT_NE(late->message.find("body type \"ball\": 5 of its 10 bodies are released after the "
                               "run ends (duration = 1 s, the last at 2.25 s)"),
            std::string::npos)
      << late->message;
  f = check(scene_text(grid(), "[" + sphere(0.005, 2500, where + R"({"times": [0, 0.5, 1]})") +
                                   "]"));
  EXPECT_EQ(find(f, "release_after_end"), nullptr) << all(f);
}

TEST_F(SanityChecks, TimeStepBeyondTheExplicitSchemesMeasuredLimit) {
  // a 50 um glass bead in air: tau_p = rho_b d^2 / (18 mu) = 0.019 s; euler: dt <= 2 tau_p
  const std::string b = "[" + sphere(2.5e-5, 2500, R"("spawn_box": [[0, 0, 6], [1, 1, 9]])") + "]";
  const auto f = check(scene_text(kUniformAir, b, R"({"scheme": "euler", "dt": 0.5})"));
  const SanityFinding* d = find(f, "dt_stability");
  ASSERT_NE(d, nullptr) << all(f);
  EXPECT_EQ(d->key, "integrator.dt");
  EXPECT_NE(d->message.find("dt = 0.5 s is"), std::string::npos) << d->message;
  EXPECT_NE(d->message.find("the measured stability limit of euler"), std::string::npos);
  // it suggests the default scheme, strang
  EXPECT_NE(d->message.find("use \"scheme\": \"strang\" or dt <= "), std::string::npos)
      << d->message;
  // the same step with the suggested scheme, and with splitting, is within what was measured
  // stable (100 tau_p)
  for (const char* scheme : {"strang", "splitting"})
    EXPECT_EQ(find(check(scene_text(kUniformAir, b,
                                    std::string(R"({"scheme": ")") + scheme + R"(", "dt": 0.5})")),
                   "dt_stability"),
              nullptr)
        << scheme;
}

TEST_F(SanityChecks, GridTooCoarseForTheBodies) {
  // all bodies start within one 2.5 m cell of the 5x5x5 grid
  const auto f = check(scene_text(
      grid(), "[" + sphere(0.005, 2500, R"("spawn_box": [[5, 5, 5], [6, 6, 6]])") + "]"));
  const SanityFinding* c = find(f, "grid_coarse");
  ASSERT_NE(c, nullptr) << all(f);
  EXPECT_EQ(c->key, "bodies[0].spawn_box");
  EXPECT_NE(c->message.find("fits within one grid cell (spacing [2.5, 2.5, 2.5] m)"),
            std::string::npos) << c->message;
  EXPECT_NE(c->message.find("use a finer grid"), std::string::npos);
  // a grid of 3 points along z
  const auto g = check(scene_text(
      grid("coarse.vti"), "[" + sphere(0.005, 2500, R"("spawn_box": [[2, 2, 2], [8, 8, 8]])") + "]"));
  const SanityFinding* z = find(g, "grid_coarse");
  ASSERT_NE(z, nullptr) << all(g);
  EXPECT_EQ(z->key, "fluid.field");
  EXPECT_NE(z->message.find("the grid has 3 points along z (spacing 5 m)"), std::string::npos)
      << z->message;
  EXPECT_NE(z->message.find("check the grid's resolution"), std::string::npos);
}

}  // namespace
}  // namespace lrigid
