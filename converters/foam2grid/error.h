// Errors of foam2grid: each carries the exit code the program returns and a message that names
// the file, flag or key and the value that is wrong.
#pragma once
#include <stdexcept>
#include <string>

namespace foam2grid {

/// Exit codes of foam2grid (documented in docs/converter.md).
enum class Exit : int { kOk = 0, kUsage = 2, kBadInput = 3, kOutput = 4, kTooLarge = 5 };

class Error : public std::runtime_error {
 public:
  Error(Exit code, const std::string& message) : std::runtime_error(message), code_(code) {}
  Exit code() const { return code_; }

 private:
  Exit code_;
};

/// Bad input: missing case, mesh, field or time, unreadable file, NaN, bounds outside the mesh.
[[noreturn]] inline void fail_input(const std::string& message) {
  throw Error(Exit::kBadInput, message);
}

/// Bad command line (flag values out of range, inconsistent flags).
[[noreturn]] inline void fail_usage(const std::string& message) {
  throw Error(Exit::kUsage, message);
}

}  // namespace foam2grid
