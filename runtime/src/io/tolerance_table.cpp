#include "io/tolerance_table.h"

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "io/source_dir.h"
#include "model/scene.h"
#include "util/error.h"

namespace lrigid {

namespace {

double positive(const nlohmann::json& e, const std::string& file, const std::string& key,
                const char* name) {
  const std::string k = key + "." + name;
  if (!e.contains(name) || !e[name].is_number()) fail_input(file, k, "missing or not a number");
  const double v = e[name].get<double>();
  if (!std::isfinite(v) || v < 0 || (v == 0 && std::string(name) == "dt"))
    fail_input(file, k, "must be a finite positive number, got " + e[name].dump());
  return v;
}

}  // namespace

ToleranceTable read_tolerance_table(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail_input(path, "", "cannot read the tolerance table (run bench/accuracy/run_study.sh "
                                "or pass --tolerance-table FILE)");
  std::stringstream ss;
  ss << in.rdbuf();
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(ss.str());
  } catch (const nlohmann::json::parse_error& e) {
    fail_input(path, "", std::string("malformed JSON: ") + e.what());
  }
  if (!j.is_object() || !j.contains("kinds") || !j["kinds"].is_object())
    fail_input(path, "kinds", "missing or not an object");
  ToleranceTable t;
  t.source = path;
  for (const auto& [kind, list] : j["kinds"].items()) {
    const std::string key = "kinds." + kind;
    if (!list.is_array()) fail_input(path, key, "not an array");
    auto& out = t.kinds[kind];
    for (size_t i = 0; i < list.size(); ++i) {
      const auto& e = list[i];
      const std::string k = key + "[" + std::to_string(i) + "]";
      if (!e.is_object()) fail_input(path, k, "not an object");
      ToleranceEntry x;
      if (!e.contains("integrator") || !e["integrator"].is_string())
        fail_input(path, k + ".integrator", "missing or not a string");
      x.integrator = e["integrator"].get<std::string>();
      Integrator scheme;
      if (!integrator_from_name(x.integrator, &scheme))
        fail_input(path, k + ".integrator", "unknown scheme '" + x.integrator + "'");
      x.dt = positive(e, path, k, "dt");
      x.error = positive(e, path, k, "error");
      x.cost = positive(e, path, k, "cost");
      out.push_back(x);
    }
  }
  return t;
}

std::string default_tolerance_table_path() {
  std::vector<std::string> candidates;
  if (const char* env = std::getenv("LRIGID_TOLERANCE_TABLE"); env && *env) return env;
  char exe[4096];
  const ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (n > 0) {
    std::string dir(exe, size_t(n));
    dir = dir.substr(0, dir.find_last_of('/'));
    candidates.push_back(dir + "/tolerance_table.json");
  }
if (const std::string src = source_dir(); !src.empty())
    candidates.push_back(src + "/docs/accuracy/tolerance_table.json");
  for (const auto& c : candidates)
    if (std::ifstream(c).good()) return c;
  return candidates.empty() ? "tolerance_table.json" : candidates.back();
}

}  // namespace lrigid
