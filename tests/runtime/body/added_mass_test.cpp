// Exact Kirchhoff tensors of spheres and ellipsoids (runtime/src/body/added_mass.cpp) against
// Lamb's results and the reference table of docs/physics/added-mass.md.
#include "body/added_mass.h"

#include <gtest/gtest.h>

#include <cmath>

#include <memory>

#include "body/mass_properties.h"
#include "body/tessellate.h"
#include "util/error.h"

namespace lrigid {
namespace {

TEST(CarlsonRD, KnownValues) {
  EXPECT_NEAR(carlson_rd(1, 1, 1), 1.0, 1e-14);  // R_D(x, x, x) = x^(-3/2)
  EXPECT_NEAR(carlson_rd(4, 4, 4), 0.125, 1e-15);
  // R_D(0, 2, 1) = 1.7972103521034 (DLMF 19.36 / Carlson 1995 test value)
  EXPECT_NEAR(carlson_rd(0, 2, 1), 1.7972103521034, 1e-12);
  EXPECT_THROW(carlson_rd(0, 0, 1), Error);
}

TEST(EllipsoidConstants, SumToTwoAndSphere) {
  EXPECT_LT((ellipsoid_constants(Vec3(1, 1, 1)) - Vec3::Constant(2.0 / 3.0)).norm(), 1e-14);
  for (const Vec3& s : {Vec3(3, 2, 1), Vec3(10, 1, 1), Vec3(1, 1, 0.001), Vec3(0.2, 5, 0.7)})
    EXPECT_NEAR(ellipsoid_constants(s).sum(), 2.0, 1e-12) << s.transpose();
  // prolate spheroid closed form: alpha0 = 2 (1 - e^2)/e^3 (atanh(e) - e), e the eccentricity
  const double e = std::sqrt(1 - 0.25);
  EXPECT_NEAR(ellipsoid_constants(Vec3(2, 1, 1))[0],
              2 * (1 - e * e) / (e * e * e) * (std::atanh(e) - e), 1e-13);
}

TEST(AddedMassAnalytic, SphereIsHalfDisplacedMassNoRotation) {
  const double rho = 998.2, r = 0.1;
  const AddedMass am = added_mass(Shape::sphere(r), rho);
  const double v = 4.0 / 3.0 * M_PI * r * r * r;
  EXPECT_EQ(am.method, "analytic");
  EXPECT_EQ(am.panels, 0);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(am.tensor(i, i), 0.5 * rho * v, 1e-12 * rho * v);
  EXPECT_EQ((am.tensor.block<3, 3>(3, 3).norm()), 0.0);
  Mat6 off = am.tensor;
  off.diagonal().setZero();
  EXPECT_EQ(off, Mat6::Zero());
}

// k = m / (rho V), k_rot = I / (rho V (a^2 + b^2) / 5); prolate along x, a/b = 2, 5, 10
// (Lamb, Hydrodynamics section 115 table; physics-notes section 3)
TEST(AddedMassAnalytic, ProlateTableValues) {
  struct Row {
    double ratio, axial, transverse, rot;
  };
  for (const Row& r : {Row{2, 0.2100, 0.7042, 0.2394}, Row{5, 0.0591, 0.8943, 0.6999},
                       Row{10, 0.0207, 0.9602, 0.8835}}) {
    const Shape s = Shape::ellipsoid(r.ratio, 1, 1);
    const double v = mass_properties(s).volume;
    const AddedMass am = added_mass(s, 1.0);
    EXPECT_NEAR(am.tensor(0, 0) / v, r.axial, 1e-4) << r.ratio;
    EXPECT_NEAR(am.tensor(1, 1) / v, r.transverse, 1e-4) << r.ratio;
    EXPECT_NEAR(am.tensor(2, 2) / v, r.transverse, 1e-4) << r.ratio;
    EXPECT_EQ(am.tensor(3, 3), 0.0) << "no added inertia about the symmetry axis";
    const double inorm = v * (r.ratio * r.ratio + 1) / 5;
    EXPECT_NEAR(am.tensor(4, 4) / inorm, r.rot, 1e-4) << r.ratio;
    EXPECT_NEAR(am.tensor(5, 5) / inorm, r.rot, 1e-4) << r.ratio;
  }
}

// oblate a = b = 1, thickness c; per rho a^3 (translation) and rho a^5 (rotation)
TEST(AddedMassAnalytic, OblateAndDiskLimit) {
  struct Row {
    double c, normal, edge, diam;
  };
  for (const Row& r : {Row{0.5, 2.335, 0.648, 0.177}, Row{0.1, 2.590, 0.031, 0.340},
                       Row{0.01, 2.659, 3e-4, 0.355}}) {
    const AddedMass am = added_mass(Shape::ellipsoid(1, 1, r.c), 1.0);
    EXPECT_NEAR(am.tensor(2, 2), r.normal, 1e-3) << r.c;
    EXPECT_NEAR(am.tensor(0, 0), r.edge, std::max(1e-3, 1e-2 * r.edge)) << r.c;
    EXPECT_NEAR(am.tensor(3, 3), r.diam, 1e-3) << r.c;
    EXPECT_EQ(am.tensor(5, 5), 0.0);
  }
  // thin disk: m_n -> 8/3 rho a^3, I_diam -> 16/45 rho a^5, edgewise -> 0; the errors fall
  // linearly with the thickness
  const double a = 0.5, rho = 1000;
  double prev = 1;
  for (double c : {1e-2, 1e-3, 1e-4}) {
    const AddedMass am = added_mass(Shape::ellipsoid(a, a, c * a), rho);
    const double en = std::abs(am.tensor(2, 2) / (8.0 / 3.0 * rho * std::pow(a, 3)) - 1);
    const double er = std::abs(am.tensor(3, 3) / (16.0 / 45.0 * rho * std::pow(a, 5)) - 1);
    EXPECT_LT(en, c) << c;
    EXPECT_LT(er, 2 * c) << c;
    EXPECT_LT(en, prev / 5);
    prev = en;
    EXPECT_LT(am.tensor(0, 0) / (rho * std::pow(a, 3)), 4 * c * c);  // ~3.3 c^2
  }
}

TEST(AddedMassAnalytic, TriaxialIsSymmetricPositiveAndScalesWithDensity) {
  const Shape s = Shape::ellipsoid(0.3, 0.2, 0.05);
  const AddedMass a1 = added_mass(s, 1.0), a2 = added_mass(s, 1.2);
  EXPECT_LT((a2.tensor - 1.2 * a1.tensor).norm(), 1e-14 * a2.tensor.norm());
  for (int i = 0; i < 6; ++i) EXPECT_GT(a1.tensor(i, i), 0.0) << i;
  // more fluid is pushed normal to the flattest face: m_z > m_y > m_x
  EXPECT_GT(a1.tensor(2, 2), a1.tensor(1, 1));
  EXPECT_GT(a1.tensor(1, 1), a1.tensor(0, 0));
  EXPECT_EQ(added_mass(s, 0.0).tensor, Mat6::Zero());
}

TEST(AddedMassBox, IsTheDiagonalOfThePanelSolution) {
  // a box's three mirror planes make its tensor diagonal: added_mass keeps the panel method's
  // diagonal and drops its off-diagonal round-off, which must be negligible against it
  const Shape s = Shape::box(0.148, 0.105, 0.0001);  // a sheet of paper, 1000:1
  const AddedMass am = added_mass(s, 1.2, 200), bem = added_mass_bem(s, 1.2, 200);
  EXPECT_EQ(am.method, "bem");
  EXPECT_EQ(am.tensor, Mat6(am.tensor.diagonal().asDiagonal()));
  EXPECT_EQ(am.tensor.diagonal(), bem.tensor.diagonal());
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) {
      if (i == j) continue;
      EXPECT_LE(std::abs(bem.tensor(i, j)), 1e-6 * std::sqrt(bem.tensor(i, i) * bem.tensor(j, j)))
          << i << "," << j;
    }
}

TEST(AddedMassBem, TheSameGeometryAgainReusesItsSolveAndAnotherGetsItsOwn) {
  // the process keeps its panel solutions: a box or mesh compiled again costs no solve and
  // gives the same tensor to the bit; any change of the geometry or the panel target solves anew
  const Shape box = Shape::box(0.06, 0.04, 4e-4);
  const int before = bem_solve_count();
  const AddedMass first = added_mass(box, 1.2, 300);
  EXPECT_EQ(bem_solve_count(), before + 1);
  const AddedMass again = added_mass(box, 1000, 300);  // another fluid: the same solve, scaled
  EXPECT_EQ(bem_solve_count(), before + 1);
  EXPECT_TRUE(again.tensor.isApprox((1000 / 1.2) * first.tensor, 1e-14));
  EXPECT_EQ(added_mass(box, 1.2, 300).tensor, first.tensor);
  EXPECT_EQ(bem_solve_count(), before + 1);
  added_mass(Shape::box(0.06, 0.04, 5e-4), 1.2, 300);  // another thickness
  EXPECT_EQ(bem_solve_count(), before + 2);
  added_mass(box, 1.2, 400);  // another panel target
  EXPECT_EQ(bem_solve_count(), before + 3);

  // meshes by their content: a copy of the mesh reuses the solve, a vertex moved within the
  // same bounding box does not
  TriangleMesh m = tessellate(Shape::box(0.05, 0.03, 0.01), 300);
  const Shape a = Shape::from_mesh(std::make_shared<const TriangleMesh>(m), "a.obj");
  const Shape copy = Shape::from_mesh(std::make_shared<const TriangleMesh>(m), "copy.obj");
  const int meshes = bem_solve_count();
  const AddedMass ma = added_mass(a, 1.2);
  EXPECT_EQ(added_mass(copy, 1.2).tensor, ma.tensor);
  EXPECT_EQ(bem_solve_count(), meshes + 1);
  bool moved = false;
  for (Vec3& v : m.vertices)
    if (std::abs(v.z() - 0.005) < 1e-12 && std::abs(v.x()) < 0.02 && std::abs(v.y()) < 0.01) {
      v.x() += 1e-4;  // in the top face: the bounding box stays
      moved = true;
      break;
    }
  ASSERT_TRUE(moved);
  const Shape b = Shape::from_mesh(std::make_shared<const TriangleMesh>(m), "b.obj");
  ASSERT_EQ(b.half_extents, a.half_extents);
  added_mass(b, 1.2);
  EXPECT_EQ(bem_solve_count(), meshes + 2);
}

TEST(AddedMass, RejectsBadArguments) {
  EXPECT_THROW(added_mass(Shape::sphere(1), -1.0), Error);
  EXPECT_THROW(added_mass(Shape::sphere(1), NAN), Error);
  EXPECT_THROW(added_mass(Shape::box(1, 1, 1), 1000, -5), Error);
}

}  // namespace
}  // namespace lrigid
