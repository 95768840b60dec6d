#include "wall_distance.h"

#include <omp.h>
#include <vtkCellArray.h>
#include <vtkGenericCell.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStaticCellLocator.h>

#include <cmath>

namespace foam2grid {

namespace {

// The wall faces of every part as one triangulated surface (the points of each part copied
// as they are; a point shared by two processors appears twice, which changes no distance).
vtkSmartPointer<vtkPolyData> wall_surface(const std::vector<MeshPart>& parts) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> tris;
  for (const MeshPart& m : parts) {
    const vtkIdType base = points->GetNumberOfPoints();
    bool any = false;
    for (const Patch& patch : m.patches) {
      if (patch.type != "wall") continue;
      for (Label f = patch.start; f < patch.start + patch.size; ++f) {
        const Label b = m.face_offsets[f], e = m.face_offsets[f + 1];
        // fan from the first point: exact for planar faces
        for (Label j = b + 1; j + 1 < e; ++j) {
          const vtkIdType t[3] = {base + m.face_points[b], base + m.face_points[j],
                                  base + m.face_points[j + 1]};
          tris->InsertNextCell(3, t);
          any = true;
        }
      }
    }
    if (!any) continue;
    for (Label p = 0; p < m.n_points(); ++p)
      points->InsertNextPoint(m.points[3 * p], m.points[3 * p + 1], m.points[3 * p + 2]);
  }
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(points);
  poly->SetPolys(tris);
  return poly;
}

}  // namespace

std::vector<float> unsigned_wall_distance(const std::vector<MeshPart>& parts,
                                          const GridSpec& grid, std::size_t* n_faces) {
  std::size_t faces = 0;
  for (const MeshPart& m : parts)
    for (const Patch& patch : m.patches)
      if (patch.type == "wall") faces += static_cast<std::size_t>(patch.size);
  if (n_faces) *n_faces = faces;
  if (faces == 0) return {};
  vtkSmartPointer<vtkPolyData> surface = wall_surface(parts);
  // everything a query reads is built here, before the threads start: the cell links, the
  // bounds, and one locator per thread (a locator's queries are not safe across threads)
  surface->BuildCells();
  double bounds[6];
  surface->GetBounds(bounds);
  const int nthreads = omp_get_max_threads();
  std::vector<vtkSmartPointer<vtkStaticCellLocator>> locators(static_cast<std::size_t>(nthreads));
  for (auto& loc : locators) {
    loc = vtkSmartPointer<vtkStaticCellLocator>::New();
    loc->SetDataSet(surface);
    loc->BuildLocator();
  }
  const std::size_t np = grid.n_points();
  std::vector<float> d(np);
  const long nx = grid.dims[0], ny = grid.dims[1], nz = grid.dims[2];
  // along a row of the grid (x fastest), the nearest wall of a point lies within the previous
  // point's distance plus the spacing (triangle inequality): a search within that radius finds
  // it at a fraction of the cost of an unbounded search; each row starts unbounded
  const double step = grid.spacing[0];
#pragma omp parallel num_threads(nthreads)
  {
    vtkStaticCellLocator* loc = locators[static_cast<std::size_t>(omp_get_thread_num())];
    vtkNew<vtkGenericCell> cell;
#pragma omp for schedule(dynamic, 16)
    for (long row = 0; row < ny * nz; ++row) {
      const long j = row % ny, k = row / ny;
      double prev = -1;
      for (long i = 0; i < nx; ++i) {
        double x[3] = {grid.origin[0] + static_cast<double>(i) * grid.spacing[0],
                       grid.origin[1] + static_cast<double>(j) * grid.spacing[1],
                       grid.origin[2] + static_cast<double>(k) * grid.spacing[2]};
        double closest[3], dist2 = 0;
        vtkIdType cell_id = -1;
        int sub_id = 0, inside = 0;
        bool found = false;
        if (prev >= 0) {
          const double radius = (prev + step) * (1 + 1e-9) + 1e-12;
          found = loc->FindClosestPointWithinRadius(x, radius, closest, cell, cell_id, sub_id,
                                                    dist2, inside) != 0;
        }
        if (!found) loc->FindClosestPoint(x, closest, cell, cell_id, sub_id, dist2);
        prev = std::sqrt(dist2);
        d[static_cast<std::size_t>(row * nx + i)] = static_cast<float>(prev);
      }
    }
  }
  return d;
}

std::vector<float> signed_wall_distance(const std::vector<float>& unsigned_d,
                                        const std::vector<std::uint8_t>& valid) {
  std::vector<float> s(unsigned_d.size());
  for (std::size_t p = 0; p < s.size(); ++p) s[p] = valid[p] ? unsigned_d[p] : -unsigned_d[p];
  return s;
}

}  // namespace foam2grid
