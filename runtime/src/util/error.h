// Errors that reach the user: each names the file, the key and the value that is wrong.
// Exit codes (documented in docs/cli.md): 0 ok, 1 runtime failure, 2 usage, 3 bad input file,
// 4 output cannot be written, 5 resource limit (memory).
#pragma once
#include <stdexcept>
#include <string>

namespace lrigid {

enum class ExitCode : int {
  Ok = 0,
  Runtime = 1,
  Usage = 2,
  BadInput = 3,
  Output = 4,
  Resource = 5
};

class Error : public std::runtime_error {
 public:
  Error(ExitCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
  ExitCode code() const { return code_; }

 private:
  ExitCode code_;
};

// "file: key: message" (parts left empty are skipped)
std::string where(const std::string& file, const std::string& key, const std::string& message);

[[noreturn]] void fail_input(const std::string& file, const std::string& key,
                             const std::string& message);

}  // namespace lrigid
