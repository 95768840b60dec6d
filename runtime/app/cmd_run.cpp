// lrigid run: placeholder until the dynamics work lands (issue 6).
#include "commands.h"
#include "util/error.h"

namespace lrigid::app {
void add_run_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("run", "Integrate the bodies of a scene");
  cmd->callback([] { throw Error(ExitCode::Runtime, "run: not implemented yet"); });
}
}  // namespace lrigid::app
