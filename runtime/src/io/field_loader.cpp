#include "io/field_loader.h"

#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <utility>
#include <vector>

#include "io/grid_reader.h"
#include "util/error.h"

namespace lrigid {

StreamMode stream_mode_from(const std::string& word) {
  if (word == "auto") return StreamMode::Auto;
  if (word == "on") return StreamMode::On;
  if (word == "off") return StreamMode::Off;
  throw Error(ExitCode::Usage, "--stream-field: \"" + word + "\" is not one of auto, on, off");
}

double physical_memory() {
  return double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
}

FluidField load_field(const Scene& scene, StreamMode stream, bool quiet) {
  if (scene.uniform_field)
    return FluidField::uniform(scene.uniform_U, scene.uniform_k, scene.uniform_epsilon,
                               scene.kinematic_viscosity, scene.drift);
  RawGridFrame first;
  auto series = std::make_shared<GridSeries>(open_grid_series(scene.field_path, &first));
  const GridSeries& g = *series;
  if (g.kinematic_viscosity > 0 &&
      std::abs(g.kinematic_viscosity - scene.kinematic_viscosity) > 0.01 * g.kinematic_viscosity &&
      !quiet)
    std::cerr << "lrigid: warning: " << scene.file
              << ": fluid.kinematic_viscosity = " << scene.kinematic_viscosity
              << " m^2/s differs from the grid's " << g.kinematic_viscosity << " m^2/s ("
              << scene.field_path << ")\n";
  if (!g.has_wall_distance && !quiet)
    std::cerr << "lrigid: note: " << scene.field_path
              << " has no point array wall_distance (a grid of an older foam2grid, or a case "
                 "without wall patches): bodies meet the solids as before, stopping where the "
                 "grid's valid points end; convert the case again with foam2grid to add it\n";
  const double all_bytes =
      double(g.times.size()) * double(g.geometry.points()) * sizeof(GridRecord);
  const bool streamed =
      g.times.size() > 2 && (stream == StreamMode::On ||
                             (stream == StreamMode::Auto && all_bytes > 0.5 * physical_memory()));
  if (streamed) {
    if (!quiet)
      std::fprintf(stderr,
                   "lrigid: streaming %s: %zu frames of %.3g MB, 2 or 3 in memory at once\n",
                   scene.field_path.c_str(), g.times.size(), all_bytes / g.times.size() / 1e6);
    // frame 0 was read with the series header: handed over, not read again
    return FluidField::streamed(
        g.geometry, g.times, [series](size_t i) { return series->load(i); },
        scene.kinematic_viscosity, scene.drift, scene.time_mode, {}, &first);
  }
  std::vector<RawGridFrame> frames;
  frames.push_back(std::move(first));
  for (size_t i = 1; i < g.times.size(); ++i) frames.push_back(g.load(i));
  return FluidField::grid(g.geometry, frames, scene.kinematic_viscosity, scene.drift,
                          scene.time_mode);
}

void check_memory(const Scene& scene) {
  // bytes of state per body (State arrays plus the writer's per-frame buffers)
  constexpr double kBytesPerBody = 4 * sizeof(Vec3) + sizeof(Quat) + sizeof(Vec3) + 64;
  size_t n = 0;
  for (const auto& b : scene.bodies) n += size_t(b.count);
  const double need = double(n) * kBytesPerBody;
  // the physical memory, or the address-space limit (ulimit -v) when that is lower
  double have = physical_memory();
  std::string what = "this machine has";
  struct rlimit lim {};
  if (getrlimit(RLIMIT_AS, &lim) == 0 && lim.rlim_cur != RLIM_INFINITY &&
      double(lim.rlim_cur) < have) {
    have = double(lim.rlim_cur);
    what = "the address-space limit (ulimit -v) is";
  }
  if (need > 0.8 * have) {
    char buf[240];
    std::snprintf(buf, sizeof buf, "%zu bodies need about %.1f GiB of memory; %s %.1f GiB", n,
                  need / (1 << 30), what.c_str(), have / (1 << 30));
    throw Error(ExitCode::Resource, where(scene.file, "bodies", buf));
  }
}

}  // namespace lrigid
