// Choosing an integrator and time step for a requested accuracy (lrigid run --tolerance E),
// from the error-versus-cost table the accuracy study measured (docs/accuracy.md). Pure
// functions: reading the table from disk is io/tolerance_table.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "model/scene.h"

namespace lrigid {

// One measured point of the study.
struct ToleranceEntry {
  std::string integrator;  // "euler", "rk4", "splitting"
  double dt = 0;           // s
  double error = 0;        // relative pathwise error (docs/accuracy.md), dimensionless
  double cost = 0;         // CPU seconds per body per simulated second, s/s
};

struct ToleranceTable {
  std::string source;                                        // file, for messages
  std::map<std::string, std::vector<ToleranceEntry>> kinds;  // scene kind -> points
};

// The kind of a scene, the key of the table: "<field>-<medium>", field "uniform" or "grid"
// (a CFD field has shear and k gradients a uniform one lacks), medium "air" when the fluid is a
// gas (density below 100 kg/m^3: bodies 10^2-10^3 times denser, drag-dominated) else "water"
// (density ratios of order 1: added mass and buoyancy dominate).
std::string scene_kind(const Scene& scene);

struct ToleranceChoice {
  ToleranceEntry entry;
  std::string kind;         // the table's kind that was used
  std::string explanation;  // one line for the user
};

// The cheapest entry of `kind` (else, if the table lacks it, of a kind with the same medium)
// whose measured error is at most `tolerance` (relative, > 0). Throws lrigid::Error
// (ExitCode::BadInput) naming the table when the kind is missing or no entry reaches the
// tolerance (the message gives the smallest measured error).
ToleranceChoice choose_for_tolerance(const ToleranceTable& table, const std::string& kind,
                                     double tolerance);

}  // namespace lrigid
