// OpenFOAM's cellPoint interpolation, reproduced: point values as volPointInterpolation makes
// them, then inside each cell linear interpolation over the tetrahedra (cell centre, face
// triangle) of OpenFOAM's decomposition. Used to sample the fields at the points of a grid.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "foam_case.h"

namespace foam2grid {

/// Number of distinct mesh points over all parts (global labels of a decomposed case).
Label count_global_points(const std::vector<MeshPart>& parts);

/// Point values of the stacked fields, (nGlobalPoints x ncomp), as volPointInterpolation:
/// inverse-distance weights from the centres of the cells around a point; points on patches
/// that are neither empty nor coupled take inverse-distance weights from the centres of their
/// patch faces and the patch face values; vectors are then constrained on symmetry patches.
std::vector<double> point_values(const std::vector<MeshPart>& parts,
                                 const std::vector<PartFields>& fields,
                                 const std::vector<FieldSpec>& specs);

/// A regular grid: point (i, j, k) sits at origin + (i dx, j dy, k dz).
struct GridSpec {
  std::array<double, 3> origin{};   ///< lower corner, m
  std::array<double, 3> spacing{};  ///< dx, dy, dz, m
  std::array<long, 3> dims{};       ///< points along x, y, z
  std::size_t n_points() const {
    return static_cast<std::size_t>(dims[0]) * static_cast<std::size_t>(dims[1]) *
           static_cast<std::size_t>(dims[2]);
  }
};

/// How values are taken inside a cell.
enum class Scheme {
  kCellPoint,  ///< OpenFOAM's cellPoint: linear over the cell's tetrahedra
  kCell,       ///< OpenFOAM's cell: the cell value (piecewise constant)
};

/// Sampled values: one float array per field (n_points x ncomp, x fastest) and the validity
/// mask (1 inside a fluid cell, 0 elsewhere; fields are exactly 0 where valid is 0).
struct GridFields {
  std::vector<std::vector<float>> arrays;
  std::vector<std::uint8_t> valid;
  /// signed distance to the nearest wall, m (wall_distance.h); not written when empty
  std::vector<float> wall_distance;
};

/// Progress of resample(): fraction of the cells done (0..1) and grid points resampled so far.
/// Called from one thread only, every few thousand cells.
using ResampleProgress = std::function<void(double fraction, std::size_t points)>;

/// Samples the fields at every grid point (OpenMP over cells).
void resample(const std::vector<MeshPart>& parts, const std::vector<PartFields>& fields,
              const std::vector<double>& point_vals, const std::vector<FieldSpec>& specs,
              const GridSpec& grid, Scheme scheme, GridFields* out,
              const ResampleProgress& on_progress = {});

/// Bounding box of all mesh points: xmin, xmax, ymin, ymax, zmin, zmax (m).
std::array<double, 6> mesh_bounds(const std::vector<MeshPart>& parts);

}  // namespace foam2grid
