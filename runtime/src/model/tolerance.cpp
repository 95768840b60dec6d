#include "model/tolerance.h"

#include <algorithm>
#include <cmath>
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
  const ToleranceEntry* most_accurate = nullptr;
  for (const ToleranceEntry& e : it->second) {
    if (!most_accurate || e.error < most_accurate->error) most_accurate = &e;
    if (e.error > tolerance) continue;
    if (!best || e.cost < best->cost || (e.cost == best->cost && e.dt > best->dt)) best = &e;
  }
  if (!best) {
    // the flag's value is what is wrong, not the table: say so first, then what is reachable
    // for this kind of scene and for the others, then where the measurements are
    std::string others;
    for (const auto& [k, entries] : table.kinds) {
      if (k == used || entries.empty()) continue;
      double m = entries[0].error;
      for (const ToleranceEntry& e : entries) m = std::min(m, e.error);
      char b[80];
      std::snprintf(b, sizeof b, "%s'%s' from %.2g", others.empty() ? "" : ", ", k.c_str(), m);
      others += b;
    }
    // the smallest error rounded up to 2 significant digits: a value that is reachable
    const double m = most_accurate->error;
    const double unit = std::pow(10.0, std::floor(std::log10(m)) - 1);
    const double suggest = std::ceil(m / unit * (1 - 1e-12)) * unit;
    char buf[600];
    std::snprintf(buf, sizeof buf,
                  "--tolerance %g is not reachable for '%s' scenes: the most accurate measured "
                  "point is %s at dt = %g s with a relative error of %.3g, so the reachable "
                  "tolerances are %.3g and above (other kinds of scenes: %s). Pass --tolerance "
                  "%.2g or more, or set integrator.scheme and integrator.dt in the scene yourself "
                  "(measurements: %s, docs/accuracy.md)",
                  tolerance, used.c_str(), most_accurate->integrator.c_str(), most_accurate->dt,
                  m, m, others.empty() ? "none" : others.c_str(), suggest, table.source.c_str());
    throw Error(ExitCode::BadInput, buf);
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
