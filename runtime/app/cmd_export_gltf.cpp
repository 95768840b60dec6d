// lrigid export-gltf RESULTS_DIR [-o out.glb] [--faces N] [--instanced]
// Bakes a finished run (trajectories.csv + summary.json) into a glTF 2.0 binary for DCC tools.
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "commands.h"
#include "io/gltf_writer.h"
#include "io/result_writer.h"
#include "util/error.h"

namespace lrigid::app {

namespace {

struct ExportArgs {
  std::string dir;
  std::string out;
  int faces = 320;
  bool instanced = false;
  bool quiet = false;
};

void export_gltf(const ExportArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  const Results r = read_results(a.dir, a.faces);
  const std::string out =
      a.out.empty() ? (std::filesystem::path(a.dir) /
                       (a.instanced ? "animation_instanced.glb" : "animation.glb"))
                          .string()
                    : a.out;
  write_gltf(out, r.frames, a.instanced ? GltfLayout::Instanced : GltfLayout::Animated);
  if (!a.quiet) {
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(stderr, "lrigid: %zu bodies x %zu frames -> %s (%.1f MB) in %.2f s\n",
                 r.frames.bodies(), r.frames.times.size(), out.c_str(),
                 double(std::filesystem::file_size(out)) / 1e6, s);
  }
}

}  // namespace

void add_export_gltf_command(CLI::App& app) {
  auto args = std::make_shared<ExportArgs>();
  auto* cmd = app.add_subcommand(
      "export-gltf", "Bake a run's trajectories into a glTF 2.0 binary (.glb) for Blender/Houdini");
  cmd->add_option("results", args->dir, "Results directory of lrigid run")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("-o,--output", args->out, "Output .glb (default RESULTS/animation.glb, with --instanced "
                  "RESULTS/animation_instanced.glb)");
  cmd->add_option("--faces", args->faces, "Triangles per body type mesh, about (default 320)")
      ->check(CLI::Range(1, 1000000));
  cmd->add_flag("--instanced", args->instanced,
                "One node per output frame with the bodies as EXT_mesh_gpu_instancing instances "
                "(docs/outputs.md)");
  cmd->add_flag("--quiet", args->quiet, "Print nothing but errors");
  cmd->callback([args] { export_gltf(*args); });
}

}  // namespace lrigid::app
