// A single-sided surface made into its thin closed body (runtime/src/body/solidify.cpp):
// closed and valid, with the mass properties of the solid it stands for.
#include "body/solidify.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "body/mass_properties.h"
#include "body/mesh_check.h"
#include "io/mesh_io.h"
#include "util/error.h"

namespace lrigid {
namespace {

// a flat rectangle lx x ly in the plane z = 0, two triangles wound counter-clockwise from +z
TriangleMesh rectangle(double lx, double ly) {
  TriangleMesh m;
  m.vertices = {Vec3(-lx / 2, -ly / 2, 0), Vec3(lx / 2, -ly / 2, 0), Vec3(lx / 2, ly / 2, 0),
                Vec3(-lx / 2, ly / 2, 0)};
  m.faces = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

std::string message_of(const TriangleMesh& m, double t) {
  try {
    solidify_surface(m, t, "leaf.obj");
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::BadInput);
    return e.what();
  }
  return "";
}

TEST(Solidify, AFlatRectangleBecomesTheBoxOfItsThickness) {
  const TriangleMesh r = rectangle(0.05, 0.03);
  EXPECT_EQ(boundary_edge_count(r), 4);
  const TriangleMesh solid = solidify_surface(r, 3e-4, "card.obj");
  EXPECT_EQ(solid.vertices.size(), 8u);
  EXPECT_EQ(solid.faces.size(), 12u);  // two per side, two per wall
  EXPECT_EQ(boundary_edge_count(solid), 0);
  const MeshCheck c = check_mesh(solid);
  EXPECT_TRUE(c.ok()) << c.message;
  const MassProperties got =
      mass_properties(Shape::from_mesh(std::make_shared<const TriangleMesh>(solid), "card.obj"));
  const MassProperties box = mass_properties(Shape::box(0.05, 0.03, 3e-4));
  EXPECT_NEAR(got.volume, box.volume, 1e-12 * box.volume);
  EXPECT_LT(got.centroid.norm(), 1e-12);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(got.inertia(i, j), box.inertia(i, j), 1e-9 * box.inertia(0, 0))
          << i << "," << j;
}

TEST(Solidify, AnArtistsCurledLeafIsTheClosedLeafOfTheSameThickness) {
  // leaf_surface.obj: the mid-surface of bent_leaf.obj in quads with UVs, as Blender writes it;
  // 0.4 mm thick it is bent_leaf.obj (whose layers are offset along the exact normal)
  const std::string dir = std::string(LRIGID_SOURCE_DIR) + "/tests/data/meshes/";
  const TriangleMesh surface = read_mesh(dir + "leaf_surface.obj");
  EXPECT_EQ(boundary_edge_count(surface), 2 * (24 + 16));
  const TriangleMesh solid = solidify_surface(surface, 4e-4, "leaf_surface.obj");
  const MeshCheck c = check_mesh(solid);
  ASSERT_TRUE(c.ok()) << c.message;
  const MassProperties got =
      mass_properties(Shape::from_mesh(std::make_shared<const TriangleMesh>(solid), "s"));
  const TriangleMesh closed = read_mesh(dir + "bent_leaf.obj");
  const MassProperties want =
      mass_properties(Shape::from_mesh(std::make_shared<const TriangleMesh>(closed), "c"));
  std::printf("volume %.6g against %.6g m^3, centroid %.3g m apart\n", got.volume, want.volume,
              (got.centroid - want.centroid).norm());
  EXPECT_NEAR(got.volume, want.volume, 1e-4 * want.volume);
  EXPECT_LT((got.centroid - want.centroid).norm(), 1e-3 * 0.06);
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(got.inertia(i, i), want.inertia(i, i), 2e-3 * want.inertia(i, i))
        << i;
}

TEST(Solidify, RefusesWhatIsNotOneOpenSheet) {
  TriangleMesh r = rectangle(0.05, 0.03);
  EXPECT_NE(message_of(r, 0).find("thickness must be > 0 m"), std::string::npos);
  EXPECT_NE(message_of(r, NAN).find("thickness must be > 0 m"), std::string::npos);

  TriangleMesh flipped = r;
  flipped.faces[1] = {0, 3, 2};  // wound the other way round from its neighbour
  const std::string f = message_of(flipped, 1e-3);
  EXPECT_NE(f.find("leaf.obj: surface is not one consistently oriented sheet: the edge from "
                   "vertex 3 (0.025 0.015 0) to 1 (-0.025 -0.015 0) is in 2 faces the same way round"),
            std::string::npos)
      << f;

  // a closed surface is a solid already
  TriangleMesh tetra;
  tetra.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  tetra.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  EXPECT_EQ(boundary_edge_count(tetra), 0);
  EXPECT_NE(message_of(tetra, 1e-3).find("surface is closed: \"thickness\" is for an open"),
            std::string::npos);

  // two sheets sharing one vertex (a bow tie)
  TriangleMesh bow;
  bow.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(-1, 0, 0), Vec3(-1, -1, 0)};
  bow.faces = {{0, 1, 2}, {0, 3, 4}};
  EXPECT_NE(message_of(bow, 1e-3).find("has two sheets meeting at vertex 1 (0 0 0)"),
            std::string::npos)
      << message_of(bow, 1e-3);

  // a sheet folded flat onto itself about an edge: the normals at the fold cancel
  TriangleMesh fold;
  fold.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 1, 0)};
  fold.faces = {{0, 1, 2}, {1, 0, 3}};
  EXPECT_NE(message_of(fold, 1e-3).find("folds back on itself at vertex"), std::string::npos)
      << message_of(fold, 1e-3);
  // a vertex no face uses is left alone
  TriangleMesh spare = r;
  spare.vertices.push_back(Vec3(5, 5, 5));
  EXPECT_EQ(message_of(spare, 1e-3), "");
}

}  // namespace
}  // namespace lrigid
