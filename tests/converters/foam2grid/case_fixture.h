// Helpers of the foam2grid tests: OpenFOAM cases copied into the build tree and run there once
// (under a file lock, since ctest runs test processes in parallel), and running commands.
#pragma once
#include <string>

namespace foam2grid_test {

/// Runs a shell command; returns its exit code, stdout+stderr in *output when given.
int run(const std::string& command, std::string* output = nullptr);

/// build/bin/foam2grid
std::string foam2grid_bin();

/// A run copy of foam_cases/<name> in the build tree (Allrun done once, redone when the source
/// case changes). Extra setup (e.g. "decomposePar") runs after Allrun when given.
std::string prepared_case(const std::string& name, const std::string& variant = "",
                          const std::string& extra_setup = "");

/// A fresh, empty directory for one test in the build tree.
std::string work_dir(const std::string& test_name);

/// Quotes a string for the shell.
std::string quote(const std::string& s);

}  // namespace foam2grid_test
