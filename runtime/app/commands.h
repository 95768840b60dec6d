// Sub-commands of the lrigid program; each adds itself to the CLI and sets its callback.
#pragma once
#include <CLI/CLI.hpp>

namespace lrigid::app {

void add_run_command(CLI::App& app);         // cmd_run.cpp
void add_added_mass_command(CLI::App& app);  // cmd_added_mass.cpp
void add_explain_command(CLI::App& app);     // cmd_explain.cpp
void add_info_command(CLI::App& app);        // cmd_info.cpp
void add_export_gltf_command(CLI::App& app);  // cmd_export_gltf.cpp
void add_render_command(CLI::App& app);       // cmd_render.cpp
void add_bench_command(CLI::App& app);        // cmd_bench.cpp
void add_view_command(CLI::App& app);         // cmd_view.cpp

}  // namespace lrigid::app
