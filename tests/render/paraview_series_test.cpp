// The ParaView series of a real run (docs/paraview.md) against trajectories.csv: bodies.pvd
// holds each body's centre of mass and quaternion at every output time; shapes.pvd holds each
// body's surface placed at (x, q): brought back into the body frame, a paper card's vertices
// fill its box (+-half extents of summary.json) and a bead's lie on its sphere.
#include <gtest/gtest.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

struct Sample {
  Eigen::Vector3d x;
  Eigen::Quaterniond q;
};

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// (timestep, file) entries of a .pvd collection
std::vector<std::pair<double, std::string>> pvd_entries(const std::string& path) {
  const std::string text = slurp(path);
  const std::regex ds(R"re(<DataSet timestep="([^"]*)"[^>]*file="([^"]*)")re");
  std::vector<std::pair<double, std::string>> out;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), ds); it != std::sregex_iterator();
       ++it)
    out.emplace_back(std::stod((*it)[1]), (*it)[2]);
  return out;
}

vtkSmartPointer<vtkPolyData> read_vtp(const std::string& path) {
  vtkNew<vtkXMLPolyDataReader> r;
  r->SetFileName(path.c_str());
  r->Update();
  return r->GetOutput();
}

class ParaviewSeries : public ::testing::Test {
 protected:
  void SetUp() override {
    // one directory per test: ctest runs the tests in parallel
    dir_ = std::string(LRIGID_BINARY_DIR) + "/tests/render/paraview_series_" +
           ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // uniform_box.json, small: 6 paper cards and 4 beads, 0.5 s, outputs every 0.1 s
    nlohmann::json s =
        nlohmann::json::parse(slurp(std::string(LRIGID_SOURCE_DIR) + "/scenes/uniform_box.json"));
    s["bodies"][0]["count"] = 6;
    s["bodies"][1]["count"] = 4;
    s["duration"] = 0.5;
    s["output"] = {{"dir", dir_ + "/out"}, {"every", 0.1}, {"formats", {"csv", "pvd"}}};
    std::ofstream(dir_ + "/scene.json") << s.dump(1);
    const std::string cmd = std::string(LRIGID_BINARY_DIR) + "/bin/lrigid run " + dir_ +
                            "/scene.json --quiet > " + dir_ + "/log 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(dir_ + "/log");
    summary_ = nlohmann::json::parse(slurp(dir_ + "/out/summary.json"));
    std::istringstream csv(slurp(dir_ + "/out/trajectories.csv"));
    std::string line;
    std::getline(csv, line);  // header
    while (std::getline(csv, line)) {
      std::vector<std::string> f;
      std::stringstream ls(line);
      for (std::string c; std::getline(ls, c, ',');) f.push_back(c);
      ASSERT_GE(f.size(), 10u) << line;
      const double t = std::stod(f[2]);
      if (times_.empty() || times_.back() != t) times_.push_back(t);
      Sample smp{
          {std::stod(f[3]), std::stod(f[4]), std::stod(f[5])},
          Eigen::Quaterniond(std::stod(f[6]), std::stod(f[7]), std::stod(f[8]), std::stod(f[9]))};
      samples_[{std::stoi(f[0]), times_.size() - 1}] = smp;
      type_[std::stoi(f[0])] = f[1];
    }
  }

  std::string dir_;
  nlohmann::json summary_;
  std::vector<double> times_;
  std::map<std::pair<int, size_t>, Sample> samples_;
  std::map<int, std::string> type_;
};

TEST_F(ParaviewSeries, BodiesPointsCarryPositionAndOrientation) {
  const auto frames = pvd_entries(dir_ + "/out/bodies.pvd");
  ASSERT_EQ(frames.size(), times_.size());
  for (size_t f = 0; f < frames.size(); ++f) {
    EXPECT_NEAR(frames[f].first, times_[f], 1e-9);
    vtkSmartPointer<vtkPolyData> p = read_vtp(dir_ + "/out/" + frames[f].second);
    ASSERT_EQ(p->GetNumberOfPoints(), vtkIdType(type_.size()));
    vtkDataArray* q = p->GetPointData()->GetArray("orientation");
    vtkDataArray* id = p->GetPointData()->GetArray("body");
    ASSERT_TRUE(q && id && q->GetNumberOfComponents() == 4);
    for (vtkIdType i = 0; i < p->GetNumberOfPoints(); ++i) {
      const Sample& s = samples_.at({int(id->GetTuple1(i)), f});
      double x[3];
      p->GetPoint(i, x);
      EXPECT_LT((Eigen::Vector3d(x[0], x[1], x[2]) - s.x).norm(), 1e-7 * (1 + s.x.norm()));
      const double* w = q->GetTuple4(i);
      const double dot = w[0] * s.q.w() + w[1] * s.q.x() + w[2] * s.q.y() + w[3] * s.q.z();
      EXPECT_NEAR(std::fabs(dot), 1.0, 1e-7) << "body " << id->GetTuple1(i) << " frame " << f;
    }
  }
}

TEST_F(ParaviewSeries, ShapesAreTheBodiesSurfacesPlacedAtXAndQ) {
  const auto frames = pvd_entries(dir_ + "/out/shapes.pvd");
  ASSERT_EQ(frames.size(), times_.size());
  std::map<std::string, nlohmann::json> types;
  for (const auto& t : summary_["body_types"]) types[t["name"]] = t;
  // float32 points a few metres from the origin: about 1e-6 m
  constexpr double kTol = 3e-6;
  for (size_t f = 0; f < frames.size(); ++f) {
    EXPECT_NEAR(frames[f].first, times_[f], 1e-9);
    vtkSmartPointer<vtkPolyData> p = read_vtp(dir_ + "/out/" + frames[f].second);
    vtkDataArray* id = p->GetCellData()->GetArray("body");
    ASSERT_TRUE(id != nullptr);
    // body -> its vertices, brought into the body frame: R^T (p - x) + com
    std::map<int, std::vector<Eigen::Vector3d>> local;
    vtkNew<vtkIdList> pts;
    for (vtkIdType c = 0; c < p->GetNumberOfCells(); ++c) {
      const int b = int(id->GetTuple1(c));
      const Sample& s = samples_.at({b, f});
      const auto& com = types.at(type_.at(b))["com"];
      p->GetCellPoints(c, pts);
      for (vtkIdType k = 0; k < pts->GetNumberOfIds(); ++k) {
        double x[3];
        p->GetPoint(pts->GetId(k), x);
        local[b].push_back(s.q.normalized().conjugate() *
                               (Eigen::Vector3d(x[0], x[1], x[2]) - s.x) +
                           Eigen::Vector3d(com[0], com[1], com[2]));
      }
    }
    ASSERT_EQ(local.size(), type_.size()) << "every body has a surface in frame " << f;
    for (const auto& [b, vs] : local) {
      const auto& shape = types.at(type_.at(b))["shape"];
      const Eigen::Vector3d h(shape["half_extents"][0], shape["half_extents"][1],
                              shape["half_extents"][2]);
      Eigen::Vector3d lo = vs[0], hi = vs[0];
      for (const Eigen::Vector3d& v : vs) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
        if (shape["type"] == "sphere") {
          EXPECT_NEAR(v.norm(), h.x(), kTol) << "body " << b;
        }
      }
      if (shape["type"] == "box") {
        // the surface spans exactly the box: corners at +-h along the body axes
        for (int k = 0; k < 3; ++k) {
          EXPECT_NEAR(hi[k], h[k], kTol) << "body " << b << " axis " << k << " frame " << f;
          EXPECT_NEAR(lo[k], -h[k], kTol) << "body " << b << " axis " << k << " frame " << f;
        }
      }
    }
  }
}

}  // namespace
