// glTF export: a run's animation.glb (and lrigid export-gltf's rebuild from the results files)
// read back with tinygltf must reproduce trajectories.csv at every output time.
#include <gtest/gtest.h>
#include <tiny_gltf.h>
#include <unistd.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "compile/compile_model.h"
#include "body/mass_properties.h"
#include "integrate/simulation.h"
#include "io/gltf_writer.h"
#include "io/result_writer.h"
#include "io/scene_json.h"
#include "support/fixture.h"
#include "support/gltf_read.h"
#include "util/error.h"

namespace lrigid {
namespace {

namespace fs = std::filesystem;

struct Row {
  double t;
  Vec3 x;
  Quat q;
};

// trajectories.csv by body
std::map<int, std::vector<Row>> read_csv(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::map<int, std::vector<Row>> rows;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string cell;
    std::vector<std::string> c;
    while (std::getline(ss, cell, ',')) c.push_back(cell);
    Row r;
    r.t = std::stod(c[2]);
    r.x = Vec3(std::stod(c[3]), std::stod(c[4]), std::stod(c[5]));
    r.q = Quat(std::stod(c[6]), std::stod(c[7]), std::stod(c[8]), std::stod(c[9]));
    rows[std::stoi(c[0])].push_back(r);
  }
  return rows;
}

using test::accessor_data;

// a free-flight run of spheres and boxes, tumbling (no effects: x = x0 + v t, torque-free spin)
Scene tumbling_scene(const std::string& dir) {
  Scene s = test::sphere_scene(0.01, 500, 1000, 1e-6, 3);
  s.bodies[0].velocity = Vec3(0.3, 0.0, -0.2);
  s.bodies[0].angular_velocity = Vec3(1.0, 2.0, 0.5);
  BodySpec box = s.bodies[0];
  box.name = "card";
  box.shape = Shape::box(0.09, 0.05, 0.004);
  box.count = 4;
  box.spawn_in_box = true;
  box.box_lo = Vec3(0, 0, 1);
  box.box_hi = Vec3(1, 1, 2);
  box.random_orientation = true;
  box.angular_velocity = Vec3(-3.0, 0.7, 5.0);
  s.bodies.push_back(box);
  s.dt = 0.01;
  s.duration = 1.0;
  s.output.dir = dir;
  s.output.every = 0.1;
  s.output.csv = true;
  s.output.pvd = true;
  s.output.glb = true;
  return s;
}

// runs the model from *st, writing the scene's outputs into dir as lrigid run does
void run_with_outputs(const Model& model, const Scene& scene, const std::string& dir, State* st) {
  ResultWriter w(dir, model, scene.output);
  RunOptions opt;
  opt.every = scene.output.every;
  opt.on_output = [&](const State& s) { w.write_frame(s); };
  const RunStats stats = simulate(model, st, opt);
  w.finish(*st, stats, nlohmann::json::object());
}

std::string run_to(const std::string& dir) {
  fs::remove_all(dir);
  const Scene scene = tumbling_scene(dir);
  const Model model = test::compile(scene);
  State st = initial_state(model, scene);
  run_with_outputs(model, scene, dir, &st);
  return dir;
}

// every body node's channels against trajectories.csv
void expect_matches_csv(const std::string& glb, const std::string& csv, size_t ntypes) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model m;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, glb)) << err;
  const auto rows = read_csv(csv);
  const size_t nb = rows.size();
  ASSERT_EQ(nb, 7u);
  ASSERT_EQ(m.nodes.size(), nb + 1);
  ASSERT_EQ(m.meshes.size(), ntypes);
  ASSERT_EQ(m.scenes.size(), 1u);
  ASSERT_EQ(m.scenes[0].nodes, std::vector<int>{0});

  // root: Z-up world -> glTF Y-up: the simulation's +z must become +y, +y become -z
  const tinygltf::Node& root = m.nodes[0];
  ASSERT_EQ(root.rotation.size(), 4u);
  const Quat rq(root.rotation[3], root.rotation[0], root.rotation[1], root.rotation[2]);
  EXPECT_TRUE(test::near(rq * Vec3(0, 0, 1), Vec3(0, 1, 0), 1e-12));
  EXPECT_TRUE(test::near(rq * Vec3(0, 1, 0), Vec3(0, 0, -1), 1e-12));
  EXPECT_EQ(root.children.size(), nb);

  ASSERT_EQ(m.animations.size(), 1u);
  const tinygltf::Animation& an = m.animations[0];
  EXPECT_EQ(an.channels.size(), 2 * nb);
  size_t checked = 0;
  for (const auto& ch : an.channels) {
    const int b = ch.target_node - 1;
    ASSERT_TRUE(rows.count(b)) << "node " << ch.target_node;
    const auto& r = rows.at(b);
    const tinygltf::AnimationSampler& s = an.samplers[size_t(ch.sampler)];
    EXPECT_EQ(s.interpolation, "LINEAR");
    const auto t = accessor_data<float>(m, s.input, 1);
    ASSERT_EQ(t.size(), r.size());
    for (size_t f = 0; f < r.size(); ++f) EXPECT_NEAR(t[f], r[f].t, 1e-6);
    if (ch.target_path == "translation") {
      const auto x = accessor_data<float>(m, s.output, 3);
      for (size_t f = 0; f < r.size(); ++f)
        EXPECT_TRUE(test::near(Vec3(x[3 * f], x[3 * f + 1], x[3 * f + 2]), r[f].x, 1e-6));
    } else {
      ASSERT_EQ(ch.target_path, "rotation");
      const auto q = accessor_data<float>(m, s.output, 4);  // x, y, z, w
      for (size_t f = 0; f < r.size(); ++f) {
        const Quat g(q[4 * f + 3], q[4 * f], q[4 * f + 1], q[4 * f + 2]);
        // the same rotation (q and -q are one rotation): compare the rotated axes
        EXPECT_TRUE(test::near(g.toRotationMatrix(), r[f].q.toRotationMatrix(), 2e-6));
        if (f > 0) {  // samples stay in one hemisphere so slerp takes the short way
          const Quat p(q[4 * f - 1], q[4 * f - 4], q[4 * f - 3], q[4 * f - 2]);
          EXPECT_GE(p.dot(g), 0.0);
        }
      }
    }
    // the static pose of the node is the first sample
    ++checked;
  }
  EXPECT_EQ(checked, 2 * nb);
  // the rotation really changes over the run (the test would not see a frozen export otherwise)
  EXPECT_GT(rows.at(0).back().q.angularDistance(rows.at(0).front().q), 0.5);

  // meshes are in the body frame: the box's vertices span exactly its half sizes
  for (size_t i = 0; i < m.meshes.size(); ++i) {
    const auto& prim = m.meshes[i].primitives.at(0);
    const auto& acc = m.accessors[size_t(prim.attributes.at("POSITION"))];
    ASSERT_EQ(acc.maxValues.size(), 3u);
    if (m.meshes[i].name == "card") {
      EXPECT_NEAR(acc.maxValues[0], 0.045, 1e-7);
      EXPECT_NEAR(acc.minValues[1], -0.025, 1e-7);
      EXPECT_NEAR(acc.maxValues[2], 0.002, 1e-7);
    } else {
      const auto p = accessor_data<float>(m, prim.attributes.at("POSITION"), 3);
      for (size_t k = 0; k < p.size(); k += 3)
        EXPECT_NEAR(Vec3(p[k], p[k + 1], p[k + 2]).norm(), 0.01, 1e-7);
    }
    EXPECT_GT(m.accessors[size_t(prim.indices)].count, 0u);
  }
  for (size_t b = 1; b <= nb; ++b) EXPECT_EQ(m.nodes[b].mesh, b <= 3 ? 0 : 1);
}

// "outside": "remove" (docs/contacts.md): a body that leaves the grid is written "exited" in
// trajectories.csv, counted in summary.json, scaled to 0 from its exit in animation.glb (a STEP
// scale channel) and left out by read_results (lrigid render, export-gltf); the others are not.
TEST(Gltf, BodiesRemovedAtTheGridsEdgeAreHidden) {
  const std::string dir = (fs::temp_directory_path() / ("lrigid_gltf_removed_" +
                                                        std::to_string(::getpid()))).string();
  fs::remove_all(dir);
  Scene s = test::sphere_scene(0.01, 500, 1.2, 1.5e-5, 2);
  s.uniform_field = false;
  s.effects = test::effects({Effect::MeanFlow, Effect::Drag});  // samples the field
  s.bodies[0].spawn_in_box = true;
  s.bodies[0].box_lo = Vec3(0.4, 0, 0.5);
  s.bodies[0].box_hi = Vec3(0.5, 0.1, 0.6);
  BodySpec still = s.bodies[0];
  still.name = "still";
  still.count = 1;
  still.spawn_in_box = false;
  still.position = Vec3(0, 0, 0.5);
  s.bodies[0].velocity = Vec3(4, 0, 0);  // leaves x = 1 at t = 0.13 s
  s.bodies.push_back(still);
  s.dt = 0.01;
  s.duration = 0.5;
  s.output.dir = dir;
  s.output.every = 0.1;
  s.output.glb = true;
  const GridGeometry g = test::grid_geometry(3, 3, 3, Vec3(-1, -1, 0), Vec3(1, 1, 1));
  const RawGridFrame f = test::grid_frame(g, [](const Vec3&, Vec3*, double*, double*) {
    return true;
  });
  const Model model =
      test::compile(s, FluidField::grid(g, {f}, 1.5e-5, Drift::Stationary, TimeMode::Clamp));
  ASSERT_EQ(model.outside, OutsideMode::Remove);
  State st = initial_state(model, s);
  run_with_outputs(model, s, dir, &st);
  ASSERT_EQ(st.status[0], BodyStatus::Exited);
  ASSERT_EQ(st.status[1], BodyStatus::Exited);
  ASSERT_EQ(st.status[2], BodyStatus::Moving);

  const Results r = read_results(dir, 80);
  EXPECT_EQ(r.summary["states"]["exited"], 2);
  EXPECT_EQ(r.summary["states"]["flying"], 1);
  EXPECT_EQ(r.summary["contacts"]["removed"], 2);
  const size_t nf = r.frames.times.size();
  ASSERT_EQ(nf, 6u);
  for (size_t fr = 0; fr < nf; ++fr) {
    const bool gone = r.frames.times[fr] > 0.15;
    EXPECT_EQ(r.frames.hidden_at(fr, 0), gone) << "t = " << r.frames.times[fr];
    EXPECT_EQ(r.frames.hidden_at(fr, 1), gone) << "t = " << r.frames.times[fr];
    EXPECT_FALSE(r.frames.hidden_at(fr, 2));
  }
  // each frame's state is read back from the state column, each type's body entry from the
  // summary
  ASSERT_EQ(r.frames.state.size(), nf * 3);
  EXPECT_EQ(r.frames.state[0], state_code_from_name("flying"));
  EXPECT_EQ(r.frames.state[(nf - 1) * 3 + 0], state_code_from_name("exited"));
  EXPECT_EQ(r.frames.state[(nf - 1) * 3 + 2], state_code_from_name("flying"));
  ASSERT_EQ(r.frames.types.size(), 2u);
  EXPECT_EQ(r.frames.types[0].entry, 0u);
  EXPECT_EQ(r.frames.types[1].entry, 1u);
  EXPECT_EQ(r.frames.types[1].variant, 0);
  tinygltf::TinyGLTF loader;
  tinygltf::Model m;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, dir + "/animation.glb")) << err;
  size_t scale_channels = 0;
  for (const auto& ch : m.animations.at(0).channels) {
    if (ch.target_path != "scale") continue;
    ++scale_channels;
    EXPECT_NE(ch.target_node, 3) << "the body still in the grid keeps its size";
    const tinygltf::AnimationSampler& sm = m.animations[0].samplers[size_t(ch.sampler)];
    EXPECT_EQ(sm.interpolation, "STEP");
    const auto k = accessor_data<float>(m, sm.output, 3);
    ASSERT_EQ(k.size(), 3 * nf);
    EXPECT_EQ(k[0], 1.f);
    EXPECT_EQ(k[3 * (nf - 1)], 0.f);
  }
  EXPECT_EQ(scale_channels, 2u);
  fs::remove_all(dir);
}

// bodies[i].release (model/release.h): a body waiting for its release has no row in
// trajectories.csv, is unreleased and hidden in what read_results gives (lrigid render,
// export-gltf) at its first recorded pose, scaled to 0 until its release in animation.glb, and
// has the state 7 (unreleased) in bodies.pvd; summary.json counts the released bodies.
TEST(Gltf, UnreleasedBodiesAreLeftOutOrHiddenUntilTheirRelease) {
  const std::string dir = (fs::temp_directory_path() / ("lrigid_gltf_release_" +
                                                        std::to_string(::getpid()))).string();
  fs::remove_all(dir);
  Scene s = tumbling_scene(dir);
  s.bodies[1].release_times = {0.35, 0.75};  // the 4 cards, 2 at each time
  const Model model = test::compile(s);
  State st = initial_state(model, s);
  run_with_outputs(model, s, dir, &st);
  // released at the outputs of 0.4 s (cards 3, 4) and 0.8 s (cards 5, 6)
  auto released_at = [](size_t body, double t) {
    return body < 3 || (body < 5 ? t > 0.35 : t > 0.75);
  };
  {
    std::ifstream csv(dir + "/trajectories.csv");
    std::string line;
    std::getline(csv, line);
    std::map<double, std::vector<size_t>> rows;  // time -> bodies with a row
    while (std::getline(csv, line)) {
      std::stringstream f(line);
      std::string body, type, t;
      std::getline(f, body, ',');
      std::getline(f, type, ',');
      std::getline(f, t, ',');
      rows[std::stod(t)].push_back(std::stoul(body));
    }
    ASSERT_EQ(rows.size(), 11u);
    for (const auto& [t, bodies] : rows) {
      std::vector<size_t> expected;
      for (size_t b = 0; b < 7; ++b)
        if (released_at(b, t)) expected.push_back(b);
      EXPECT_EQ(bodies, expected) << "t = " << t;
    }
  }
  const Results r = read_results(dir, 80);
  EXPECT_EQ(r.summary["released"], 7);
  EXPECT_EQ(r.summary["contacts"]["removed"], 0);
  const size_t nf = r.frames.times.size();
  ASSERT_EQ(nf, 11u);
  const int unreleased = state_code_from_name("unreleased");
  for (size_t fr = 0; fr < nf; ++fr)
    for (size_t b = 0; b < 7; ++b) {
      const double t = r.frames.times[fr];
      EXPECT_EQ(r.frames.hidden_at(fr, b), !released_at(b, t)) << "body " << b << " t = " << t;
      EXPECT_EQ(r.frames.state[fr * 7 + b] == unreleased, !released_at(b, t))
          << "body " << b << " t = " << t;
    }
  EXPECT_EQ(r.frames.x[0 * 7 + 5], r.frames.x[8 * 7 + 5]) << "its first recorded pose before it";
  EXPECT_NE(r.frames.x[8 * 7 + 5], r.frames.x[9 * 7 + 5]) << "and it moves from its release on";

  tinygltf::TinyGLTF loader;
  tinygltf::Model m;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, dir + "/animation.glb")) << err;
  size_t scale_channels = 0;
  for (const auto& ch : m.animations.at(0).channels) {
    if (ch.target_path != "scale") continue;
    ++scale_channels;
    const tinygltf::AnimationSampler& sm = m.animations[0].samplers[size_t(ch.sampler)];
    EXPECT_EQ(sm.interpolation, "STEP");
    const auto k = accessor_data<float>(m, sm.output, 3);
    ASSERT_EQ(k.size(), 3 * nf);
    EXPECT_EQ(k[0], 0.f) << "hidden at t = 0";
    EXPECT_EQ(k[3 * 3], 0.f) << "and at t = 0.3 s";
    EXPECT_EQ(k[3 * (nf - 1)], 1.f) << "shown at the end";
  }
  EXPECT_EQ(scale_channels, 4u) << "the four cards";

  vtkNew<vtkXMLPolyDataReader> points;
  points->SetFileName((dir + "/bodies/bodies_000000.vtp").c_str());
  points->Update();
  vtkDataArray* state = points->GetOutput()->GetPointData()->GetArray("state");
  ASSERT_NE(state, nullptr);
  ASSERT_EQ(state->GetNumberOfTuples(), 7);
  for (vtkIdType b = 0; b < 7; ++b)
    EXPECT_EQ(state->GetComponent(b, 0) == unreleased, b >= 3) << "body " << b;
  fs::remove_all(dir);
}

TEST(Gltf, RunAnimationMatchesTrajectories) {
  const std::string dir = ::testing::TempDir() + "gltf_run_" + std::to_string(::getpid());
  run_to(dir);
  expect_matches_csv(dir + "/animation.glb", dir + "/trajectories.csv", 2);
  // the shapes series came along with the points
  EXPECT_TRUE(fs::exists(dir + "/shapes.pvd"));
  EXPECT_TRUE(fs::exists(dir + "/shapes/shapes_000010.vtp"));
  // no temporary names left behind
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
  fs::remove_all(dir);
}

TEST(Gltf, ExportFromResultsFilesMatchesTrajectories) {
  const std::string dir = ::testing::TempDir() + "gltf_export_" + std::to_string(::getpid());
  run_to(dir);
  const Results r = read_results(dir, 320);
  EXPECT_EQ(r.frames.times.size(), 11u);
  write_gltf(dir + "/exported.glb", r.frames);
  expect_matches_csv(dir + "/exported.glb", dir + "/trajectories.csv", 2);
  fs::remove_all(dir);
}

TEST(Gltf, ASingleSidedLeafIsReadBackAsTheBodyItWas) {
  // a leaf surface scaled by 2 and given a thickness: render and export-gltf rebuild the thin
  // body the run simulated (the summary's scale and thickness), not the open surface
  const std::string dir = ::testing::TempDir() + "gltf_leaf_" + std::to_string(::getpid());
  fs::remove_all(dir);
  const std::string mesh = std::string(LRIGID_SOURCE_DIR) + "/tests/data/meshes/leaf_surface.obj";
  const Scene scene = parse_scene(R"({"version": 1, "fluid": {"density": 1.2,
      "kinematic_viscosity": 1.5e-5, "uniform": {"U": [1, 0, 0], "k": 0.01, "epsilon": 0.01}},
      "gravity": [0, 0, -9.81], "effects": ["gravity", "drag"],
      "integrator": {"scheme": "splitting", "dt": 0.01}, "duration": 0.1, "seed": 1,
      "bodies": [{"name": "leaf", "shape": {"type": "mesh", "file": ")" + mesh + R"(",
                  "scale": 2, "thickness": 0.0008}, "density": 600, "count": 3,
                  "position": [0, 0, 1]}],
      "output": {"dir": ")" + dir + R"(", "every": 0.05, "formats": ["csv", "glb"]}})",
                                  dir + "/scene.json");
  const Model model = test::compile(scene);
  State st = initial_state(model, scene);
  run_with_outputs(model, scene, dir, &st);
  const Results r = read_results(dir, 320);
  ASSERT_EQ(r.frames.types.size(), 1u);
  const Shape back = Shape::from_mesh(
      std::make_shared<const TriangleMesh>(r.frames.types[0].surface), "read back");
  const double volume = mass_properties(back).volume;
  EXPECT_NEAR(volume, model.types[0].volume, 1e-9 * model.types[0].volume);
  // twice the 6 x 4 cm leaf, 0.8 mm thick
  EXPECT_NEAR(volume, 0.12 * 0.08 * 8e-4, 0.02 * 0.12 * 0.08 * 8e-4);
  fs::remove_all(dir);
}

TEST(Gltf, RunTooLongToKeepInMemoryIsRefusedUpFront) {
  const std::string dir = ::testing::TempDir() + "gltf_huge_" + std::to_string(::getpid());
  Scene scene = tumbling_scene(dir);
  scene.duration = 1e9;  // 1e10 frames of 7 bodies: far beyond any machine's memory
  const Model model = test::compile(scene);
  try {
    ResultWriter w(dir, model, scene.output);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::Resource);
    EXPECT_NE(std::string(e.what()).find("output.formats"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

// A run killed while writing its animation leaves animation.glb.tmpPID.tmpPID (the staged name's
// own temporary); the resumed run must clear what the interrupted one began of its final files
// and keep its output so far, or the results folder differs from an uninterrupted run's. It
// clears them only once the checkpoint has passed its checks (go_on): a writer made for a
// resume that is then refused removes nothing.
TEST(Gltf, ResumeClearsTheInterruptedRunsUnfinishedFiles) {
  const std::string dir = ::testing::TempDir() + "gltf_resume_" + std::to_string(::getpid());
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string tag = ".tmp42";
  for (const char* name : {"trajectories.csv", "animation.glb", "animation.glb.tmp42",
                           "landings.csv.tmp42", "bodies.pvd.tmp42", "notes.tmp421"})
    std::ofstream(dir + "/" + name + (std::string(name) == "trajectories.csv" ? tag : ""))
        << "x\n";
  std::ofstream(dir + "/animation.glb.tmp42.tmp42") << "half\n";
  // the animation.glb there is an earlier run's result (its manifest says so): the run may
  // replace it at its finish, so it does not refuse to start (io/results_dir.h)
  std::ofstream(dir + "/lrigid-manifest.json")
      << R"({"files": ["animation.glb"], "folders": {}})" << "\n";
  fs::create_directories(dir + "/bodies" + tag);
  fs::create_directories(dir + "/shapes" + tag);
  std::ofstream(dir + "/bodies" + tag + "/bodies_0000.vtp") << "frame\n";
  const Scene scene = tumbling_scene(dir);
  const Model model = test::compile(scene);
  auto listing = [&] {
    std::vector<std::string> v;
    for (const auto& e : fs::recursive_directory_iterator(dir))
      v.push_back(fs::relative(e.path(), dir).string());
    std::sort(v.begin(), v.end());
    return v;
  };
  const std::vector<std::string> before = listing();
  {
    ResultWriter w(dir, model, scene.output, tag);
  }
  EXPECT_EQ(listing(), before) << "a resume refused before go_on() changed the folder";
  {
    ResultWriter w(dir, model, scene.output, tag);
    w.go_on();
  }
  const std::vector<std::string> left = listing();
  // what is not the interrupted run's stays (another run's animation.glb, notes.tmp421)
  for (const char* gone : {"animation.glb.tmp42", "animation.glb.tmp42.tmp42",
                           "landings.csv.tmp42", "bodies.pvd.tmp42"})
    EXPECT_EQ(std::count(left.begin(), left.end(), gone), 0) << gone;
  for (const char* kept : {"animation.glb", "notes.tmp421"})
    EXPECT_EQ(std::count(left.begin(), left.end(), kept), 1) << kept;
  fs::remove_all(dir);
}

TEST(Gltf, BadInputIsRefused) {
  const std::string dir = ::testing::TempDir();
  GltfAnimation a;
  a.types.push_back({"s", {}});
  a.body_type = {0};
  EXPECT_THROW(write_gltf(dir + "/none.glb", a), Error);  // no frames
  a.times = {0.0};
  a.x = {Vec3::Zero()};
  EXPECT_THROW(write_gltf(dir + "/none.glb", a), Error);  // q missing
  EXPECT_FALSE(fs::exists(dir + "/none.glb"));
  try {
    read_results(dir + "/no_such_results", 20);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("summary.json: file not found"), std::string::npos);
  }
}

}  // namespace
}  // namespace lrigid
