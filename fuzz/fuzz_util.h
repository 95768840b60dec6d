// Helpers shared by the libFuzzer targets: a private scratch directory and whole-file writes.
#pragma once
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

namespace lrigid::fuzz {

// /tmp/lrigid_fuzz_<pid>, created once, removed at exit
inline const std::string& scratch() {
  static const std::string dir = [] {
    std::string d = "/tmp/lrigid_fuzz_" + std::to_string(::getpid());
    std::filesystem::create_directories(d);
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all("/tmp/lrigid_fuzz_" + std::to_string(::getpid()), ec);
    });
    return d;
  }();
  return dir;
}

inline std::string write_scratch(const std::string& name, const uint8_t* data, size_t size) {
  const std::string path = scratch() + "/" + name;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) std::abort();
  if (size > 0 && std::fwrite(data, 1, size, f) != size) std::abort();
  std::fclose(f);
  return path;
}

}  // namespace lrigid::fuzz
