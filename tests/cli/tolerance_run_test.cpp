// lrigid run --tolerance end to end on the shipped table: the binary finds
// docs/accuracy/tolerance_table.json by itself (no --tolerance-table), says what it chose, and
// the run's summary.json records the integrator and dt that the table's cheapest entry
// reaching the tolerance has, worked out here from the table independently of lrigid.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const std::string kLrigid = std::string(LRIGID_BINARY_DIR) + "/bin/lrigid";
const std::string kTable = std::string(LRIGID_SOURCE_DIR) + "/docs/accuracy/tolerance_table.json";

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// a uniform flow of air: the table's "uniform-air" kind
const char* kScene = R"({
  "fluid": { "density": 1.204, "kinematic_viscosity": 1.5e-5,
             "uniform": { "U": [1.0, 0.0, 0.0], "k": 0.1, "epsilon": 0.05 } },
  "gravity": [0, 0, -9.81],
  "effects": "auto",
  "integrator": { "scheme": "euler", "dt": 0.01 },
  "duration": 0.02,
  "seed": 3,
  "bodies": [ { "name": "bead", "shape": { "type": "sphere", "radius": 0.003 },
                "density": 30, "count": 2, "position": [0, 0, 1] } ],
  "output": { "dir": "out", "every": 0.01, "formats": ["csv"] }
})";

struct RunResult {
  int code;
  std::string err;
};

RunResult run_in(const fs::path& dir, const std::string& tolerance) {
  const std::string cmd = "cd '" + dir.string() + "' && env -u LRIGID_TOLERANCE_TABLE '" +
                          kLrigid + "' run scene.json --tolerance " + tolerance +
                          " 2> stderr.txt";
  const int st = std::system(cmd.c_str());
  return {WIFEXITED(st) ? WEXITSTATUS(st) : -1, slurp(dir / "stderr.txt")};
}

class ToleranceRun : public ::testing::Test {
 protected:
  void SetUp() override {
    char tmpl[] = "/tmp/lrigid_tol_XXXXXX";
    ASSERT_NE(mkdtemp(tmpl), nullptr);
    dir_ = tmpl;
    std::ofstream(dir_ / "scene.json") << kScene;
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path dir_;
};

TEST_F(ToleranceRun, ChoosesTheCheapestShippedEntryThatReachesIt) {
  const json table = json::parse(slurp(kTable));
  const json& entries = table.at("kinds").at("uniform-air");
  ASSERT_GT(entries.size(), 2u);
  // a tolerance between the best and the worst measured error, so that the choice matters
  double lo = 1e300, hi = 0;
  for (const json& e : entries) {
    lo = std::min(lo, e.at("error").get<double>());
    hi = std::max(hi, e.at("error").get<double>());
  }
  for (const double tol : {2 * lo, std::sqrt(lo * hi), hi}) {
    SCOPED_TRACE("tolerance " + std::to_string(tol));
    const json* best = nullptr;
    for (const json& e : entries)
      if (e.at("error").get<double>() <= tol &&
          (!best || e.at("cost").get<double>() < best->at("cost").get<double>()))
        best = &e;
    ASSERT_NE(best, nullptr);
    std::ostringstream t;
    t.precision(17);
    t << tol;
    const RunResult r = run_in(dir_, t.str());
    ASSERT_EQ(r.code, 0) << r.err;
    // it says which table it used, and that table is the shipped one (or a copy of it)
    const auto from = r.err.find("; from ");
    ASSERT_NE(from, std::string::npos) << r.err;
    std::string used = r.err.substr(from + 7);
    used = used.substr(0, used.find('\n'));
    EXPECT_EQ(slurp(used), slurp(kTable)) << used;
    const json s = json::parse(slurp(dir_ / "out" / "summary.json"));
    EXPECT_EQ(s.at("integrator"), best->at("integrator")) << r.err;
    EXPECT_EQ(s.at("dt").get<double>(), best->at("dt").get<double>()) << r.err;
  }
}

TEST_F(ToleranceRun, ATighterToleranceThanMeasuredIsRefused) {
  const RunResult r = run_in(dir_, "1e-9");
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("tolerance_table.json"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "out" / "summary.json"));
  // the flag's value is named first (not the table's path, which would look broken), with
  // the tolerances that are reachable for this kind of scene, worked out here from the table
  EXPECT_EQ(r.err.rfind("lrigid: error: --tolerance 1e-09 is not reachable for 'uniform-air' "
                        "scenes",
                        0),
            0u)
      << r.err;
  const json table = json::parse(slurp(kTable));
  double smallest = 1e300;
  for (const json& e : table.at("kinds").at("uniform-air"))
    smallest = std::min(smallest, e.at("error").get<double>());
  char reachable[80];
  std::snprintf(reachable, sizeof reachable, "the reachable tolerances are %.3g and above",
                smallest);
  EXPECT_NE(r.err.find(reachable), std::string::npos) << r.err;
  // the suggested value is reachable: a run with it goes through
  const auto at = r.err.find("Pass --tolerance ");
  ASSERT_NE(at, std::string::npos) << r.err;
  const std::string suggested = r.err.substr(at + 17, r.err.find(' ', at + 17) - at - 17);
  EXPECT_GE(std::stod(suggested), smallest);
  EXPECT_NE(r.err.find("or set integrator.scheme and integrator.dt in the scene yourself"),
            std::string::npos);
  const RunResult ok = run_in(dir_, suggested);
  EXPECT_EQ(ok.code, 0) << ok.err;
}

}  // namespace
