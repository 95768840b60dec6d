// lrigid bench (issue 11): on the uniform-field scene it measures every requested point, counts
// the body-steps it timed (bodies x steps) and reports the State bytes per body; bad arguments
// are usage errors.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

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

TEST(CliBench, BadArgumentsAreUsageErrors) {
  EXPECT_EQ(run(kScene + " --integrators leapfrog"), 2);
  EXPECT_EQ(run(kScene + " --effects wind_chill"), 2);
}

}  // namespace
