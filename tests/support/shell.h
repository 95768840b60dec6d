// For tests that run a program (build/bin/lrigid) and look at what it prints: a shell
// command's exit status and its stdout + stderr. No dependencies (shell_png.h adds PNGs).
#pragma once
#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace lrigid::test {

// runs a shell command; returns its exit status (-1 when it did not exit) and stdout+stderr
inline int sh(const std::string& cmd, std::string* out = nullptr) {
  std::string text;
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return -1;
  char buf[512];
  while (fgets(buf, sizeof buf, p)) text += buf;
  const int st = pclose(p);
  if (out) *out = text;
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

}  // namespace lrigid::test
