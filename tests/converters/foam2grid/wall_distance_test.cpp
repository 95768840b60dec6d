// foam2grid's wall_distance array against the closed form of the tiny case's geometry: walls are
// the ground z = 0 and the cut-out cube [0.3, 0.45] x [0.4/3, 0.8/3] x [0, 0.15] m (its five
// faces); the top and the sides are symmetry planes and the inlet and outlet patches, which give
// no wall. In the fluid the distance is min(z, distance to the box); inside the cube (including
// its footprint on the ground, where the mesh has no face) it is minus the distance to its
// nearest face.
#include <gtest/gtest.h>
#include <vtkFloatArray.h>

#include <algorithm>
#include <cmath>

#include "foam2grid/case_fixture.h"
#include "foam2grid/vti_util.h"

using namespace foam2grid_test;

namespace {

constexpr double kLo[3] = {0.3, 0.4 / 3, 0.0}, kHi[3] = {0.45, 0.8 / 3, 0.15};

double closed_form(const double* x) {
  bool inside = true;
  double out2 = 0, in = HUGE_VAL;
  for (int a = 0; a < 3; ++a) {
    const double below = kLo[a] - x[a], above = x[a] - kHi[a];
    const double gap = std::max({below, above, 0.0});
    out2 += gap * gap;
    // the bottom z = 0 is the ground the cube stands on: points on it under the cube are inside
    inside = inside && (below < 0 || a == 2) && above < 0;
    // the cube's bottom lies on the ground and is no face: only the other five count
    if (a < 2) in = std::min({in, -below, -above});
    else in = std::min(in, -above);
  }
  if (inside) return -in;
  return std::min(x[2], std::sqrt(out2));
}

int run_f2g(const std::string& args, std::string* out) {
  return run(quote(foam2grid_bin()) + " " + args, out);
}

}  // namespace

TEST(Foam2gridWallDistance, MatchesTheClosedFormOfTheCubeOnTheGround) {
  const std::string w = work_dir("wall_distance");
  const std::string out = w + "/tiny.vti";
  std::string log;
  ASSERT_EQ(run_f2g(quote(prepared_case("tiny")) + " -o " + quote(out) + " --spacing 0.0137", &log),
            0)
      << log;
  EXPECT_NE(log.find("wall distance: "), std::string::npos) << log;
  vtkSmartPointer<vtkImageData> im = read_vti(out);
  auto* d = vtkFloatArray::SafeDownCast(im->GetPointData()->GetArray("wall_distance"));
  ASSERT_NE(d, nullptr);
  ASSERT_EQ(d->GetNumberOfComponents(), 1);
  vtkDataArray* valid = im->GetPointData()->GetArray("valid");
  double worst = 0;
  vtkIdType negative = 0;
  for (vtkIdType i = 0; i < im->GetNumberOfPoints(); ++i) {
    double x[3];
    im->GetPoint(i, x);
    const double got = d->GetValue(i), want = closed_form(x);
    worst = std::max(worst, std::fabs(got - want));
    // the sign is the validity: positive (or 0 on a wall) in the fluid, negative in the cube
    if (valid->GetTuple1(i) != 0) {
      EXPECT_GE(got, 0.0) << i;
    } else {
      EXPECT_LT(got, 0.0) << i;
    }
    negative += got < 0;
  }
  // float32 storage of distances below 0.5 m: a few 1e-8 m
  EXPECT_LT(worst, 1e-6) << "largest deviation from the closed form, m";
  EXPECT_GT(negative, 1000);  // the cube holds grid points
}

TEST(Foam2gridWallDistance, IsAlwaysWrittenAndCannotBeRequested) {
  const std::string w = work_dir("wall_distance_fields");
  std::string log;
  EXPECT_EQ(run_f2g(quote(prepared_case("tiny")) + " -o " + quote(w + "/x.vti") +
                        " --fields U,wall_distance -q",
                    &log),
            2);
  EXPECT_NE(log.find("'wall_distance' is always written"), std::string::npos) << log;
}
