#include "case_fixture.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace foam2grid_test {

std::string quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'') {
      out += "'\\''";
    } else {
      out += c;
    }
  }
  return out + "'";
}

int run(const std::string& command, std::string* output) {
  const std::string cmd = "(" + command + ") 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  if (p == nullptr) throw std::runtime_error("cannot run: " + command);
  std::string out;
  std::array<char, 4096> buf;
  std::size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) out.append(buf.data(), n);
  const int status = pclose(p);
  if (output) *output = out;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

std::string foam2grid_bin() { return std::string(LRIGID_BINARY_DIR) + "/bin/foam2grid"; }

std::string work_dir(const std::string& test_name) {
  const fs::path d = fs::path(LRIGID_BINARY_DIR) / "tests/converters/work" / test_name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d.string();
}

std::string prepared_case(const std::string& name, const std::string& variant,
                          const std::string& extra_setup) {
  const fs::path src = fs::path(LRIGID_SOURCE_DIR) / "foam_cases" / name;
  const fs::path root = fs::path(LRIGID_BINARY_DIR) / "tests/converters/cases";
  fs::create_directories(root);
  const fs::path dst = root / (name + variant);
  // one process prepares, the others wait
  const std::string lock_path = (root / ".lock").string();
  const int fd = open(lock_path.c_str(), O_CREAT | O_RDWR, 0644);
  if (fd < 0 || flock(fd, LOCK_EX) != 0) throw std::runtime_error("cannot lock " + lock_path);
  std::string fingerprint;
  run("cd " + quote(src.string()) + " && find . -type f -printf '%T@ %s %p\\n' | sort | md5sum",
      &fingerprint);
  fingerprint += extra_setup;
  const fs::path stamp = dst / ".prepared";
  std::string old;
  if (fs::exists(stamp)) {
    std::ifstream in(stamp);
    std::stringstream ss;
    ss << in.rdbuf();
    old = ss.str();
  }
  if (old != fingerprint) {
    fs::remove_all(dst);
    std::string log;
    const std::string cmd =
        "cp -r " + quote(src.string()) + " " + quote(dst.string()) + " && cd " +
        quote(dst.string()) +
        " && FOAM_CASES_DIR=" + quote((fs::path(LRIGID_SOURCE_DIR) / "foam_cases").string()) +
        " ./Allrun > log.Allrun 2>&1" +
        (extra_setup.empty() ? ""
                             : " && export WM_PROJECT_DIR=/usr/share/openfoam && " + extra_setup +
                                   " > log.extra 2>&1");
    const int rc = run(cmd, &log);
    if (rc != 0) {
      flock(fd, LOCK_UN);
      close(fd);
      throw std::runtime_error("preparing " + dst.string() + " failed (" + std::to_string(rc) +
                               "): " + log + " (see log.Allrun there)");
    }
    std::ofstream(stamp) << fingerprint;
  }
  flock(fd, LOCK_UN);
  close(fd);
  return dst.string();
}

}  // namespace foam2grid_test
