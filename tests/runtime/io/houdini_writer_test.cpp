// houdini_points.csv of a run against its trajectories.csv: Houdini's attribute names, one row
// per body and frame, the values within the printed digits, orient in Houdini's x, y, z, w order.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "io/houdini_writer.h"
#include "support/dcc_run.h"
#include "support/temp_dir.h"

namespace lrigid {
namespace {

struct HoudiniCache : test::TempDirTest {};

TEST_F(HoudiniCache, RowsAreTheTrajectoriesWithHoudinisNames) {
  test::run_dcc_scene(dir.string(), R"(["csv", "houdini"])");
  const auto rows = test::read_trajectories((dir / "trajectories.csv").string());
  const nlohmann::json summary = nlohmann::json::parse(std::ifstream(dir / "summary.json"));
  std::vector<int> variant;  // of each body, from its type in the summary
  for (const auto& t : summary["body_types"])
    for (size_t k = 0; k < t["count"].get<size_t>(); ++k) variant.push_back(t["variant"]);
  ASSERT_EQ(variant.size(), 5u);
  std::ifstream in(dir / "houdini_points.csv");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line,
            "frame,time,id,entry,variant,state,Px,Py,Pz,orientx,orienty,orientz,orientw,vx,vy,vz,"
            "wx,wy,wz");
  size_t n = 0;
  std::vector<Quat> first;  // body 0's orientations
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::vector<std::string> c;
    for (std::string cell; std::getline(ss, cell, ',');) c.push_back(cell);
    ASSERT_EQ(c.size(), 19u) << line;
    ASSERT_LT(n, rows.size());
    const test::TrajectoryRow& r = rows[n];
    EXPECT_EQ(std::stoul(c[0]), n / 5 + 1) << "frames count from 1";
    EXPECT_NEAR(std::stod(c[1]), r.t, 1e-12);
    EXPECT_EQ(std::stoul(c[2]), r.body);
    EXPECT_EQ(c[3], r.type);
    EXPECT_EQ(std::stoi(c[4]), variant[r.body]);
    EXPECT_EQ(c[5], r.state);
    auto d = [&](size_t i) { return std::stod(c[i]); };
    EXPECT_TRUE(test::near(Vec3(d(6), d(7), d(8)), r.x, 1e-8 * (1 + r.x.norm())));
    // x, y, z, w: the trajectory's rotation, up to the sign continuity keeps
    const Quat q(d(12), d(9), d(10), d(11));
    EXPECT_NEAR(std::abs(q.coeffs().dot(r.q.coeffs())), 1.0, 1e-8);
    EXPECT_TRUE(test::near(Vec3(d(13), d(14), d(15)), r.v, 1e-8 * (1 + r.v.norm())));
    EXPECT_TRUE(test::near(Vec3(d(16), d(17), d(18)), r.w, 1e-8 * (1 + r.w.norm())));
    if (r.body == 0) first.push_back(q);
    ++n;
  }
  // consecutive samples in one hemisphere (interpolated the short way round)
  ASSERT_EQ(first.size(), 5u);
  for (size_t f = 1; f < first.size(); ++f) EXPECT_GE(first[f].dot(first[f - 1]), 0.0);
  EXPECT_EQ(n, rows.size()) << "every body at every frame (none is hidden here)";
  EXPECT_EQ(n, 25u);
}

}  // namespace
}  // namespace lrigid
