// lrigid run --tolerance: the choice from a small measured table, scene kinds, table errors.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "io/tolerance_table.h"
#include "model/tolerance.h"
#include "util/error.h"

namespace lrigid {
namespace {

ToleranceTable small_table() {
  ToleranceTable t;
  t.source = "<test>";
  t.kinds["uniform-air"] = {
      {"euler", 1e-3, 0.02, 0.002},   {"euler", 1e-4, 0.002, 0.02},
      {"splitting", 2e-3, 0.008, 0.0015}, {"splitting", 5e-4, 0.002, 0.006},
      {"rk4", 1e-2, 0.05, 0.0009},    {"rk4", 2e-3, 0.0003, 0.0045},
  };
  t.kinds["grid-water"] = {{"splitting", 1e-3, 0.01, 0.003}};
  return t;
}

TEST(Tolerance, PicksTheCheapestEntryThatReachesTheTolerance) {
  const ToleranceTable t = small_table();
  // 1 %: splitting at 2 ms (0.8 %, cost 0.0015) beats euler 0.1 ms and the rk4 at 2 ms
  ToleranceChoice c = choose_for_tolerance(t, "uniform-air", 0.01);
  EXPECT_EQ(c.entry.integrator, "splitting");
  EXPECT_DOUBLE_EQ(c.entry.dt, 2e-3);
  EXPECT_EQ(c.kind, "uniform-air");
  EXPECT_NE(c.explanation.find("splitting"), std::string::npos);
  // 0.1 %: only rk4 at 2 ms
  c = choose_for_tolerance(t, "uniform-air", 1e-3);
  EXPECT_EQ(c.entry.integrator, "rk4");
  EXPECT_DOUBLE_EQ(c.entry.dt, 2e-3);
  // 10 %: everything passes, the cheapest is rk4 at 10 ms
  c = choose_for_tolerance(t, "uniform-air", 0.1);
  EXPECT_EQ(c.entry.integrator, "rk4");
  EXPECT_DOUBLE_EQ(c.entry.dt, 1e-2);
}

TEST(Tolerance, UnreachableToleranceNamesTheSmallestMeasuredError) {
  try {
    choose_for_tolerance(small_table(), "uniform-air", 1e-5);
    FAIL() << "no throw";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::BadInput);
    EXPECT_NE(std::string(e.what()).find("0.0003"), std::string::npos) << e.what();
    // the flag's value first, what is reachable, and what to do
    const std::string w = e.what();
    EXPECT_EQ(w.rfind("--tolerance 1e-05 is not reachable for 'uniform-air' scenes", 0), 0u) << w;
    EXPECT_NE(w.find("the reachable tolerances are 0.0003 and above"), std::string::npos) << w;
    EXPECT_NE(w.find("Pass --tolerance 0.0003 or more"), std::string::npos) << w;
  }
  EXPECT_THROW(choose_for_tolerance(small_table(), "uniform-air", 0), Error);
  EXPECT_THROW(choose_for_tolerance(small_table(), "uniform-air", -1), Error);
}

TEST(Tolerance, FallsBackToAKindWithTheSameMedium) {
  const ToleranceChoice c = choose_for_tolerance(small_table(), "uniform-water", 0.05);
  EXPECT_EQ(c.kind, "grid-water");
  EXPECT_NE(c.explanation.find("closest kind"), std::string::npos);
  ToleranceTable t = small_table();
  t.kinds.erase("grid-water");
  EXPECT_THROW(choose_for_tolerance(t, "grid-water", 0.05), Error);
}

TEST(Tolerance, SceneKindFromFieldAndMedium) {
  Scene s;
  s.uniform_field = true;
  s.fluid_density = 1.204;
  EXPECT_EQ(scene_kind(s), "uniform-air");
  s.uniform_field = false;
  s.fluid_density = 998.2;
  EXPECT_EQ(scene_kind(s), "grid-water");
}

std::string write_tmp(const std::string& name, const std::string& text) {
  const std::string p = std::string(LRIGID_BINARY_DIR) + "/" + name;
  std::ofstream(p) << text;
  return p;
}

TEST(ToleranceTable, ReadsAndRejectsBadEntries) {
  const std::string ok = write_tmp(
      "tol_ok.json",
      R"({"kinds": {"uniform-air": [{"integrator": "rk4", "dt": 0.002, "error": 0.01,)"
      R"( "cost": 0.004}]}})");
  const ToleranceTable t = read_tolerance_table(ok);
  ASSERT_EQ(t.kinds.at("uniform-air").size(), 1u);
  EXPECT_EQ(t.kinds.at("uniform-air")[0].integrator, "rk4");
  EXPECT_DOUBLE_EQ(t.kinds.at("uniform-air")[0].dt, 0.002);
  const std::string bad = write_tmp(
      "tol_bad.json",
      R"({"kinds": {"uniform-air": [{"integrator": "rk4", "dt": -1, "error": 0.01,)"
      R"( "cost": 0.004}]}})");
  try {
    read_tolerance_table(bad);
    FAIL() << "no throw";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("tol_bad.json"), std::string::npos) << m;
    EXPECT_NE(m.find("kinds.uniform-air[0].dt"), std::string::npos) << m;
  }
  const std::string scheme = write_tmp(
      "tol_scheme.json",
      R"({"kinds": {"uniform-air": [{"integrator": "verlet", "dt": 1, "error": 0.01,)"
      R"( "cost": 0.004}]}})");
  EXPECT_THROW(read_tolerance_table(scheme), Error);
  EXPECT_THROW(read_tolerance_table(write_tmp("tol_json.json", "{\"kinds\": [")), Error);
  EXPECT_THROW(read_tolerance_table(std::string(LRIGID_BINARY_DIR) + "/no_such.json"), Error);
}

}  // namespace
}  // namespace lrigid
