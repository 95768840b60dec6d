// The solids' surface as a grid resolves it (fluid/solid_surface.h): each site pairs a fluid
// point with a solid neighbour along an axis; a box keeps the sites whose fluid point lies in it;
// a body placed at a site lies on the face between the two points, its offset into the fluid.
#include "fluid/solid_surface.h"

#include <gtest/gtest.h>

#include "support/fixture.h"

namespace lrigid {
namespace {

// a 12 x 10 x 8 grid of 0.5 m with a block of solid points (a building) at x in [2, 3.5],
// y in [1.5, 3], z in [0, 1.5]
FluidField block_grid() {
  const GridGeometry g = test::grid_geometry(12, 10, 8, Vec3::Zero(), Vec3::Constant(0.5));
  const RawGridFrame f = test::grid_frame(g, [](const Vec3& x, Vec3* U, double* k, double* e) {
    *U = Vec3(1, 0, 0);
    *k = 0.1;
    *e = 0.05;
    return !(x.x() >= 2 && x.x() <= 3.5 && x.y() >= 1.5 && x.y() <= 3 && x.z() <= 1.5);
  });
  return FluidField::grid(g, {f}, 1.5e-5, Drift::Stationary, TimeMode::Clamp);
}

bool solid_at(const Vec3& x) {
  return x.x() >= 2 - 1e-9 && x.x() <= 3.5 + 1e-9 && x.y() >= 1.5 - 1e-9 && x.y() <= 3 + 1e-9 &&
         x.z() <= 1.5 + 1e-9;
}

TEST(SolidSurface, EachSitePairsAFluidPointWithASolidNeighbour) {
  const FluidField field = block_grid();
  const GridGeometry& g = field.geometry();
  const double inf = 1e30;
  const auto sites = solid_surface_sites(field, Vec3::Constant(-inf), Vec3::Constant(inf));
  // the block's faces: x: 2 faces of 4 x 4 points, y: 2 of 4 x 4, top: 4 x 4 (its bottom is the
  // grid's): 80 pairs
  EXPECT_EQ(sites.size(), 80u);
  for (const SurfaceSite& s : sites) {
    int c[3];
    grid_point_indices(g, s.point, c);
    Vec3 fluid, solid;
    for (int a = 0; a < 3; ++a) fluid[a] = c[a] * g.spacing[a];
    solid = fluid;
    solid[s.axis] += s.side * g.spacing[s.axis];
    EXPECT_FALSE(solid_at(fluid)) << fluid.transpose();
    EXPECT_TRUE(solid_at(solid)) << solid.transpose();
    // a body at the site, 0.2 m into the fluid, across the face: its distance to the solid point
    // along the axis is half a spacing + 0.2 m, within half a spacing across
    for (const double a : {0.0, 0.5, 0.999}) {
      const Vec3 x = surface_site_position(g, s, 0.2, a, 1 - a);
      const Vec3 d = (x - solid).cwiseAbs();
      EXPECT_NEAR(d[s.axis], 0.25 + 0.2, 1e-12);
      EXPECT_LE(d[(s.axis + 1) % 3], 0.25 + 1e-12);
      EXPECT_LE(d[(s.axis + 2) % 3], 0.25 + 1e-12);
    }
  }
  // a box keeps the sites whose fluid point lies in it: the block's top face only
  const auto top = solid_surface_sites(field, Vec3(0, 0, 1.9), Vec3(6, 5, 2.1));
  EXPECT_EQ(top.size(), 16u);
  for (const SurfaceSite& s : top) EXPECT_EQ(s.axis, 2);
  EXPECT_TRUE(solid_surface_sites(field, Vec3(4.5, 4, 0), Vec3(5.5, 4.5, 3)).empty())
      << "a box away from the block";
}

}  // namespace
}  // namespace lrigid
