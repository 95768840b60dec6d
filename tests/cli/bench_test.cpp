// lrigid bench: on the uniform-field scene it measures every requested point, counts
// the body-steps it timed (bodies x steps) and reports the State bytes per body; bad arguments
// are usage errors.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "support/shell.h"

namespace {

const std::string kLrigid = std::string(LRIGID_BINARY_DIR) + "/bin/lrigid";
const std::string kScene = std::string(LRIGID_SOURCE_DIR) + "/scenes/uniform_box.json";

int run(const std::string& args) {
  const int rc = std::system((kLrigid + " bench " + args + " > /dev/null 2>&1").c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

TEST(CliBench, MeasuresEveryPointAndCountsBodySteps) {
  const auto out = std::filesystem::temp_directory_path() / "lrigid_bench_test.json";
  std::filesystem::remove(out);
  ASSERT_EQ(run(kScene + " --n 40,80 --integrators euler,splitting --threads 1,2 --body-steps 1 "
                "--min-steps 5 --warmup 1 --json " + out.string()),
            0);
  std::ifstream f(out);
  const nlohmann::json j = nlohmann::json::parse(f);
  ASSERT_EQ(j["runs"].size(), 8u);
  for (const auto& r : j["runs"]) {
    const long long n = r["n"];
    // every body steps 5 times unless it landed or left
    EXPECT_LE(r["body_steps"].get<long long>(), 5 * n);
    EXPECT_GT(r["body_steps"].get<long long>(), 0);
    EXPECT_GT(r["body_steps_per_s"].get<double>(), 0.0);
    EXPECT_GE(r["state_bytes_per_body"].get<double>(), 4.0 * 24 + 32);
  }
  std::filesystem::remove(out);
}

// what lrigid with `args` prints, run from `cwd`
std::string output(const std::string& cwd, const std::string& args) {
  std::string r;
  lrigid::test::sh("cd '" + cwd + "' && " + kLrigid + " " + args, &r);
  return r;
}

// by default the scene's own effects, said before the numbers with the columns, the
// same effects lrigid explain says the scene simulates
TEST(CliBench, UsesTheScenesOwnEffectsAndSaysWhichAndWhatTheColumnsAre) {
  const std::string tmp = std::filesystem::temp_directory_path().string();
  const std::string b = output(tmp, "bench " + kScene +
                                        " --n 20 --integrators euler --threads 1 --body-steps 1 "
                                        "--min-steps 1 --warmup 0");
  EXPECT_NE(b.find("effects: the scene's (\"auto\": chosen per body type)"), std::string::npos)
      << b;
  const std::string e = output(tmp, "explain " + kScene);
  // "simulated: ..." of each body type, in order, against bench's "  name: ..." lines
  size_t at = 0;
  for (const char* name : {"paper_card", "polystyrene_bead"}) {
    const size_t s = e.find("simulated: ", at);
    ASSERT_NE(s, std::string::npos) << e;
    const std::string list = e.substr(s + 11, e.find('\n', s) - s - 11);
    at = s + 1;
    EXPECT_NE(b.find(std::string("  ") + name + ": " + list + "\n"), std::string::npos)
        << name << ": " << list << "\n" << b;
  }
  EXPECT_NE(b.find("B/body (bytes of State per body)"), std::string::npos) << b;
  EXPECT_NE(b.find("scalar% (% of the body-steps of batched body types handed to the scalar "
                   "step"),
            std::string::npos) << b;
  EXPECT_NE(output(tmp, "bench " + kScene + " --effects all --n 20 --integrators euler "
                        "--threads 1 --body-steps 1 --min-steps 1 --warmup 0")
                .find("effects: all, for every body type (--effects all)"),
            std::string::npos);
}

// the default scene is the repository's, whatever the working directory
TEST(CliBench, DefaultSceneResolvesFromTheRepositoryNotTheWorkingDirectory) {
  const std::string tmp = std::filesystem::temp_directory_path().string();
  const std::string b = output(tmp, "bench --n 10 --integrators euler --threads 1 "
                                    "--body-steps 1 --min-steps 1 --warmup 0");
  // it runs (the wind grid exists) or fails on the grid, but it found the scene file
  EXPECT_NE(b.find(std::string(LRIGID_SOURCE_DIR) + "/scenes/leaves_wind.json"),
            std::string::npos) << b;
  EXPECT_EQ(b.find("scenes/leaves_wind.json: file not found"), std::string::npos) << b;
}

TEST(CliBench, BadArgumentsAreUsageErrors) {
  EXPECT_EQ(run(kScene + " --integrators leapfrog"), 2);
  EXPECT_EQ(run(kScene + " --effects wind_chill"), 2);
  // counts beyond the scene's limit of 1e8 bodies overflowed the body count: std::bad_alloc,
  // exit 1; NaN passed CLI11's range checks and was taken as a count of body-steps
  EXPECT_EQ(run(kScene + " --n 99999999999"), 2);
  EXPECT_EQ(run(kScene + " --n 0"), 2);
  EXPECT_EQ(run(kScene + " --body-steps nan"), 2);
  EXPECT_EQ(run(kScene + " --body-steps 1e300"), 2);
}

TEST(CliBench, MoreBodiesThanMemoryIsAResourceError) {
  // 3e7 bodies (about 6 GiB) under an address-space limit of 4 GiB: exit 5 before anything is
  // allocated, as lrigid run does (bench allocated until std::bad_alloc, exit 1)
  EXPECT_EQ(std::system(("ulimit -v 4194304; " + kLrigid + " bench " + kScene +
                         " --n 30000000 --integrators euler --threads 1 > /dev/null 2>&1; "
                         "test $? -eq 5")
                            .c_str()),
            0);
}

}  // namespace
