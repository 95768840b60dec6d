// SIGINT, SIGTERM, SIGHUP: remove the run's temporary output files, then die of the signal.
#pragma once

namespace lrigid::app {

// Installs the handlers. Temporary files are those named "<name>.tmp<pid>" (result_writer,
// atomic_file); the handler finds the output directory from the process's open files.
void install_signal_cleanup();

// From now on the handlers leave the temporaries alone: a checkpoint refers to them
// (lrigid run --resume).
void keep_temporaries_on_signal();

}  // namespace lrigid::app
