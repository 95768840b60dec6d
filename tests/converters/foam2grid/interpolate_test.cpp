// OpenFOAM's geometry and cellPoint interpolation (converters/foam2grid/foam_case.cpp and
// interpolate.cpp) on hand-made meshes with known answers.
#include "interpolate.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace foam2grid;

namespace {

// two unit cubes side by side along x: cells 0 [0,1]^3 and 1 [1,2]x[0,1]^2, one internal face,
// patch "walls" (10 faces). Faces point out of their owner.
MeshPart two_cubes(bool stretch) {
  MeshPart m;
  const double x2 = stretch ? 3.0 : 2.0;  // second cell 2 m long when stretched
  const double xs[3] = {0, 1, x2};
  for (int k = 0; k < 2; ++k) {
    for (int j = 0; j < 2; ++j) {
      for (int i = 0; i < 3; ++i) {
        m.points.insert(m.points.end(), {xs[i], double(j), double(k)});
      }
    }
  }
  auto id = [](int i, int j, int k) { return Label(i + 3 * (j + 2 * k)); };
  std::vector<std::vector<Label>> faces;
  // internal face x = 1, normal +x (owner 0 -> neighbour 1)
  faces.push_back({id(1, 0, 0), id(1, 1, 0), id(1, 1, 1), id(1, 0, 1)});
  m.neighbour = {1};
  std::vector<Label> owner = {0};
  for (int c = 0; c < 2; ++c) {
    if (c == 0) faces.push_back({id(0, 0, 0), id(0, 0, 1), id(0, 1, 1), id(0, 1, 0)});  // -x
    if (c == 1) faces.push_back({id(2, 0, 0), id(2, 1, 0), id(2, 1, 1), id(2, 0, 1)});  // +x
    faces.push_back({id(c, 0, 0), id(c + 1, 0, 0), id(c + 1, 0, 1), id(c, 0, 1)});      // -y
    faces.push_back({id(c, 1, 0), id(c, 1, 1), id(c + 1, 1, 1), id(c + 1, 1, 0)});      // +y
    faces.push_back({id(c, 0, 0), id(c, 1, 0), id(c + 1, 1, 0), id(c + 1, 0, 0)});      // -z
    faces.push_back({id(c, 0, 1), id(c + 1, 0, 1), id(c + 1, 1, 1), id(c, 1, 1)});      // +z
    for (int f = 0; f < 5; ++f) owner.push_back(c);
  }
  m.owner = owner;
  m.face_offsets = {0};
  for (auto& f : faces) {
    m.face_points.insert(m.face_points.end(), f.begin(), f.end());
    m.face_offsets.push_back(Label(m.face_points.size()));
  }
  m.n_cells = 2;
  Patch p;
  p.name = "walls";
  p.type = "wall";
  p.start = 1;
  p.size = 10;
  m.patches.push_back(p);
  compute_geometry(&m);
  return m;
}

}  // namespace

TEST(Geometry, CellCentresAndVolumesOfBoxes) {
  const MeshPart m = two_cubes(true);
  EXPECT_NEAR(m.cell_centres[0], 0.5, 1e-14);
  EXPECT_NEAR(m.cell_centres[3], 2.0, 1e-14);
  EXPECT_NEAR(m.cell_centres[4], 0.5, 1e-14);
  EXPECT_NEAR(m.cell_volumes[0], 1.0, 1e-14);
  EXPECT_NEAR(m.cell_volumes[1], 2.0, 1e-14);
  // outward area vector of the +x wall face of cell 1: (1, 0, 0) m^2
  const Label f = 6 - m.n_internal_faces();
  EXPECT_NEAR(m.boundary_face_areas[3 * f], 1.0, 1e-14);
  EXPECT_NEAR(m.boundary_face_centres[3 * f], 3.0, 1e-14);
}

TEST(CellPoint, ReproducesPointValuesCellValuesAndTheWallRule) {
  const MeshPart m = two_cubes(true);
  std::vector<FieldSpec> specs = {{"k", 1, 0}};
  std::vector<PartFields> fields(1);
  fields[0].ncomp = 1;
  fields[0].cells = {1.0, 4.0};
  // wall values: 10 on the faces of cell 0, 20 on those of cell 1
  fields[0].boundary = {10, 10, 10, 10, 10, 20, 20, 20, 20, 20};
  const std::vector<double> pv = point_values({m}, fields, specs);
  // every point is a wall point: inverse-distance mean of the wall faces around it. Point
  // (0,0,0) touches three faces of cell 0 only -> 10; point (1,0,0) touches two faces of
  // each cell at distances sqrt(0.5) (cell 0) and sqrt(1.25) (cell 1, 2 m long).
  EXPECT_NEAR(pv[0], 10.0, 1e-14);
  const double w0 = 1 / std::sqrt(0.5), w1 = 1 / std::sqrt(1.25);
  EXPECT_NEAR(pv[1], (2 * w0 * 10 + 2 * w1 * 20) / (2 * w0 + 2 * w1), 1e-12);

  // grid with points at mesh points, at the cell centres and in between
  GridSpec g;
  g.origin = {0, 0, 0};
  g.spacing = {0.5, 0.5, 0.5};
  g.dims = {7, 3, 3};  // x up to 3 m
  GridFields out;
  resample({m}, fields, pv, specs, g, Scheme::kCellPoint, &out);
  auto at = [&](int i, int j, int k) { return std::size_t(i + 7 * (j + 3 * k)); };
  for (std::size_t i = 0; i < out.valid.size(); ++i) EXPECT_EQ(out.valid[i], 1) << i;
  EXPECT_NEAR(out.arrays[0][at(0, 0, 0)], pv[0], 1e-6);                    // mesh point
  EXPECT_NEAR(out.arrays[0][at(2, 2, 2)], pv[1 + 3 * (1 + 2 * 1)], 1e-6);  // (1,1,1)
  EXPECT_NEAR(out.arrays[0][at(1, 1, 1)], 1.0, 1e-6);                      // centre of cell 0
  EXPECT_NEAR(out.arrays[0][at(4, 1, 1)], 4.0, 1e-6);                      // centre of cell 1
  // cell scheme: the cell value everywhere in the cell
  GridFields cell;
  resample({m}, fields, pv, specs, g, Scheme::kCell, &cell);
  EXPECT_FLOAT_EQ(cell.arrays[0][at(1, 0, 2)], 1.0f);
  EXPECT_FLOAT_EQ(cell.arrays[0][at(5, 2, 0)], 4.0f);

  // a grid reaching beyond the mesh: the outside points are invalid and exactly 0
  g.origin = {-0.75, 0, 0};
  resample({m}, fields, pv, specs, g, Scheme::kCellPoint, &out);
  EXPECT_EQ(out.valid[at(0, 1, 1)], 0);
  EXPECT_EQ(out.arrays[0][at(0, 1, 1)], 0.0f);
  EXPECT_EQ(out.valid[at(2, 1, 1)], 1);
}

TEST(CellPoint, IsLinearAlongATetEdge) {
  // the value at a point on the segment from the cell centre to a mesh point is the linear
  // blend of the cell value and that point value (barycentric weights of one tet edge)
  const MeshPart m = two_cubes(false);
  std::vector<FieldSpec> specs = {{"k", 1, 0}};
  std::vector<PartFields> fields(1);
  fields[0].ncomp = 1;
  fields[0].cells = {2.0, 2.0};
  fields[0].boundary.assign(10, 0.0);
  fields[0].boundary[0] = 8.0;  // the -x wall face of cell 0
  const std::vector<double> pv = point_values({m}, fields, specs);
  GridSpec g;
  g.origin = {0.25, 0.25, 0.25};  // a quarter of the way from (0,0,0) to the centre
  g.spacing = {1, 1, 1};
  g.dims = {1, 1, 1};
  GridFields out;
  resample({m}, fields, pv, specs, g, Scheme::kCellPoint, &out);
  ASSERT_EQ(out.valid[0], 1);
  EXPECT_NEAR(out.arrays[0][0], 0.5 * pv[0] + 0.5 * 2.0, 1e-6);
}
