// A short run written with every cache for DCC tools (io/dcc_cache.h): three leaves of an OBJ
// with texture coordinates in two variants and two pebbles, tumbling; and trajectories.csv read
// back whole, what each cache is checked against.
#pragma once
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "integrate/simulation.h"
#include "io/result_writer.h"
#include "io/scene_json.h"
#include "support/fixture.h"

namespace lrigid::test {

struct TrajectoryRow {
  size_t body;
  std::string type;
  double t;
  Vec3 x;
  Quat q;
  Vec3 v, w;
  std::string state;
};

// trajectories.csv, row by row (frame by frame, bodies in order)
inline std::vector<TrajectoryRow> read_trajectories(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<TrajectoryRow> rows;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string cell;
    std::vector<std::string> c;
    while (std::getline(ss, cell, ',')) c.push_back(cell);
    if (c.size() < 17) continue;
    auto d = [&](size_t i) { return std::stod(c[i]); };
    rows.push_back({size_t(std::stoul(c[0])), c[1], d(2), Vec3(d(3), d(4), d(5)),
                    Quat(d(6), d(7), d(8), d(9)), Vec3(d(10), d(11), d(12)),
                    Vec3(d(13), d(14), d(15)), c[16]});
  }
  return rows;
}

inline std::string leaf_obj() {
  return std::string(LRIGID_SOURCE_DIR) + "/tests/data/meshes/leaf_surface.obj";
}

// runs the scene into `dir` with `formats` (a JSON list), as lrigid run does
inline void run_dcc_scene(const std::string& dir, const std::string& formats) {
  const Scene scene = parse_scene(R"({"version": 1, "fluid": {"density": 1.2,
      "kinematic_viscosity": 1.5e-5, "uniform": {"U": [1, 0, 0], "k": 0.01, "epsilon": 0.01}},
      "gravity": [0, 0, -9.81], "effects": ["gravity", "drag"],
      "integrator": {"scheme": "splitting", "dt": 0.01}, "duration": 0.2, "seed": 1,
      "bodies": [{"name": "leaf", "shape": {"type": "mesh", "file": ")" + leaf_obj() + R"(",
                  "scale": 2, "thickness": 0.0008}, "density": 600, "count": 3,
                  "position": [0, 0, 1], "angular_velocity": [3, 1, 2],
                  "variation": {"size": [0.9, 1.1], "variants": 2}},
                 {"name": "pebble", "shape": {"type": "sphere", "radius": 0.004},
                  "density": 2500, "count": 2, "position": [0.2, 0, 1],
                  "velocity": [0.5, 0, 0], "angular_velocity": [0, 4, 0]}],
      "output": {"dir": ")" + dir + R"(", "every": 0.05, "formats": )" + formats + "}}",
                                  dir + "/scene.json");
  const Model model = compile(scene);
  State st = initial_state(model, scene);
  ResultWriter w(dir, model, scene.output);
  RunOptions opt;
  opt.every = scene.output.every;
  opt.on_output = [&](const State& s) { w.write_frame(s); };
  const RunStats stats = simulate(model, &st, opt);
  w.finish(st, stats, nlohmann::json::object());
}

}  // namespace lrigid::test
