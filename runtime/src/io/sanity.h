// Sanity checks of a scene before it runs (docs/scene-format.md, "Sanity warnings"):
// what is valid input but most likely a mistake, above all in units (sizes in centimetres
// written as metres, a spawn box in another frame than the grid). Each finding names the scene
// key, its value, what looks wrong and what to check.
//   - a body type whose size or mass is implausible for its fluid and grid
//   - a density no material has
//   - a spawn box or position outside the grid, inside the flow's solids, or under the ground
//   - a time step beyond what the chosen scheme was measured to handle (docs/stability.md)
//   - bodies released after the run ends (bodies[i].release)
//   - a grid too coarse for the bodies (the bodies all start within one cell; a grid of fewer
//     than 4 points along an axis)
// Findings are warnings, except one: every body of the scene starting outside the grid or inside
// its solids is an error (the run would end at t = 0). `lrigid run --strict` makes every warning an error.
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "compile/compile_model.h"
#include "model/model.h"
#include "model/scene.h"

namespace lrigid {

struct SanityFinding {
  std::string check;    // which check: body_size, body_mass, density, spawn_outside_grid,
                        // spawn_partly_outside_grid, spawn_inside_solid,
                        // spawn_partly_inside_solid, spawn_below_ground, dt_stability,
                        // grid_coarse, release_after_end, all_outside_grid,
                        // all_outside_fluid
  std::string key;      // the scene key, e.g. "bodies[0].shape"
  std::string message;  // the value, what looks wrong, what to check
  bool error = false;   // an error even without --strict
};

std::vector<SanityFinding> check_scene(const Scene& scene, const Model& model);

// [{check, key, message, error}] for summary.json and lrigid explain's data
nlohmann::json findings_json(const std::vector<SanityFinding>& findings);

// Prints each finding to stderr ("lrigid: warning: FILE: KEY: MESSAGE"; not with quiet, but
// errors always), then throws lrigid::Error(ExitCode::BadInput) naming the first one that is an
// error, or, with `strict`, the first warning.
void report_findings(const std::vector<SanityFinding>& findings, const std::string& scene_file,
                     bool strict, bool quiet);

}  // namespace lrigid
