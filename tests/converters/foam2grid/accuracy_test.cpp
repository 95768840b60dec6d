// foam2grid against OpenFOAM itself: values on the grid must equal what OpenFOAM's own
// cellPoint interpolation (the sets function object run by postProcess) gives at the same
// points, on the tiny case (simpleFoam, k-epsilon, cube obstacle, symmetry and wall patches).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <random>
#include <sstream>
#include <vector>

#include "foam2grid/case_fixture.h"
#include "foam2grid/vti_util.h"

namespace fs = std::filesystem;
using namespace foam2grid_test;

// Tolerance: 1e-6 of each field's range over the grid. The grid stores float32 (rounding of
// 6e-8 of the value, and |value| <= range here), OpenFOAM writes its samples with
// writePrecision 8 (5e-9 relative), and both read the same 8-digit field files; the rest is
// floating-point summation order in the point interpolation (~1e-15). Measured: 6e-8 at
// most (docs/converter.md). 1e-6 is still 10^5 below the gap between the cellPoint and cell
// schemes (checked below), so a wrong tet, weight or boundary rule fails the test.
constexpr double kTolerance = 1e-6;

namespace {

struct Sample {
  double x[3];
  double ours[6];  // U (3), k, epsilon, nut
  double of[6];
  bool have_u = false, have_s = false;
};

// random valid grid points
std::vector<Sample> pick_points(vtkImageData* im, std::size_t n, unsigned seed) {
  vtkDataArray* valid = im->GetPointData()->GetArray("valid");
  std::vector<vtkIdType> ids;
  for (vtkIdType i = 0; i < im->GetNumberOfPoints(); ++i) {
    if (valid->GetTuple1(i) != 0) ids.push_back(i);
  }
  std::mt19937_64 rng(seed);
  std::shuffle(ids.begin(), ids.end(), rng);
  ids.resize(std::min(n, ids.size()));
  std::vector<Sample> out(ids.size());
  const char* names[] = {"k", "epsilon", "nut"};
  for (std::size_t i = 0; i < ids.size(); ++i) {
    im->GetPoint(ids[i], out[i].x);
    double u[3];
    im->GetPointData()->GetArray("U")->GetTuple(ids[i], u);
    for (int k = 0; k < 3; ++k) out[i].ours[k] = u[k];
    for (int f = 0; f < 3; ++f)
      out[i].ours[3 + f] = im->GetPointData()->GetArray(names[f])->GetTuple1(ids[i]);
  }
  return out;
}

// the sets function object (cloud of points, cellPoint) through postProcess on the latest time
void sample_with_openfoam(const std::string& case_dir, std::vector<Sample>* s) {
  {
    std::ofstream d(case_dir + "/system/foam2gridCloud");
    d << "FoamFile { version 2.0; format ascii; class dictionary; object foam2gridCloud; }\n"
      << "functions\n{\n  foam2gridCloud\n  {\n    type sets;\n    libs (\"libsampling.so\");\n"
      << "    interpolationScheme cellPoint;\n    setFormat raw;\n    writeControl writeTime;\n"
      << "    fields (U k epsilon nut);\n    sets\n    (\n      pts\n      {\n"
      << "        type cloud;\n        axis xyz;\n        points\n        (\n";
    d << std::setprecision(17);
    for (const Sample& p : *s)
      d << "          (" << p.x[0] << " " << p.x[1] << " " << p.x[2] << ")\n";
    d << "        );\n      }\n    );\n  }\n}\n";
  }
  std::string log;
  const int rc = run("cd " + quote(case_dir) +
                         " && export WM_PROJECT_DIR=/usr/share/openfoam && /usr/bin/postProcess"
                         " -dict system/foam2gridCloud -latestTime -fields '(U k epsilon nut)'"
                         " > log.postProcess 2>&1",
                     &log);
  ASSERT_EQ(rc, 0) << "postProcess failed, see " << case_dir << "/log.postProcess " << log;
  fs::path dir;
  for (const auto& e : fs::directory_iterator(case_dir + "/postProcessing/foam2gridCloud"))
    dir = e.path();
  auto match = [&](double x, double y, double z) -> Sample* {
    Sample* best = nullptr;
    double bd = 1e300;
    for (Sample& p : *s) {
      const double d = std::fabs(p.x[0] - x) + std::fabs(p.x[1] - y) + std::fabs(p.x[2] - z);
      if (d < bd) {
        bd = d;
        best = &p;
      }
    }
    return bd < 1e-6 ? best : nullptr;
  };
  {
    std::ifstream in(dir / "pts_U.xy");
    ASSERT_TRUE(in) << "no " << (dir / "pts_U.xy");
    double x, y, z, a, b, c;
    while (in >> x >> y >> z >> a >> b >> c) {
      Sample* p = match(x, y, z);
      ASSERT_NE(p, nullptr) << "OpenFOAM sampled a point not asked for: " << x << " " << y << " "
                            << z;
      p->of[0] = a;
      p->of[1] = b;
      p->of[2] = c;
      p->have_u = true;
    }
  }
  {
    // scalar fields in alphabetical order
    std::ifstream in(dir / "pts_epsilon_k_nut.xy");
    ASSERT_TRUE(in) << "no " << (dir / "pts_epsilon_k_nut.xy");
    double x, y, z, eps, k, nut;
    while (in >> x >> y >> z >> eps >> k >> nut) {
      Sample* p = match(x, y, z);
      ASSERT_NE(p, nullptr);
      p->of[3] = k;
      p->of[4] = eps;
      p->of[5] = nut;
      p->have_s = true;
    }
  }
}

// field ranges over the valid grid points: |U| max for U, max - min for the scalars
void ranges(vtkImageData* im, double r[4]) {
  vtkDataArray* valid = im->GetPointData()->GetArray("valid");
  const char* names[] = {"U", "k", "epsilon", "nut"};
  for (int f = 0; f < 4; ++f) {
    vtkDataArray* a = im->GetPointData()->GetArray(names[f]);
    double mn = 1e300, mx = -1e300;
    for (vtkIdType i = 0; i < im->GetNumberOfPoints(); ++i) {
      if (valid->GetTuple1(i) == 0) continue;
      double v;
      if (f == 0) {
        double u[3];
        a->GetTuple(i, u);
        v = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        mn = 0;
      } else {
        v = a->GetTuple1(i);
      }
      mn = std::min(mn, v);
      mx = std::max(mx, v);
    }
    r[f] = mx - mn;
  }
}

// worst |ours - OpenFOAM| / range per field: U (over components), k, epsilon, nut
void discrepancy(const std::vector<Sample>& s, const double r[4], double worst[4], int* n) {
  std::fill(worst, worst + 4, 0.0);
  *n = 0;
  for (const Sample& p : s) {
    if (!p.have_u || !p.have_s) continue;
    ++*n;
    for (int k = 0; k < 3; ++k)
      worst[0] = std::max(worst[0], std::fabs(p.ours[k] - p.of[k]) / r[0]);
    for (int f = 1; f < 4; ++f) {
      worst[f] = std::max(worst[f], std::fabs(p.ours[2 + f] - p.of[2 + f]) / r[f]);
    }
  }
}

// runs foam2grid on case_dir, samples n random valid grid points with OpenFOAM, returns the
// worst discrepancy per field relative to its range (U, k, epsilon, nut), checks >= 200 points
void compare(const std::string& case_dir, const std::string& w, const std::string& flags,
             double worst[4], double ranges_out[4]) {
  const std::string vti = w + "/grid.vti";
  std::string out;
  ASSERT_EQ(run(quote(foam2grid_bin()) + " " + quote(case_dir) + " -o " + quote(vti) + " " + flags +
                    " -q",
                &out),
            0)
      << out;
  vtkSmartPointer<vtkImageData> im = read_vti(vti);
  std::vector<Sample> s = pick_points(im, 400, 20261122u);
  sample_with_openfoam(case_dir, &s);
  int n = 0;
  ranges(im, ranges_out);
  discrepancy(s, ranges_out, worst, &n);
  std::cout << "points compared: " << n << " of " << s.size() << "\n"
            << "max |foam2grid - OpenFOAM| / range: U " << worst[0] << ", k " << worst[1]
            << ", epsilon " << worst[2] << ", nut " << worst[3] << "\n"
            << "ranges: |U| " << ranges_out[0] << " m/s, k " << ranges_out[1]
            << " m^2/s^2, epsilon " << ranges_out[2] << " m^2/s^3, nut " << ranges_out[3]
            << " m^2/s\n";
  EXPECT_GE(n, 200);
}

}  // namespace

TEST(Foam2gridAccuracy, CellPointMatchesOpenFoamSampleAtRandomGridPoints) {
  const std::string prepared = prepared_case("tiny");
  const std::string w = work_dir("accuracy_cellpoint");
  const std::string c = w + "/case";
  ASSERT_EQ(run("cp -r " + quote(prepared) + " " + quote(c)), 0);
  const std::string vti = w + "/tiny.vti";
  std::string out;
  // 0.0137 m: does not line up with the 0.03 m cells (nor with the 0.15 m cube)
  ASSERT_EQ(
      run(quote(foam2grid_bin()) + " " + quote(c) + " -o " + quote(vti) + " --spacing 0.0137 -q",
          &out),
      0)
      << out;
  vtkSmartPointer<vtkImageData> im = read_vti(vti);
  std::vector<Sample> s = pick_points(im, 400, 20261122u);
  sample_with_openfoam(c, &s);
  double r[4], worst[4];
  int n = 0;
  ranges(im, r);
  discrepancy(s, r, worst, &n);
  std::cout << "points compared: " << n << " of " << s.size() << "\n"
            << "max |foam2grid - OpenFOAM| / range: U " << worst[0] << ", k " << worst[1]
            << ", epsilon " << worst[2] << ", nut " << worst[3] << "\n"
            << "ranges: |U| " << r[0] << " m/s, k " << r[1] << " m^2/s^2, epsilon " << r[2]
            << " m^2/s^3, nut " << r[3] << " m^2/s\n";
  EXPECT_GE(n, 200);
  EXPECT_LE(worst[0], kTolerance) << "U";
  EXPECT_LE(worst[1], kTolerance) << "k";
  EXPECT_LE(worst[2], kTolerance) << "epsilon";
  EXPECT_LE(worst[3], kTolerance) << "nut";

  // the check has teeth: the piecewise-constant cell scheme is far outside the tolerance
  const std::string vti_cell = w + "/tiny_cell.vti";
  ASSERT_EQ(run(quote(foam2grid_bin()) + " " + quote(c) + " -o " + quote(vti_cell) +
                    " --spacing 0.0137 --interpolation cell -q",
                &out),
            0)
      << out;
  vtkSmartPointer<vtkImageData> im_cell = read_vti(vti_cell);
  std::vector<Sample> sc = pick_points(im_cell, 400, 20261122u);
  for (std::size_t i = 0; i < sc.size(); ++i) {
    std::copy(s[i].of, s[i].of + 6, sc[i].of);
    sc[i].have_u = s[i].have_u;
    sc[i].have_s = s[i].have_s;
  }
  double worst_cell[4];
  discrepancy(sc, r, worst_cell, &n);
  std::cout << "cell scheme, max discrepancy / range: U " << worst_cell[0] << ", k "
            << worst_cell[1] << ", epsilon " << worst_cell[2] << ", nut " << worst_cell[3] << "\n";
  EXPECT_GT(worst_cell[0], 1e3 * kTolerance);
  EXPECT_GT(worst_cell[1], 1e3 * kTolerance);
}

// A skewed, graded mesh: the tiny case's box with two top corners moved (warped inlet, top and
// side faces) and grading 2 : 0.5 : 3, so cell centres, face centres, inverse-distance weights
// and the tet decomposition are all non-trivial; 30 simpleFoam iterations give the fields.
TEST(Foam2gridAccuracy, CellPointMatchesOpenFoamOnASkewedGradedMesh) {
  const std::string w = work_dir("accuracy_skewed");
  const std::string c = w + "/case";
  const std::string src = std::string(LRIGID_SOURCE_DIR) + "/foam_cases/tiny";
  std::string log;
  ASSERT_EQ(run("cp -r " + quote(src) + " " + quote(c) + " && cd " + quote(c) +
                    " && sed -i -e 's/(\\$xMax \\$yMax \\$zMax)/(1.32 0.46 0.34)/'"
                    " -e 's/(0     \\$yMax \\$zMax)/(-0.06 0.43 0.27)/'"
                    " -e 's/simpleGrading (1 1 1)/simpleGrading (2 0.5 3)/' system/blockMeshDict"
                    " && grep -q '(1.32 0.46 0.34)' system/blockMeshDict"
                    " && grep -q '(-0.06 0.43 0.27)' system/blockMeshDict"
                    " && grep -q 'simpleGrading (2 0.5 3)' system/blockMeshDict"
                    " && export WM_PROJECT_DIR=/usr/share/openfoam"
                    " && /usr/bin/blockMesh > log.blockMesh 2>&1"
                    " && /usr/bin/topoSet > log.topoSet 2>&1"
                    " && /usr/bin/subsetMesh fluid -patch obstacle -overwrite > log.subsetMesh 2>&1"
                    " && rm -rf 0 && cp -r 0.orig 0"
                    " && foamDictionary -entry endTime -set 30 system/controlDict > /dev/null"
                    " && foamDictionary -entry writeInterval -set 30 system/controlDict > /dev/null"
                    " && /usr/bin/simpleFoam > log.simpleFoam 2>&1 && test -d 30",
                &log),
            0)
      << "preparing the skewed case failed in " << c << ": " << log;
  double worst[4], r[4];
  compare(c, w, "--resolution 71 29 23", worst, r);
  EXPECT_LE(worst[0], kTolerance) << "U";
  EXPECT_LE(worst[1], kTolerance) << "k";
  EXPECT_LE(worst[2], kTolerance) << "epsilon";
  EXPECT_LE(worst[3], kTolerance) << "nut";
}
