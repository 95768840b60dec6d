// The scene parser accepts the documented schema and rejects everything else with a message
// naming the file, the key path and the value.
#include "io/scene_json.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "body/mass_properties.h"
#include "model/model.h"
#include "util/error.h"

namespace lrigid {
namespace {

using json = nlohmann::json;

json valid_scene() {
  return json::parse(R"({
    "version": 1,
    "fluid": {"density": 1000, "kinematic_viscosity": 1e-6,
              "uniform": {"U": [0.1, 0, 0], "k": 0.01, "epsilon": 0.001}},
    "gravity": [0, 0, -9.81],
    "effects": ["gravity", "buoyancy", "drag"],
    "integrator": {"scheme": "rk4", "dt": 0.001},
    "duration": 2.5,
    "seed": 12,
    "bodies": [{"name": "ball", "shape": {"type": "sphere", "radius": 0.01}, "density": 2500,
                "count": 3, "position": [0, 0, 1], "velocity": [1, 0, 0]}],
    "ground": {"z": -1},
    "turbulence": {"model": "body", "drift": "original"},
    "output": {"dir": "out", "every": 0.1, "formats": ["csv"]}
  })");
}

// the message of the error parse_scene throws, or "" if it does not throw
std::string error_of(const json& j, ExitCode* code = nullptr) {
  try {
    parse_scene(j.dump(), "/tmp/scene.json");
  } catch (const Error& e) {
    if (code) *code = e.code();
    return e.what();
  }
  return "";
}

TEST(SceneJson, ReadsEveryKey) {
  const Scene s = parse_scene(valid_scene().dump(), "/tmp/scene.json");
  EXPECT_EQ(s.fluid_density, 1000);
  EXPECT_TRUE(s.uniform_field);
  EXPECT_EQ(s.uniform_U, Vec3(0.1, 0, 0));
  EXPECT_EQ(s.integrator, Integrator::RK4);
  EXPECT_EQ(s.dt, 0.001);
  EXPECT_EQ(s.duration, 2.5);
  EXPECT_EQ(s.seed, 12u);
  ASSERT_EQ(s.bodies.size(), 1u);
  EXPECT_EQ(s.bodies[0].count, 3);
  EXPECT_EQ(s.bodies[0].shape.type, ShapeType::Sphere);
  EXPECT_EQ(s.bodies[0].velocity, Vec3(1, 0, 0));
  EXPECT_TRUE(s.has_ground);
  EXPECT_EQ(s.ground_z, -1);
  EXPECT_EQ(s.turbulence_model, TurbulenceModel::Body);
  EXPECT_EQ(s.drift, Drift::Original);
  EXPECT_TRUE(s.crossing_trajectories);  // the default
  json j = valid_scene();
  j["turbulence"]["crossing_trajectories"] = false;
  EXPECT_FALSE(parse_scene(j.dump(), "/tmp/scene.json").crossing_trajectories);
  EXPECT_TRUE(s.effects.has(Effect::Drag));
  EXPECT_FALSE(s.effects.has(Effect::AddedMass));
  EXPECT_TRUE(s.output.csv);
  EXPECT_FALSE(s.output.pvd);
  EXPECT_EQ(s.output.dir, "out");
  // integrator.batched and integrator.precision default to the batched step in double
  EXPECT_TRUE(s.batched);
  EXPECT_EQ(s.precision, Precision::Double);
}

TEST(SceneJson, BatchedStepKeys) {
  json j = valid_scene();
  j["integrator"]["batched"] = false;
  j["integrator"]["precision"] = "float";
  const Scene s = parse_scene(j.dump(), "/tmp/scene.json");
  EXPECT_FALSE(s.batched);
  EXPECT_EQ(s.precision, Precision::Float);
}

TEST(SceneJson, MalformedJsonReportsLineAndColumn) {
  const std::string text = "{\n  \"fluid\": {\n    \"density\": 1000,,\n  }\n}";
  try {
    parse_scene(text, "/tmp/bad.json");
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_EQ(e.code(), ExitCode::BadInput);
    EXPECT_NE(m.find("/tmp/bad.json"), std::string::npos) << m;
    EXPECT_NE(m.find("line 3"), std::string::npos) << m;
    EXPECT_NE(m.find("column 21"), std::string::npos) << m;
  }
}

struct BadCase {
  const char* what;
  std::function<void(json&)> edit;
  const char* expect;  // must appear in the message
};

class SceneJsonErrors : public ::testing::TestWithParam<BadCase> {};

TEST_P(SceneJsonErrors, NameKeyAndValue) {
  json j = valid_scene();
  GetParam().edit(j);
  ExitCode code = ExitCode::Ok;
  const std::string m = error_of(j, &code);
  ASSERT_FALSE(m.empty()) << GetParam().what << ": accepted";
  EXPECT_EQ(code, ExitCode::BadInput);
  EXPECT_NE(m.find("/tmp/scene.json"), std::string::npos) << m;
  EXPECT_NE(m.find(GetParam().expect), std::string::npos) << GetParam().what << ": " << m;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, SceneJsonErrors,
    ::testing::Values(
        BadCase{"unknown top key", [](json& j) { j["colour"] = "red"; }, "unknown key \"colour\""},
        BadCase{"unknown nested key", [](json& j) { j["bodies"][0]["shape"]["radious"] = 1; },
                "bodies[0].shape: unknown key \"radious\" (did you mean \"radius\"?)"},
        // a typo in a required key is named (before the key is found missing)
        BadCase{"typo in a required key",
                [](json& j) {
                  auto& b = j["bodies"][0];
                  b["densty"] = b["density"];
                  b.erase("density");
                },
                "bodies[0]: unknown key \"densty\" (did you mean \"density\"?)"},
        BadCase{"typo in a required fluid key",
                [](json& j) {
                  auto& f = j["fluid"];
                  f["kinematic_viscocity"] = f["kinematic_viscosity"];
                  f.erase("kinematic_viscosity");
                },
                "fluid: unknown key \"kinematic_viscocity\" (did you mean "
                "\"kinematic_viscosity\"?)"},
        BadCase{"typo in one of two alternatives",
                [](json& j) {
                  auto& b = j["bodies"][0];
                  b["spawn_bx"] = {{0, 0, 0}, {1, 1, 1}};
                  b.erase("position");
                  b.erase("spawn_box");
                },
                "bodies[0]: unknown key \"spawn_bx\" (did you mean \"spawn_box\"?)"},
        BadCase{"typo at the top", [](json& j) { j["durration"] = j["duration"]; },
                "unknown key \"durration\" (did you mean \"duration\"?)"},
        BadCase{"dotted key", [](json& j) { j["art.turbulence_scale"] = 0.5; },
                "unknown key \"art.turbulence_scale\": keys are nested, not dotted; write "
                "\"art\": { \"turbulence_scale\": ... }"},
        BadCase{"valid key that does not apply",
                [](json& j) { j["bodies"][0]["shape"] = {{"type", "box"}, {"size", {1, 1, 1}},
                                                         {"radius", 0.1}}; },
                "bodies[0].shape: key \"radius\" does not apply here"},
        BadCase{"wrong type", [](json& j) { j["duration"] = "long"; },
                "duration: must be a number, got \"long\""},
        BadCase{"negative size", [](json& j) { j["bodies"][0]["shape"]["radius"] = -0.1; },
                "bodies[0].shape.radius: must be > 0, got -0.1"},
        // the centre of mass of a solid body lies inside it (the test scene's body: a sphere of
        // radius 1 cm)
        BadCase{"mass offset outside the body",
                [](json& j) { j["bodies"][0]["mass_offset"] = {0, 0.008, -0.008}; },
                "bodies[0].mass_offset: [0, 0.008, -0.008] m from the volume centroid puts the "
                "centre of mass outside the body (the sphere's radius 0.01 m)"},
        BadCase{"mass offset outside a box",
                [](json& j) {
                  j["bodies"][0]["shape"] = {{"type", "box"}, {"size", {0.06, 0.04, 0.001}}};
                  j["bodies"][0]["mass_offset"] = {0, 0, 0.0006};
                },
                "bodies[0].mass_offset: [0, 0, 0.0006] m from the volume centroid puts the centre "
                "of mass outside the body (the box's half extents [0.03, 0.02, 0.0005] m)"},
        BadCase{"zero density", [](json& j) { j["bodies"][0]["density"] = 0; },
                "bodies[0].density: must be in [1e-6, 1e6] kg/m^3, got 0"},
        BadCase{"fluid density", [](json& j) { j["fluid"]["density"] = -1; },
                "fluid.density: must be in [1e-6, 1e6] kg/m^3, got -1"},
        BadCase{"zero dt", [](json& j) { j["integrator"]["dt"] = 0; },
                "integrator.dt: must be > 0, got 0"},
        BadCase{"negative duration", [](json& j) { j["duration"] = -2; },
                "duration: must be > 0, got -2"},
        BadCase{"missing key", [](json& j) { j.erase("gravity"); }, "gravity: is required"},
        BadCase{"unknown effect", [](json& j) { j["effects"].push_back("magic"); },
                "effects[3]: unknown effect \"magic\""},
        BadCase{"unknown scheme", [](json& j) { j["integrator"]["scheme"] = "leapfrog"; },
                "integrator.scheme: must be euler, rk4, splitting or strang, got \"leapfrog\""},
        BadCase{"unknown precision", [](json& j) { j["integrator"]["precision"] = "half"; },
                "integrator.precision: must be double or float, got \"half\""},
        BadCase{"batched not a bool", [](json& j) { j["integrator"]["batched"] = "yes"; },
                "integrator.batched: must be true or false, got \"yes\""},
        BadCase{"bad count", [](json& j) { j["bodies"][0]["count"] = 0; },
                "bodies[0].count: must be an integer >= 1, got 0"},
        BadCase{"both placements",
                [](json& j) {
                  j["bodies"][0]["spawn_box"] = {{0, 0, 0}, {1, 1, 1}};
                },
                "bodies[0]: needs exactly one of \"position\", \"spawn_box\" or \"spawn\""},
        BadCase{"short vector",
                [](json& j) {
                  j["gravity"] = {0, -9.81};
                },
                "gravity: must be an array of 3 numbers"},
        BadCase{"zero quaternion",
                [](json& j) {
                  j["bodies"][0]["orientation"] = {0, 0, 0, 0};
                },
                "bodies[0].orientation: quaternion must not be zero"},
        BadCase{"missing field file",
                [](json& j) {
                  j["fluid"].erase("uniform");
                  j["fluid"]["field"] = "nowhere.vti";
                },
                "fluid.field: file not found: /tmp/nowhere.vti"},
        BadCase{"negative k", [](json& j) { j["fluid"]["uniform"]["k"] = -1; },
                "fluid.uniform.k: must be in [0, 1e8] m^2/s^2, got -1"},
        BadCase{"huge gravity", [](json& j) { j["gravity"] = {0, 0, -1e308}; },
                "gravity: must all be in [-1e4, 1e4] m/s^2, got [0,0,-1e+308]"},
        BadCase{"step beyond the run", [](json& j) { j["integrator"]["dt"] = 1e3; },
                "integrator.dt: must be at most duration"},
        BadCase{"missing mesh",
                [](json& j) {
                  j["bodies"][0]["shape"] = {{"type", "mesh"}, {"file", "no.obj"}};
                },
                "no.obj"},
        BadCase{"bad format",
                [](json& j) {
                  j["output"]["formats"] = {"csv", "xls"};
                },
                "output.formats[1]: must be one of \"csv\", \"pvd\", \"glb\", \"glb_instanced\", "
                "\"houdini\", \"usd\", got \"xls\""},
        BadCase{"misspelt cache format",
                [](json& j) {
                  j["output"]["formats"] = {"csv", "glb_instance"};
                },
                "output.formats[1]: must be one of \"csv\", \"pvd\", \"glb\", \"glb_instanced\", "
                "\"houdini\", \"usd\", got \"glb_instance\""},
        BadCase{"turbulence model", [](json& j) { j["turbulence"]["model"] = "les"; },
                "turbulence.model: must be \"body\" or \"seen\", got \"les\""},
        BadCase{"crossing trajectories",
                [](json& j) { j["turbulence"]["crossing_trajectories"] = "no"; },
                "turbulence.crossing_trajectories"},
        BadCase{"schema version", [](json& j) { j["version"] = 2; },
                "version: only schema version 1 is supported, got 2"}),
    [](const auto& info) {
      std::string n = info.param.what;
      for (char& c : n)
        if (!isalnum(static_cast<unsigned char>(c))) c = '_';
      return n;
    });

void expect_every_typo_named(const json& scene);  // below

// contacts (docs/scene-format.md "Contacts"): parsed and validated, not yet applied by the step
TEST(SceneJson, ContactDefaultsAndKeys) {
  const Scene d = parse_scene(valid_scene().dump(), "/tmp/scene.json");
  EXPECT_EQ(d.ground_contact, ContactMode::Collide);
  EXPECT_EQ(d.walls_contact, ContactMode::Collide);
  EXPECT_EQ(d.outside, OutsideMode::Remove);
  EXPECT_EQ(d.bodies[0].contact.restitution, ContactSpec{}.restitution);
  EXPECT_EQ(d.bodies[0].contact.friction, ContactSpec{}.friction);
  EXPECT_EQ(d.bodies[0].contact.rolling_resistance, 0.0);  // none: no body stops rolling

  json j = valid_scene();
  j["contact"] = {{"restitution", 0.1}, {"friction", 0.8}};
  j["ground"]["contact"] = "stop";
  j["walls"] = {{"contact", "stop"}};
  j["outside"] = "stop";
  json second = j["bodies"][0];
  second["name"] = "other";
  j["bodies"][0]["contact"] = {{"restitution", 0.6}, {"rolling_resistance", 0.02}};
  j["bodies"].push_back(second);
  const Scene s = parse_scene(j.dump(), "/tmp/scene.json");
  EXPECT_EQ(s.ground_contact, ContactMode::Stop);
  EXPECT_EQ(s.walls_contact, ContactMode::Stop);
  EXPECT_EQ(s.outside, OutsideMode::Stop);
  // the body's own key wins; the others come from the scene's "contact"
  EXPECT_EQ(s.bodies[0].contact.restitution, 0.6);
  EXPECT_EQ(s.bodies[0].contact.friction, 0.8);
  EXPECT_EQ(s.bodies[1].contact.restitution, 0.1);
  EXPECT_EQ(s.bodies[1].contact.friction, 0.8);
  EXPECT_EQ(s.bodies[0].contact.rolling_resistance, 0.02);
  EXPECT_EQ(s.bodies[1].contact.rolling_resistance, 0.0);
  // the limits are allowed
  j["contact"] = {{"restitution", 1}, {"friction", 0}, {"rolling_resistance", 0}};
  EXPECT_EQ(error_of(j), "");
  expect_every_typo_named(j);
  EXPECT_STREQ(contact_mode_name(ContactMode::Collide), "collide");
  EXPECT_STREQ(outside_mode_name(OutsideMode::Remove), "remove");
}

INSTANTIATE_TEST_SUITE_P(
    Contacts, SceneJsonErrors,
    ::testing::Values(
        BadCase{"negative restitution",
                [](json& j) { j["bodies"][0]["contact"] = {{"restitution", -0.2}}; },
                "bodies[0].contact.restitution: must lie in [0, 1] (normal speed after / before "
                "an impact), got -0.2"},
        BadCase{"restitution above 1", [](json& j) { j["contact"] = {{"restitution", 1.5}}; },
                "contact.restitution: must lie in [0, 1] (normal speed after / before an "
                "impact), got 1.5"},
        BadCase{"negative friction",
                [](json& j) { j["bodies"][0]["contact"] = {{"friction", -1}}; },
                "bodies[0].contact.friction: must be >= 0 (Coulomb coefficient), got -1"},
        BadCase{"friction not a number", [](json& j) { j["contact"] = {{"friction", "high"}}; },
                "contact.friction: must be a number, got \"high\""},
        BadCase{"negative rolling resistance",
                [](json& j) { j["bodies"][0]["contact"] = {{"rolling_resistance", -0.01}}; },
                "bodies[0].contact.rolling_resistance: must be >= 0 (rolling resistance "
                "coefficient), got -0.01"},
        BadCase{"rolling resistance not a number",
                [](json& j) { j["contact"] = {{"rolling_resistance", true}}; },
                "contact.rolling_resistance: must be a number, got true"},
        BadCase{"unknown ground contact mode", [](json& j) { j["ground"]["contact"] = "bounce"; },
                "ground.contact: must be \"collide\" or \"stop\", got \"bounce\""},
        BadCase{"unknown walls contact mode", [](json& j) { j["walls"] = {{"contact", "slide"}}; },
                "walls.contact: must be \"collide\" or \"stop\", got \"slide\""},
        BadCase{"unknown outside mode", [](json& j) { j["outside"] = "wrap"; },
                "outside: must be \"remove\" or \"stop\", got \"wrap\""},
        BadCase{"typo in contact", [](json& j) { j["contact"] = {{"restitusion", 0.5}}; },
                "contact: unknown key \"restitusion\" (did you mean \"restitution\"?)"}),
    [](const auto& info) {
      std::string n = info.param.what;
      for (char& c : n)
        if (!isalnum(static_cast<unsigned char>(c))) c = '_';
      return n;
    });

TEST(SceneJson, ArtDirectionAndVariation) {
  json j = valid_scene();
  j["effects"] = {"gravity", "drag", "lift", "magnus", "basset"};
  j["art"] = {{"mean_flow_scale", 1.5}, {"turbulence_scale", 0.5}};
  j["bodies"][0]["variation"] = {
      {"size", {0.8, 1.2}}, {"density", {0.9, 1.1}}, {"spin", {0, 20}}, {"variants", 4}};
  const Scene s = parse_scene(j.dump(), "/tmp/scene.json");
  EXPECT_TRUE(s.effects.has(Effect::Lift));
  EXPECT_TRUE(s.effects.has(Effect::Magnus));
  EXPECT_TRUE(s.effects.has(Effect::Basset));
  EXPECT_EQ(s.mean_flow_scale, 1.5);
  EXPECT_EQ(s.turbulence_scale, 0.5);
  const BodySpec& b = s.bodies[0];
  EXPECT_EQ(b.size_min, 0.8);
  EXPECT_EQ(b.size_max, 1.2);
  EXPECT_EQ(b.density_min, 0.9);
  EXPECT_EQ(b.density_max, 1.1);
  EXPECT_EQ(b.spin_max, 20);
  EXPECT_EQ(b.variants, 4);
}

TEST(SceneJson, BadArtDirectionNamesTheKey) {
  json j = valid_scene();
  j["art"] = {{"turbulence_scale", -1}};
  EXPECT_NE(error_of(j).find("art.turbulence_scale: must be in [0, 1000], got -1"), std::string::npos)
      << error_of(j);
  j = valid_scene();
  j["art"] = {{"wind", 2}};
  EXPECT_NE(error_of(j).find("art: unknown key \"wind\""), std::string::npos) << error_of(j);
  j = valid_scene();
  j["bodies"][0]["variation"] = {{"size", {1.2, 0.8}}};
  EXPECT_NE(error_of(j).find("bodies[0].variation.size: upper bound below lower bound"),
            std::string::npos)
      << error_of(j);
  j = valid_scene();
  j["bodies"][0]["variation"] = {{"density", {0, 2}}};
  EXPECT_NE(error_of(j).find("bodies[0].variation.density: lower bound must be > 0"),
            std::string::npos)
      << error_of(j);
  j = valid_scene();
  j["bodies"][0]["variation"] = {{"variants", 0}};
  EXPECT_NE(error_of(j).find("bodies[0].variation.variants: must be an integer in [1, 256]"),
            std::string::npos)
      << error_of(j);
}

// "release": by rate (from an optional start) or at listed times; without it every body starts
// at t = 0
TEST(SceneJson, ReleaseByRateOrTimes) {
  json j = valid_scene();
  EXPECT_FALSE(parse_scene(j.dump(), "/tmp/scene.json").bodies[0].released_over_time());
  j["bodies"][0]["release"] = {{"rate", 20}, {"start", 0.5}};
  BodySpec b = parse_scene(j.dump(), "/tmp/scene.json").bodies[0];
  EXPECT_TRUE(b.released_over_time());
  EXPECT_EQ(b.release_rate, 20);
  EXPECT_EQ(b.release_start, 0.5);
  EXPECT_TRUE(b.release_times.empty());
  j["bodies"][0]["release"] = {{"rate", 4}};
  EXPECT_EQ(parse_scene(j.dump(), "/tmp/scene.json").bodies[0].release_start, 0);
  j["bodies"][0]["release"] = {{"times", {0, 0.25, 1}}};
  b = parse_scene(j.dump(), "/tmp/scene.json").bodies[0];
  EXPECT_EQ(b.release_rate, 0);
  EXPECT_EQ(b.release_times, (std::vector<double>{0, 0.25, 1}));
}

TEST(SceneJson, BadReleaseNamesTheKeyAndValue) {
  const std::vector<std::pair<json, std::string>> cases = {
      {{{"rate", 0}}, "bodies[0].release.rate: must be > 0, got 0"},
      {{{"rate", -2}}, "bodies[0].release.rate: must be > 0, got -2"},
      {{{"rate", 1}, {"start", -1}}, "bodies[0].release.start: must be in [0, 1e9] s, got -1"},
      {{{"times", {0.5, -1}}}, "bodies[0].release.times[1]: must be in [0, 1e9] s, got -1"},
      {{{"times", {0.5, 0.5}}},
       "bodies[0].release.times[1]: must be greater than the time before it (0.5)"},
      {{{"times", {1, 0.5}}},
       "bodies[0].release.times[1]: must be greater than the time before it (1)"},
      {{{"times", json::array()}}, "bodies[0].release.times: must be a non-empty list"},
      {{{"times", {0, 1}}, {"start", 1}}, "bodies[0].release.start: applies to \"rate\" only"},
      {{{"rate", 1}, {"times", {0}}},
       "bodies[0].release: needs exactly one of \"rate\" (bodies per second) or \"times\" "
       "(s), got both"},
      {json::object(), "bodies[0].release: needs exactly one of \"rate\""},
      {{{"rat", 1}}, "bodies[0].release: unknown key \"rat\" (did you mean \"rate\"?)"},
      {{{"time", {1}}}, "bodies[0].release: unknown key \"time\" (did you mean \"times\"?)"},
  };
  for (const auto& [release, message] : cases) {
    json j = valid_scene();
    j["bodies"][0]["release"] = release;
    ExitCode code = ExitCode::Ok;
    const std::string m = error_of(j, &code);
    EXPECT_NE(m.find("/tmp/scene.json: " + message), std::string::npos)
        << release.dump() << " -> " << m;
    EXPECT_EQ(code, ExitCode::BadInput) << release.dump();
  }
}

TEST(SceneJson, MissingFileSaysSo) {
  try {
    read_scene("/nonexistent/scene.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/scene.json: file not found"),
              std::string::npos)
        << e.what();
  }
}

// strang is the default scheme. The scene file requires "scheme", so the default is
// what a Scene or Model built in code starts with and what every shipped scene (scenes/*.json,
// which Allrun, the tests, benches and validation studies copy) names.
TEST(SceneJson, ShippedScenesAndDefaultsRunStrang) {
  EXPECT_EQ(kDefaultIntegrator, Integrator::Strang);
  EXPECT_EQ(Scene().integrator, Integrator::Strang);
  EXPECT_EQ(Model().integrator, Integrator::Strang);
  int scenes = 0;
  for (const auto& e :
       std::filesystem::directory_iterator(std::string(LRIGID_SOURCE_DIR) + "/scenes")) {
    if (e.path().extension() != ".json") continue;
    ++scenes;
    // the scheme as the parser reads it (read_scene would also want the scene's grid, which
    // ./Allrun makes)
    std::ifstream in(e.path());
    const json j = json::parse(in);
    Integrator scheme = Integrator::Euler;
    ASSERT_TRUE(integrator_from_name(j.at("integrator").at("scheme").get<std::string>(), &scheme))
        << e.path();
    EXPECT_EQ(scheme, Integrator::Strang) << e.path();
  }
  EXPECT_GE(scenes, 9) << "the shipped scenes: leaves_wind, debris_tank, uniform_box, ...";
}


// ---- a typo in any key of a scene is named, with the key it was meant to be ----

// Every key path below `j` (objects only; list elements by index), e.g. {"bodies", 0, "shape"}.
void key_paths(const json& j, json::json_pointer at, std::vector<json::json_pointer>* out) {
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) {
      out->push_back(at / it.key());
      key_paths(it.value(), at / it.key(), out);
    }
  } else if (j.is_array()) {
    for (size_t i = 0; i < j.size(); ++i) key_paths(j[i], at / i, out);
  }
}

// For each key of `scene`: the same scene with that key misspelt (its middle letter doubled)
// must fail naming the misspelt key and suggesting the real one, whatever else the scene says.
void expect_every_typo_named(const json& scene) {
  std::vector<json::json_pointer> paths;
  key_paths(scene, json::json_pointer(), &paths);
  ASSERT_GT(paths.size(), 5u);
  for (const auto& p : paths) {
    const std::string key = p.back();
    std::string typo = key;
    typo.insert(typo.size() / 2, 1, typo[typo.size() / 2]);
    json j = scene;
    json& parent = j[p.parent_pointer()];
    parent[typo] = parent[key];
    parent.erase(key);
    const std::string m = error_of(j);
    SCOPED_TRACE(p.to_string() + " -> " + typo);
    EXPECT_NE(m.find("unknown key \"" + typo + "\" (did you mean \"" + key + "\"?)"),
              std::string::npos)
        << m;
  }
}

TEST(SceneJson, ATypoInAnyKeyIsNamed) {
  // every key the format has, over four scenes (alternatives exclude each other)
  const std::string mesh = std::string(LRIGID_SOURCE_DIR) + "/tests/data/meshes/tetra.obj";
  json full = valid_scene();
  full["version"] = 1;
  full["integrator"]["batched"] = true;
  full["integrator"]["precision"] = "double";
  full["art"] = {{"mean_flow_scale", 1.0}, {"turbulence_scale", 0.5}};
  full["output"]["checkpoint_every"] = 60;
  auto& b = full["bodies"][0];
  b["mass_offset"] = {0, 0, 0};
  b["orientation"] = "random";
  b["angular_velocity"] = {0, 0, 1};
  b["shape"]["panels"] = 200;
  b["variation"] = {{"size", {0.9, 1.1}}, {"density", {0.9, 1.1}}, {"spin", {0, 1}},
                    {"variants", 4}};
  b["release"] = {{"rate", 10}, {"start", 0.5}};
  ASSERT_EQ(error_of(full), "");
  expect_every_typo_named(full);

  json other = valid_scene();
  other["fluid"].erase("uniform");
  other["fluid"]["field"] = mesh;  // parse_scene only checks that the file exists
  other["fluid"]["time"] = "loop";
  other["bodies"][0].erase("position");
  other["bodies"][0]["spawn_box"] = {{0, 0, 0}, {1, 1, 1}};
  other["bodies"][0]["shape"] = {{"type", "mesh"}, {"file", mesh}, {"scale", 0.01}};
  other["bodies"][0]["release"] = {{"times", {0, 1}}};
  ASSERT_EQ(error_of(other), "");
  expect_every_typo_named(other);

  json box = valid_scene();
  box["bodies"][0]["shape"] = {{"type", "box"}, {"size", {0.1, 0.2, 0.3}}};
  ASSERT_EQ(error_of(box), "");
  expect_every_typo_named(box);
  json ell = valid_scene();
  ell["bodies"][0]["shape"] = {{"type", "ellipsoid"}, {"semi_axes", {0.1, 0.2, 0.3}}};
  ASSERT_EQ(error_of(ell), "");
  expect_every_typo_named(ell);
}

TEST(SceneJson, AMeshsMassOffsetStaysInItsBoundingBox) {
  // a mesh's centre of mass is checked against its bounding box, measured from the volume
  // centroid (which is not the box's centre for a tetrahedron)
  const std::string mesh = std::string(LRIGID_SOURCE_DIR) + "/tests/data/meshes/tetra.obj";
  json j = valid_scene();
  j["bodies"][0]["shape"] = {{"type", "mesh"}, {"file", mesh}, {"scale", 0.01}};
  j["bodies"][0]["mass_offset"] = {0.0005, 0.0005, 0.0005};
  EXPECT_EQ(error_of(j), "");
  j["bodies"][0]["mass_offset"] = {0.02, 0, 0};
  ExitCode code = ExitCode::Ok;
  const std::string m = error_of(j, &code);
  EXPECT_EQ(code, ExitCode::BadInput);
  EXPECT_NE(m.find("bodies[0].mass_offset: [0.02, 0, 0] m from the volume centroid puts the "
                   "centre of mass outside the body (the mesh's bounding box "),
            std::string::npos)
      << m;
}

TEST(SceneJson, ASingleSidedLeafMeshTakesItsThickness) {
  // an open leaf as DCC tools export it (quads, UVs) with "thickness": the closed leaf it
  // stands for; without it, the message says what to add; a closed mesh refuses the key
  const std::string dir = std::string(LRIGID_SOURCE_DIR) + "/tests/data/meshes/";
  json j = valid_scene();
  j["bodies"][0]["shape"] = {{"type", "mesh"}, {"file", dir + "leaf_surface.obj"},
                             {"thickness", 4e-4}};
  const Scene s = parse_scene(j.dump(), "/tmp/scene.json");
  ASSERT_EQ(s.bodies[0].shape.type, ShapeType::Mesh);
  const double volume = mass_properties(s.bodies[0].shape).volume;
  // curled 4 mm over its 6 cm: 1.2 % more area than its 6 x 4 cm outline
  EXPECT_GT(volume, 1.005 * 0.06 * 0.04 * 4e-4);
  EXPECT_LT(volume, 1.02 * 0.06 * 0.04 * 4e-4);

  j["bodies"][0]["shape"].erase("thickness");
  std::string m = error_of(j);
  EXPECT_NE(m.find("bodies[0].shape.file: "), std::string::npos) << m;
  EXPECT_NE(m.find("leaf_surface.obj: mesh is open: 80 boundary edges"), std::string::npos) << m;
  EXPECT_NE(m.find("a single-sided surface (a leaf, a card) needs its thickness: \"shape\": "
                   "{\"type\": \"mesh\", \"file\": ..., \"thickness\": t} (m)"),
            std::string::npos)
      << m;

  // half of it is more than the curl's 11 cm radius: the inner layer folds over itself
  j["bodies"][0]["shape"]["thickness"] = 0.5;
  m = error_of(j);
  EXPECT_NE(m.find("bodies[0].shape.thickness: "), std::string::npos) << m;
  EXPECT_NE(m.find("intersects itself"), std::string::npos) << m;
  EXPECT_NE(m.find("the thickness 0.5 m is more than the surface's bends leave room for"),
            std::string::npos)
      << m;

  for (const json& bad : {json(-1e-4), json(0), json(2e6), json("thin")}) {
    j["bodies"][0]["shape"]["thickness"] = bad;
    m = error_of(j);
    EXPECT_NE(m.find("bodies[0].shape.thickness: "), std::string::npos) << bad << ": " << m;
  }

  j["bodies"][0]["shape"] = {{"type", "mesh"}, {"file", dir + "tetra.obj"}, {"scale", 0.01},
                             {"thickness", 4e-4}};
  m = error_of(j);
  EXPECT_NE(m.find("bodies[0].shape.thickness: " + dir +
                   "tetra.obj: surface is closed: \"thickness\" is for an open, single-sided "
                   "surface"),
            std::string::npos)
      << m;
}

}  // namespace
}  // namespace lrigid
