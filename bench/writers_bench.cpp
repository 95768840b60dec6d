// The cost of the outputs against the simulation (docs/performance.md, "Output cost"):
// runs a scene (default: scenes/leaves_wind.json, the scene ./Allrun runs) and, at every output
// frame, writes it with each writer in turn, timing each one on its own:
//   csv     trajectories.csv rows (io/result_writer.h, "csv" only)
//   bodies  bodies_NNNNNN.vtp (io/vtp_frames.h)      } together: "pvd"
//   shapes  shapes_NNNNNN.vtp (io/vtp_frames.h)      }
//   glb, glb_instanced, houdini, usd   the caches for DCC tools (io/dcc_cache.h), each alone:
//           the frame kept in memory, plus its file written at the end, shared out per frame
// then runs it again with lrigid run's own writer (csv + pvd, the .vtp frames on a thread of
// their own) and times what the run's thread pays for it. Prints, per writer, CPU and wall time per frame and per body per frame, and bytes per frame,
// next to the simulation's time for the steps between two frames. CPU time is this process's
// (the machine may be shared: wall time is then an upper bound).
//   build/bin/writers_bench [--scene S] [--duration T] [--every DT] [--threads 1]
//                           [--compression lz4|none|zlib] [--dir D] [--json]
// Needs the scene's grid (results/grids/windCourtyard.vti for the default scene: ./Allrun).
#include <time.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "compile/compile_model.h"
#include "integrate/simulation.h"
#include "io/added_mass_cache.h"
#include "io/dcc_cache.h"
#include "io/field_loader.h"
#include "io/result_writer.h"
#include "io/scene_json.h"
#include "io/vtp_frames.h"
#include "model/state.h"

namespace fs = std::filesystem;
using namespace lrigid;

namespace {

// this thread's CPU time (the simulation runs on it with --threads 1; the frames' thread of
// the second pass is not counted)
double cpu_now() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}
double wall_now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

struct Clock {
  double cpu = 0, wall = 0;
  template <class F>
  void time(F&& f) {
    const double c0 = cpu_now(), w0 = wall_now();
    f();
    cpu += cpu_now() - c0;
    wall += wall_now() - w0;
  }
};

uintmax_t bytes_under(const fs::path& p) {
  uintmax_t n = 0;
  std::error_code ec;
  if (fs::is_regular_file(p, ec)) return fs::file_size(p, ec);
  for (const auto& e : fs::recursive_directory_iterator(p, ec))
    if (e.is_regular_file(ec)) n += e.file_size(ec);
  return n;
}

[[noreturn]] void usage(const char* why) {
  std::fprintf(stderr, "writers_bench: %s\nusage: writers_bench [--scene S] [--duration T] "
                       "[--every DT] [--threads N] [--compression lz4|none|zlib] [--dir D] [--json]\n",
               why);
  std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
  std::string scene_path = std::string(LRIGID_SOURCE_DIR) + "/scenes/leaves_wind.json";
  double duration = -1, every = -1;
  int threads = 1;
  std::string compression = "lz4";
  std::string dir = (fs::temp_directory_path() / "lrigid_writers_bench").string();
  bool as_json = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) usage(("missing value after " + a).c_str());
      return argv[++i];
    };
    if (a == "--scene") scene_path = next();
    else if (a == "--duration") duration = std::atof(next().c_str());
    else if (a == "--every") every = std::atof(next().c_str());
    else if (a == "--threads") threads = std::atoi(next().c_str());
    else if (a == "--compression") compression = next();
    else if (a == "--dir") dir = next();
    else if (a == "--json") as_json = true;
    else usage(("unknown argument " + a).c_str());
  }
  const VtpCompression comp = compression == "none"   ? VtpCompression::None
                              : compression == "zlib" ? VtpCompression::ZLib
                              : compression == "lz4"  ? VtpCompression::LZ4
                                                      : (usage("--compression: lz4, none or zlib"),
                                                         VtpCompression::None);
  try {
    Scene scene = read_scene(scene_path);
    if (duration > 0) scene.duration = duration;
    if (every > 0) scene.output.every = every;
    fs::remove_all(dir);
    fs::create_directories(dir);
    const Model model = compile_model(scene, load_field(scene, StreamMode::Off, true),
                                      cached_added_mass);
    State state = initial_state(model, scene);

    OutputSpec csv_spec = scene.output;
    csv_spec.csv = true, csv_spec.pvd = false;
    for (const DccFormat& d : kDccFormats) csv_spec.*d.enabled = false;
    for (const char* d : {"csv", "bodies", "shapes"}) fs::create_directories(fs::path(dir) / d);
    ResultWriter csv((fs::path(dir) / "csv").string(), model, csv_spec);
    // one writer per cache for DCC tools, each in a folder of its own
    std::vector<std::unique_ptr<ResultWriter>> caches;
    for (const DccFormat& d : kDccFormats) {
      OutputSpec spec = csv_spec;
      spec.csv = false;
      spec.*d.enabled = true;
      fs::create_directories(fs::path(dir) / d.format);
      caches.push_back(
          std::make_unique<ResultWriter>((fs::path(dir) / d.format).string(), model, spec));
    }
    std::vector<Clock> c_caches(caches.size());
    BodiesFrames bodies(model, comp);
    std::vector<TriangleMesh> surfaces;
    for (const BodyType& t : model.types)
      surfaces.push_back(series_surface(t, shape_faces_for(model.body_count)));
    ShapesFrames shapes(std::move(surfaces), comp);

    Clock c_csv, c_bodies, c_shapes, c_all;
    size_t frames = 0;
    RunOptions opt;
    opt.every = scene.output.every;
    opt.threads = threads;
    opt.on_output = [&](const State& s) {
      char name[64];
      c_all.time([&] {
        c_csv.time([&] { csv.write_frame(s); });
        std::snprintf(name, sizeof name, "bodies/bodies_%06zu.vtp", frames);
        c_bodies.time([&] { bodies.write(s, (fs::path(dir) / name).string()); });
        std::snprintf(name, sizeof name, "shapes/shapes_%06zu.vtp", frames);
        c_shapes.time([&] { shapes.write(s, (fs::path(dir) / name).string()); });
        for (size_t k = 0; k < caches.size(); ++k)
          c_caches[k].time([&] { caches[k]->write_frame(s); });
      });
      ++frames;
    };
    Clock total;
    RunStats stats;
    total.time([&] { stats = simulate(model, &state, opt); });
    c_csv.time([&] { csv.finish(state, stats, nlohmann::json::object()); });
    for (size_t k = 0; k < caches.size(); ++k)
      c_caches[k].time([&] { caches[k]->finish(state, stats, nlohmann::json::object()); });
    const double sim_cpu = total.cpu - c_all.cpu, sim_wall = total.wall - c_all.wall;

    // pass 2: what lrigid run pays on its own thread with the default formats (csv + pvd, the
    // .vtp frames written on the frames' thread, io/vtp_frames.h FramesThread)
    State state2 = initial_state(model, scene);
    OutputSpec run_spec = scene.output;
    run_spec.csv = true, run_spec.pvd = true;
    for (const DccFormat& d : kDccFormats) run_spec.*d.enabled = false;
    fs::create_directories(fs::path(dir) / "run");
    Clock c_run, total2;
    {
      ResultWriter run((fs::path(dir) / "run").string(), model, run_spec);
      RunOptions opt2 = opt;
      opt2.on_output = [&](const State& s) { c_run.time([&] { run.write_frame(s); }); };
      RunStats stats2;
      total2.time([&] { stats2 = simulate(model, &state2, opt2); });
      c_run.time([&] { run.finish(state2, stats2, nlohmann::json::object()); });
    }
    const double sim2_wall = total2.wall - c_run.wall;

    const double nb = double(model.body_count), nf = double(frames);
    const uint64_t steps_between = output_stride(model, scene.output.every);
    nlohmann::json j;
    j["scene"] = scene_path;
    j["bodies"] = model.body_count;
    j["frames"] = frames;
    j["steps_between_frames"] = steps_between;
    j["threads"] = threads;
    j["compression"] = compression;
    j["simulation"] = {{"cpu_ms_per_frame", 1e3 * sim_cpu / nf},
                       {"wall_ms_per_frame", 1e3 * sim_wall / nf}};
    struct Row {
      const char* name;
      const Clock& c;
      uintmax_t bytes;
    };
    std::vector<Row> rows = {
        {"csv", c_csv, bytes_under(fs::path(dir) / "csv" / "trajectories.csv")},
        {"bodies", c_bodies, bytes_under(fs::path(dir) / "bodies")},
        {"shapes", c_shapes, bytes_under(fs::path(dir) / "shapes")}};
    for (size_t k = 0; k < caches.size(); ++k)
      rows.push_back({kDccFormats[k].format, c_caches[k],
                      bytes_under(fs::path(dir) / kDccFormats[k].format / kDccFormats[k].file)});
    for (const Row& r : rows)
      j["writers"][r.name] = {{"cpu_ms_per_frame", 1e3 * r.c.cpu / nf},
                              {"wall_ms_per_frame", 1e3 * r.c.wall / nf},
                              {"cpu_us_per_body_frame", 1e6 * r.c.cpu / (nf * nb)},
                              {"bytes_per_frame", double(r.bytes) / nf}};
    const double pvd_cpu = c_bodies.cpu + c_shapes.cpu, pvd_wall = c_bodies.wall + c_shapes.wall;
    j["default_outputs"] = {{"formats", "csv + pvd (bodies + shapes)"},
                            {"cpu_ms_per_frame", 1e3 * (c_csv.cpu + pvd_cpu) / nf},
                            {"wall_ms_per_frame", 1e3 * (c_csv.wall + pvd_wall) / nf},
                            {"ratio_to_simulation_cpu", (c_csv.cpu + pvd_cpu) / sim_cpu}};
    j["run_default_outputs"] = {{"wall_ms_per_frame_on_the_run", 1e3 * c_run.wall / nf},
                                {"cpu_ms_per_frame_on_the_run", 1e3 * c_run.cpu / nf},
                                {"simulation_wall_ms_per_frame", 1e3 * sim2_wall / nf},
                                {"ratio_to_simulation_wall", c_run.wall / sim2_wall}};
    if (as_json) {
      std::printf("%s\n", j.dump(2).c_str());
    } else {
      std::printf("scene %s: %zu bodies, %zu frames, %llu steps between frames, %d thread(s), "
                  "vtp compression %s\n",
                  scene_path.c_str(), model.body_count, frames,
                  (unsigned long long)steps_between, threads, compression.c_str());
      std::printf("%-22s %12s %12s %16s %14s\n", "", "CPU ms/frame", "wall ms/frame",
                  "CPU us/body/frame", "kB/frame");
      std::printf("%-22s %12.3f %12.3f %16s %14s\n", "simulation (between)", 1e3 * sim_cpu / nf,
                  1e3 * sim_wall / nf, "", "");
      for (const Row& r : rows)
        std::printf("%-22s %12.3f %12.3f %16.3f %14.1f\n", r.name, 1e3 * r.c.cpu / nf,
                    1e3 * r.c.wall / nf, 1e6 * r.c.cpu / (nf * nb), double(r.bytes) / nf / 1e3);
      std::printf("%-22s %12.3f %12.3f   (%.2f x the simulation, CPU)\n", "csv + pvd (default)",
                  1e3 * (c_csv.cpu + pvd_cpu) / nf, 1e3 * (c_csv.wall + pvd_wall) / nf,
                  (c_csv.cpu + pvd_cpu) / sim_cpu);
      std::printf("lrigid run's writer, csv + pvd, .vtp frames on their own thread: %.3f ms/frame "
                  "wall (%.3f CPU) on the run's thread, simulation %.3f ms/frame wall: %.2f x\n",
                  1e3 * c_run.wall / nf, 1e3 * c_run.cpu / nf, 1e3 * sim2_wall / nf,
                  c_run.wall / sim2_wall);
    }
    fs::remove_all(dir);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "writers_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
