#include "model/tolerance.h"

#include <algorithm>
#include <cstdio>
#include <limits>

#include "util/error.h"

namespace lrigid {

namespace {

std::string medium_of(const std::string& kind) {
  const size_t dash = kind.find('-');
  return dash == std::string::npos ? kind : kind.substr(dash + 1);
}

}  // namespace

std::string scene_kind(const Scene& scene) {
  const std::string field = scene.uniform_field ? "uniform" : "grid";
  const std::string medium = scene.fluid_density < 100 ? "air" : "water";
  return field + "-" + medium;
}

ToleranceChoice choose_for_tolerance(const ToleranceTable& table, const std::string& kind,
                                     double tolerance) {
  if (!(tolerance > 0))
    throw Error(ExitCode::Usage, "--tolerance must be a positive relative error, got " +
                                     std::to_string(tolerance));
  std::string used = kind;
  auto it = table.kinds.find(kind);
  if (it == table.kinds.end()) {
    for (auto k = table.kinds.begin(); k != table.kinds.end(); ++k)
      if (medium_of(k->first) == medium_of(kind)) {
        it = k;
        used = k->first;
        break;
      }
  }
  if (it == table.kinds.end() || it->second.empty()) {
    std::string have;
    for (const auto& k : table.kinds) have += (have.empty() ? "" : ", ") + k.first;
    throw Error(ExitCode::BadInput,
                where(table.source, "kinds", "no measurements for scenes of kind '" + kind +
                                                 "' (the table has: " + have + ")"));
  }
  const ToleranceEntry* best = nullptr;
  double smallest = std::numeric_limits<double>::infinity();
  for (const ToleranceEntry& e : it->second) {
    smallest = std::min(smallest, e.error);
    if (e.error > tolerance) continue;
    if (!best || e.cost < best->cost || (e.cost == best->cost && e.dt > best->dt)) best = &e;
  }
  if (!best) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "no measured integrator and dt reaches a relative error of %g for '%s' "
                  "scenes; the smallest measured is %.3g",
                  tolerance, used.c_str(), smallest);
    throw Error(ExitCode::BadInput, where(table.source, "kinds." + used, buf));
  }
  ToleranceChoice c;
  c.entry = *best;
  c.kind = used;
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "tolerance %g: %s with dt = %g s (measured error %.3g, cost %.3g s per body per "
                "simulated second, the cheapest of %zu measured points for '%s' scenes%s)",
                tolerance, best->integrator.c_str(), best->dt, best->error, best->cost,
                it->second.size(), used.c_str(),
                used == kind ? "" : (", the closest kind to '" + kind + "'").c_str());
  c.explanation = buf;
  return c;
}

}  // namespace lrigid
