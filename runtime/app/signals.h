// SIGINT, SIGTERM, SIGHUP: remove the run's temporary output files, then die of the signal.
#pragma once

namespace lrigid::app {

// Installs the handlers. Temporary files are those named "<name>.tmp<pid>" (result_writer,
// atomic_file); the handler finds the output directory from the process's open files.
void install_signal_cleanup();

}  // namespace lrigid::app
