// lrigid: rigid bodies in turbulent flow. See README.md and docs/cli.md.
#include <iostream>
#include <sstream>

#include "commands.h"
#include "signals.h"
#include "util/cli_suggest.h"
#include "util/error.h"

int main(int argc, char** argv) {
  lrigid::app::install_signal_cleanup();  // interrupted runs leave no temporary files
  CLI::App app{"lrigid: rigid bodies immersed in turbulent flow (Langevin Rigid). Units are SI."};
  app.set_version_flag("--version", std::string("lrigid ") + LRIGID_VERSION);
  app.require_subcommand(1);
  lrigid::app::add_run_command(app);
  lrigid::app::add_added_mass_command(app);
  lrigid::app::add_explain_command(app);
  lrigid::app::add_info_command(app);
  lrigid::app::add_export_gltf_command(app);
  lrigid::app::add_render_command(app);
  lrigid::app::add_bench_command(app);
  lrigid::app::add_view_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    if (dynamic_cast<const CLI::ExtrasError*>(&e)) {
      std::istringstream hints(lrigid::unknown_flag_hints(app, app.remaining(true)));
      for (std::string line; std::getline(hints, line);) std::cerr << "lrigid: " << line << "\n";
    }
    return static_cast<int>(lrigid::ExitCode::Usage);
  } catch (const lrigid::Error& e) {
    std::cerr << "lrigid: error: " << e.what() << "\n";
    return static_cast<int>(e.code());
  } catch (const std::exception& e) {
    std::cerr << "lrigid: error: " << e.what() << "\n";
    return static_cast<int>(lrigid::ExitCode::Runtime);
  }
  return 0;
}
