// lrigid info GRID: what a grid file holds, for placing bodies in it (io/grid_info.h): its box,
// spacing and times, the flow over the whole grid, and each solid (a building, a wall, an
// insert: points without flow) with its bounding box and the flow around it.
#include <cstdio>
#include <ostream>
#include <memory>
#include <string>

#include "commands.h"
#include "io/atomic_file.h"
#include "io/grid_info.h"

namespace lrigid::app {

namespace {

using nlohmann::json;

std::string box(const json& lo, const json& hi) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "[[%.4g, %.4g, %.4g], [%.4g, %.4g, %.4g]]", lo[0].get<double>(),
                lo[1].get<double>(), lo[2].get<double>(), hi[0].get<double>(),
                hi[1].get<double>(), hi[2].get<double>());
  return buf;
}

void info(const std::string& grid, const std::string& json_out, size_t max_solids) {
  const json j = grid_info(grid, max_solids);
  if (!json_out.empty())
    write_file_atomically(json_out, [&](std::ostream& o) { o << j.dump(1) << "\n"; }, false);
  const json& p = j["points"];
  std::printf("grid: %s\n", grid.c_str());
  std::printf("box %s m, spacing %.4g x %.4g x %.4g m, %d x %d x %d points\n",
              box(j["origin"], j["upper"]).c_str(), j["spacing"][0].get<double>(),
              j["spacing"][1].get<double>(), j["spacing"][2].get<double>(), p[0].get<int>(),
              p[1].get<int>(), p[2].get<int>());
  const json& t = j["times"];
  if (t.size() > 1)
    std::printf("times: %zu frames, %.4g to %.4g s\n", t.size(), t.front().get<double>(),
                t.back().get<double>());
  else
    std::printf("time: %.4g s (steady)\n", t.front().get<double>());
  std::printf("kinematic viscosity %.3g m^2/s; wall distance: %s\n",
              j["kinematic_viscosity"].get<double>(),
              j["has_wall_distance"].get<bool>() ? "yes" : "no (an older foam2grid)");
  const json& f = j["flow"];
  std::printf("flow over %zu fluid points (the first frame): |U| median %.3g m/s, largest %.3g "
              "m/s; k median %.3g m^2/s^2\n",
              j["fluid_points"].get<size_t>(), f["U_median"].get<double>(),
              f["U_max"].get<double>(), f["k_median"].get<double>());
  const json& s = j["solids"];
  const size_t total = j["solids_total"].get<size_t>();
  if (total == 0) {
    std::printf("solids: none (every point has flow)\n");
    return;
  }
  std::printf("solids (points without flow, each a connected set; its box is within half a "
              "spacing of its surface; the flow 3 spacings out from it):\n");
  for (size_t i = 0; i < s.size(); ++i)
    std::printf("  %zu. %s m, %zu points; around it |U| median %.3g m/s, k %.3g m^2/s^2\n", i + 1,
                box(s[i]["lo"], s[i]["hi"]).c_str(), s[i]["points"].get<size_t>(),
                s[i]["around"]["U_median"].get<double>(),
                s[i]["around"]["k_median"].get<double>());
  if (total > s.size())
    std::printf("  ... and %zu smaller (--solids N shows more)\n", total - s.size());
}

}  // namespace

void add_info_command(CLI::App& app) {
  auto grid = std::make_shared<std::string>();
  auto json_out = std::make_shared<std::string>();
  auto max_solids = std::make_shared<size_t>(20);
  auto* cmd = app.add_subcommand(
      "info", "What a grid file (.vti or .pvd) holds: its box, spacing and times, the flow, and "
              "each solid (building, wall) with its bounding box and the flow around it, for "
              "placing spawn boxes (m)");
  cmd->add_option("grid", *grid, "Grid file written by foam2grid (.vti, or a .pvd series)")
      ->required();
  cmd->add_option("--json", *json_out, "Also write the data as JSON to this file");
  cmd->add_option("--solids", *max_solids, "How many solids to list, largest first")
      ->check(CLI::Range(size_t(1), size_t(100000)));
  cmd->callback([grid, json_out, max_solids] { info(*grid, *json_out, *max_solids); });
}

}  // namespace lrigid::app
