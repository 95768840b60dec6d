// Reads the measured error-versus-cost table (docs/accuracy/tolerance_table.json, written by
// bench/accuracy/make_report.py) that lrigid run --tolerance chooses from.
//   { "kinds": { "<kind>": [ {"integrator": "splitting", "dt": 0.001, "error": 0.004,
//                             "cost": 0.0021}, ... ] }, ... }
// dt in s, error relative, cost in CPU seconds per body per simulated second.
#pragma once
#include <string>

#include "model/tolerance.h"

namespace lrigid {

// Throws lrigid::Error (ExitCode::BadInput) naming the file and key for a missing file,
// malformed JSON or a bad entry.
ToleranceTable read_tolerance_table(const std::string& path);

// Where --tolerance looks when no table is given: $LRIGID_TOLERANCE_TABLE, else
// tolerance_table.json next to the running binary, else the source tree's
// docs/accuracy/tolerance_table.json. Returns the first that exists (or the last candidate).
std::string default_tolerance_table_path();

}  // namespace lrigid
