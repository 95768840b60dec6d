// lrigid added-mass: placeholder until the body-types work lands (issue 5).
#include "commands.h"
#include "util/error.h"

namespace lrigid::app {
void add_added_mass_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("added-mass", "Mass properties and Kirchhoff tensor of a body");
  cmd->callback([] { throw Error(ExitCode::Runtime, "added-mass: not implemented yet"); });
}
}  // namespace lrigid::app
