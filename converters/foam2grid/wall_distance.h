// The distance from each grid point to the nearest wall of the mesh (faces of the patches of
// type `wall`), written as the point array `wall_distance` (docs/grid-format.md). The runtime
// meets solids where it crosses 0 (docs/contacts.md).
#pragma once
#include <cstdint>
#include <vector>

#include "foam_case.h"
#include "interpolate.h"

namespace foam2grid {

/// The unsigned distance (m) from every grid point (x fastest) to the nearest face of a wall
/// patch of any part: exact to the faces triangulated as fans from their first point (exact for
/// planar faces), found through a bounding-volume hierarchy of the triangles, OpenMP over rows
/// of the grid. Empty when the mesh has no wall face. *n_faces (when given) receives the number
/// of wall faces used.
std::vector<float> unsigned_wall_distance(const std::vector<MeshPart>& parts,
                                          const GridSpec& grid, std::size_t* n_faces = nullptr);

/// The signed distance: +d at valid points (in the fluid), -d where valid is 0 (inside a solid,
/// or outside the mesh). Empty when `unsigned_d` is.
std::vector<float> signed_wall_distance(const std::vector<float>& unsigned_d,
                                        const std::vector<std::uint8_t>& valid);

}  // namespace foam2grid
