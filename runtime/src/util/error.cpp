#include "util/error.h"

namespace lrigid {

std::string where(const std::string& file, const std::string& key, const std::string& message) {
  std::string s;
  if (!file.empty()) s += file + ": ";
  if (!key.empty()) s += key + ": ";
  return s + message;
}

void fail_input(const std::string& file, const std::string& key, const std::string& message) {
  throw Error(ExitCode::BadInput, where(file, key, message));
}

}  // namespace lrigid
