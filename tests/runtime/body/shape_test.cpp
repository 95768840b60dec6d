// Shapes, tessellation, mesh checks and mass properties (runtime/src/body/shape.cpp,
// tessellate.cpp, mesh_check.cpp, mass_properties.cpp).
#include "body/shape.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <vector>
#include <functional>

#include "body/mass_properties.h"
#include "body/mesh_check.h"
#include "body/tessellate.h"
#include "support/fixture.h"
#include "util/error.h"

namespace lrigid {
namespace {

Shape mesh_shape(TriangleMesh m) {
  return Shape::from_mesh(std::make_shared<const TriangleMesh>(std::move(m)), "test");
}

TEST(Shape, ConstructorsStoreHalfExtents) {
  EXPECT_EQ(Shape::sphere(0.3).half_extents, Vec3(0.3, 0.3, 0.3));
  EXPECT_EQ(Shape::ellipsoid(3, 2, 1).half_extents, Vec3(3, 2, 1));
  EXPECT_EQ(Shape::box(2, 4, 6).half_extents, Vec3(1, 2, 3));
  EXPECT_EQ(Shape::box(2, 4, 6).type, ShapeType::Box);
  EXPECT_STREQ(shape_type_name(ShapeType::Ellipsoid), "ellipsoid");
}

TEST(Shape, RejectsNonPositiveSizes) {
  const auto bad_input = [](auto make) {
    try {
      make();
    } catch (const Error& e) {
      return e.code() == ExitCode::BadInput;
    }
    return false;
  };
  EXPECT_TRUE(bad_input([] { Shape::sphere(0); }));
  EXPECT_TRUE(bad_input([] { Shape::sphere(-1); }));
  EXPECT_TRUE(bad_input([] { Shape::sphere(NAN); }));
  EXPECT_TRUE(bad_input([] { Shape::ellipsoid(1, 0, 1); }));
  EXPECT_TRUE(bad_input([] { Shape::box(1, 1, -0.1); }));
  EXPECT_TRUE(bad_input([] { Shape::box(INFINITY, 1, 1); }));
  try {
    Shape::box(1, -2, 1);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ly"), std::string::npos) << e.what();
  }
}

TEST(Shape, RejectsLengthsOutOfRange) {
  // a radius of 1e-200 m underflowed the added-mass integrals (carlson_rd: invalid arguments);
  // a box of 1e160 m kept the boundary elements busy without end
  for (const auto& make : std::vector<std::function<void()>>{
           [] { Shape::sphere(1e-200); }, [] { Shape::sphere(1e300); },
           [] { Shape::ellipsoid(1e-200, 1e-200, 2e-200); }, [] { Shape::box(1e160, 1, 1); }}) {
    try {
      make();
      ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ExitCode::BadInput);
      EXPECT_NE(std::string(e.what()).find("[1e-9, 1e6] m"), std::string::npos) << e.what();
    }
  }
  // the ends of the range are lengths
  EXPECT_EQ(Shape::sphere(1e-9).half_extents.x(), 1e-9);
  EXPECT_EQ(Shape::box(1e6, 1e6, 10).half_extents.x(), 5e5);
  // a sheet thinner than 1e-5 of its width: the boundary elements' tensor was not positive
  try {
    Shape::box(1, 1, 1e-6);
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::BadInput);
    EXPECT_NE(std::string(e.what()).find("at most 1e5"), std::string::npos) << e.what();
  }
  EXPECT_EQ(Shape::box(1, 1, 1e-5).half_extents.z(), 5e-6);
}

TEST(MassProperties, ClosedForms) {
  const MassProperties s = mass_properties(Shape::sphere(2));
  EXPECT_NEAR(s.volume, 4.0 / 3.0 * M_PI * 8, 1e-12);
  EXPECT_NEAR(s.inertia(0, 0), 0.4 * s.volume * 4, 1e-12);
  EXPECT_EQ(s.centroid, Vec3::Zero());

  const MassProperties e = mass_properties(Shape::ellipsoid(3, 2, 1));
  EXPECT_NEAR(e.volume, 8 * M_PI, 1e-12);
  EXPECT_NEAR(e.inertia(0, 0), e.volume * (4 + 1) / 5, 1e-12);
  EXPECT_NEAR(e.inertia(1, 1), e.volume * (9 + 1) / 5, 1e-12);
  EXPECT_NEAR(e.inertia(2, 2), e.volume * (9 + 4) / 5, 1e-12);

  const MassProperties b = mass_properties(Shape::box(1, 2, 3));
  EXPECT_NEAR(b.volume, 6, 1e-12);
  EXPECT_NEAR(b.inertia(0, 0), 6 * (4 + 9) / 12.0, 1e-12);
  EXPECT_NEAR(b.inertia(1, 1), 6 * (1 + 9) / 12.0, 1e-12);
  EXPECT_NEAR(b.inertia(2, 2), 6 * (1 + 4) / 12.0, 1e-12);
}

TEST(MassProperties, BoxMeshMatchesClosedFormAfterRotationAndShift) {
  const Shape box = Shape::box(0.4, 0.2, 0.1);
  const MassProperties exact = mass_properties(box);
  TriangleMesh m = tessellate(box, 200);
  const Mat3 r = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Vec3 shift(10, -3, 2);
  for (Vec3& v : m.vertices) v = r * v + shift;
  const MassProperties mp = mass_properties(mesh_shape(m));
  EXPECT_NEAR(mp.volume, exact.volume, 1e-12);
  EXPECT_LT((mp.centroid - shift).norm(), 1e-12);
  EXPECT_LT((mp.inertia - r * exact.inertia * r.transpose()).norm(),
            1e-12 * exact.inertia.norm() * 10);
}

// the shadow of a closed surface: a box's faces, a thin n-gon plate's outline along its normal
// (not its bounding box), a convex body seen along any axis
TEST(MassProperties, ProjectedAreaIsTheShadowsArea) {
  const TriangleMesh box = tessellate(Shape::box(0.4, 0.2, 0.1), 200);
  EXPECT_NEAR(projected_area(box, 0), 0.2 * 0.1, 1e-14);
  EXPECT_NEAR(projected_area(box, 1), 0.4 * 0.1, 1e-14);
  EXPECT_NEAR(projected_area(box, 2), 0.4 * 0.2, 1e-14);
  const int n = 48;
  const double r = 0.03, t = 7e-5;
  const TriangleMesh disk = test::polygon_prism(n, r, t);
  EXPECT_NO_THROW(mass_properties(mesh_shape(disk)));  // closed and outward
  EXPECT_NEAR(projected_area(disk, 2), 0.5 * n * r * r * std::sin(2 * M_PI / n), 1e-15);
  // edge-on: the rectangle of the polygon's width (2r, a vertex on the x axis) by t
  EXPECT_NEAR(projected_area(disk, 1), 2 * r * t, 1e-15);
}

TEST(MassProperties, Tetrahedron) {
  TriangleMesh t;
  t.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  t.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const MassProperties mp = mass_properties(mesh_shape(t));
  EXPECT_NEAR(mp.volume, 1.0 / 6.0, 1e-15);
  EXPECT_LT((mp.centroid - Vec3::Constant(0.25)).norm(), 1e-15);
  // unit right tetrahedron about its centroid: I_xx = 1/80, I_xy = 1/480 (products of inertia
  // -int x y dV = -1/120 about the corner, +V (1/4)^2 shift)
  EXPECT_NEAR(mp.inertia(0, 0), 1.0 / 80.0, 1e-15);
  EXPECT_NEAR(mp.inertia(0, 1), 1.0 / 480.0, 1e-15);
}

// inscribed icosphere: volume and inertia approach the sphere's, error ~ 1/faces
TEST(MassProperties, TessellatedSphereConverges) {
  const Shape s = Shape::sphere(1);
  const MassProperties exact = mass_properties(s);
  double prev_err = 1;
  for (int faces : {80, 320, 1280, 5120}) {
    const TriangleMesh m = tessellate(s, faces);
    ASSERT_EQ(static_cast<int>(m.faces.size()), faces);
    const MassProperties mp = mass_properties(mesh_shape(m));
    const double err = std::abs(mp.volume / exact.volume - 1);
    const double ierr = std::abs(mp.inertia(0, 0) / exact.inertia(0, 0) - 1);
    EXPECT_LT(mp.centroid.norm(), 1e-12);
    EXPECT_LT(err, prev_err / 3.5) << faces << " faces";
    EXPECT_LT(ierr, 3 * err);
    prev_err = err;
  }
  EXPECT_LT(prev_err, 3e-3);  // 5120 faces: 0.22 %
}

TEST(Tessellate, ClosedOutwardAndNearTarget) {
  for (const Shape& s : {Shape::sphere(1), Shape::ellipsoid(3, 1, 0.2), Shape::box(1, 1, 1),
                         Shape::box(0.05, 0.04, 0.001)}) {
    for (int target : {20, 300, 1500}) {
      const TriangleMesh m = tessellate(s, target);
      const MeshCheck c = check_mesh(m);
      EXPECT_TRUE(c.ok()) << shape_type_name(s.type) << " " << target << ": " << c.message;
      const double ratio = static_cast<double>(m.faces.size()) / target;
      if (target >= 300) {
        EXPECT_TRUE(ratio > 0.5 && ratio < 2.0) << m.faces.size() << " vs " << target;
      }
    }
  }
  // the box mesh is exact, the ellipsoid mesh inscribed
  EXPECT_NEAR(mass_properties(tessellate(Shape::box(1, 2, 3), 500)).volume, 6, 1e-12);
  const double v = mass_properties(tessellate(Shape::ellipsoid(3, 2, 1), 1280)).volume;
  EXPECT_LT(v, 8 * M_PI);
  EXPECT_GT(v, 0.99 * 8 * M_PI);
  EXPECT_THROW(tessellate(Shape::sphere(1), 0), Error);
}

TEST(Tessellate, SubdivisionKeepsMeshGeometry) {
  TriangleMesh t;
  t.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  t.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const Shape s = mesh_shape(t);
  const TriangleMesh m = tessellate(s, 256);  // 4 * 4^3
  EXPECT_EQ(m.faces.size(), 256u);
  EXPECT_TRUE(check_mesh(m).ok());
  const MassProperties a = mass_properties(s), b = mass_properties(m);
  EXPECT_NEAR(a.volume, b.volume, 1e-15);
  EXPECT_LT((a.inertia - b.inertia).norm(), 1e-15);
}

// the meshes are mirror symmetric in each coordinate plane (tested through vertex sets)
TEST(Tessellate, MirrorSymmetric) {
  for (const Shape& s : {Shape::ellipsoid(3, 2, 1), Shape::box(1, 2, 0.5)}) {
    const TriangleMesh m = tessellate(s, 500);
    for (int axis = 0; axis < 3; ++axis) {
      for (const Vec3& v : m.vertices) {
        Vec3 w = v;
        w[axis] = -w[axis];
        double best = INFINITY;
        for (const Vec3& u : m.vertices) best = std::min(best, (u - w).norm());
        ASSERT_LT(best, 1e-12) << shape_type_name(s.type) << " axis " << axis;
      }
    }
  }
}

TriangleMesh tetra() {
  TriangleMesh t;
  t.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  t.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return t;
}

TEST(MeshCheck, DetectsEachDefect) {
  EXPECT_TRUE(check_mesh(tetra()).ok());

  TriangleMesh three = tetra();
  three.faces.pop_back();
  EXPECT_EQ(check_mesh(three).defect, MeshDefect::Empty);  // 3 faces
  TriangleMesh box = tessellate(Shape::box(1, 1, 1), 96);
  box.faces.pop_back();
  const MeshCheck oc = check_mesh(box);
  EXPECT_EQ(oc.defect, MeshDefect::Open);
  EXPECT_NE(oc.message.find("open"), std::string::npos);

  TriangleMesh inv = tetra();
  for (auto& f : inv.faces) std::swap(f[1], f[2]);
  const MeshCheck ic = check_mesh(inv);
  EXPECT_EQ(ic.defect, MeshDefect::Inverted);
  EXPECT_NE(ic.message.find("inverted"), std::string::npos);

  TriangleMesh flip = tetra();
  std::swap(flip.faces[0][1], flip.faces[0][2]);
  EXPECT_EQ(check_mesh(flip).defect, MeshDefect::Inconsistent);

  TriangleMesh deg = tetra();
  deg.vertices[3] = Vec3(0.5, 0.5, 0);  // apex on the hypotenuse: face (1, 2, 3) is collinear
  const MeshCheck dc = check_mesh(deg);
  EXPECT_EQ(dc.defect, MeshDefect::Degenerate);
  EXPECT_NE(dc.message.find("face 3"), std::string::npos) << dc.message;
  TriangleMesh rep = tetra();
  rep.faces[1] = {0, 1, 1};
  EXPECT_EQ(check_mesh(rep).defect, MeshDefect::Degenerate);

  TriangleMesh bad = tetra();
  bad.faces[2][1] = 9;
  EXPECT_EQ(check_mesh(bad).defect, MeshDefect::BadIndex);
  TriangleMesh nan = tetra();
  nan.vertices[2].x() = NAN;
  EXPECT_EQ(check_mesh(nan).defect, MeshDefect::NonFinite);

  // two tetrahedra glued at one vertex: every edge fine, vertex 0 has two fans
  TriangleMesh bow = tetra();
  for (const Vec3& v : {Vec3(-1, 0, 0), Vec3(0, -1, 0), Vec3(0, 0, -1)}) bow.vertices.push_back(v);
  for (const auto& f : tetra().faces) {
    std::array<int, 3> g;
    for (int k = 0; k < 3; ++k) g[k] = f[k] == 0 ? 0 : f[k] + 3;
    bow.faces.push_back(g);  // mirrored copy: reflection flips orientation, so swap two
    std::swap(bow.faces.back()[1], bow.faces.back()[2]);
  }
  const MeshCheck bc = check_mesh(bow);
  EXPECT_EQ(bc.defect, MeshDefect::NonManifold) << bc.message;
  EXPECT_NE(bc.message.find("vertex 0"), std::string::npos) << bc.message;

  // two closed tetrahedra overlapping: every edge and vertex fine, positive volume, but the
  // surfaces cross (a surface whose inside is ambiguous for the volume and the boundary elements)
  TriangleMesh two = tetra();
  for (const Vec3& v : tetra().vertices) two.vertices.push_back(v + Vec3(0.2, 0.2, 0.2));
  for (const auto& f : tetra().faces) two.faces.push_back({f[0] + 4, f[1] + 4, f[2] + 4});
  const MeshCheck tc = check_mesh(two);
  EXPECT_EQ(tc.defect, MeshDefect::SelfIntersecting) << tc.message;
  EXPECT_NE(tc.message.find("intersects itself"), std::string::npos) << tc.message;
  // the same two apart are a valid body of two parts
  TriangleMesh apart = two;
  for (size_t i = 4; i < apart.vertices.size(); ++i) apart.vertices[i] += Vec3(3, 0, 0);
  EXPECT_TRUE(check_mesh(apart).ok()) << check_mesh(apart).message;
  // one surface: a unit cube (corner index 4 ix + 2 iy + iz) with corner (1, 1, 1) pushed
  // through its bottom face
  TriangleMesh cube;
  for (int ix = 0; ix < 2; ++ix)
    for (int iy = 0; iy < 2; ++iy)
      for (int iz = 0; iz < 2; ++iz) cube.vertices.emplace_back(ix, iy, iz);
  for (const std::array<int, 4>& q : {std::array<int, 4>{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1},
                                      {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}}) {
    cube.faces.push_back({q[0], q[1], q[2]});
    cube.faces.push_back({q[0], q[2], q[3]});
  }
  ASSERT_TRUE(check_mesh(cube).ok()) << check_mesh(cube).message;
  cube.vertices[7] = Vec3(0.4, 0.7, -0.5);
  const MeshCheck cc = check_mesh(cube);
  EXPECT_EQ(cc.defect, MeshDefect::SelfIntersecting) << cc.message;
  // meshes that only come close stay valid: a thin curled leaf, tessellated shapes
  EXPECT_TRUE(check_mesh(test::polygon_prism(64, 0.03, 1e-5)).ok());
  EXPECT_TRUE(check_mesh(tessellate(Shape::ellipsoid(0.03, 0.02, 1e-4), 1500)).ok());

  // from_mesh refuses, naming the source
  try {
    Shape::from_mesh(std::make_shared<const TriangleMesh>(inv), "leaf.obj");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::BadInput);
    EXPECT_NE(std::string(e.what()).find("leaf.obj"), std::string::npos);
  }
}

TEST(Shape, FromMeshBoundingBox) {
  TriangleMesh m = tessellate(Shape::box(2, 4, 6), 100);
  for (Vec3& v : m.vertices) v += Vec3(5, 5, 5);
  const Shape s = mesh_shape(m);
  EXPECT_LT((s.half_extents - Vec3(1, 2, 3)).norm(), 1e-12);
  EXPECT_EQ(s.source, "test");
}

}  // namespace
}  // namespace lrigid
