// A hint for mistyped command-line flags (lrigid, foam2grid): CLI11 says "The following
// arguments were not expected: --sed"; this names the nearest flag the (sub)command knows.
#pragma once
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "util/suggest.h"

namespace lrigid {

// For each unexpected argument starting with '-', one line
// `unknown flag "--sed" (did you mean "--seed"?)`; "" when there is none.
inline std::string unknown_flag_hints(const CLI::App& app, const std::vector<std::string>& extras) {
  // the flags of the subcommand being parsed (the deepest one), else of the app
  const CLI::App* at = &app;
  for (;;) {
    const auto subs = at->get_subcommands();
    if (subs.empty()) break;
    at = subs.front();
  }
  std::vector<std::string> flags;
  for (const CLI::App* a : {at, &app}) {
    for (const CLI::Option* o : a->get_options()) {
      for (const std::string& l : o->get_lnames()) flags.push_back("--" + l);
      for (const std::string& s : o->get_snames()) flags.push_back("-" + s);
    }
    if (a == &app) break;
  }
  std::string out;
  for (std::string e : extras) {
    if (e.size() < 2 || e[0] != '-') continue;
    if (const auto eq = e.find('='); eq != std::string::npos) e.resize(eq);
    out += "unknown flag \"" + e + "\"" + did_you_mean(e, flags) + "\n";
  }
  return out;
}

}  // namespace lrigid
