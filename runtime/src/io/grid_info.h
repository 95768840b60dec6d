// What a grid file holds, for authoring a scene against it (lrigid info): its box, spacing and
// times, the flow over the whole grid, and the solids (buildings, walls, a tank's inserts: the
// points where the grid has no flow, valid = 0) one by one, each with its bounding box and the
// flow around it. A solid is a connected set of such points (neighbours along the axes).
#pragma once
#include <string>

#include <nlohmann/json.hpp>

namespace lrigid {

// {file, points [nx, ny, nz], origin, spacing, upper (m), times (s), kinematic_viscosity,
//  has_wall_distance, fluid_points, flow {U_median, U_max, k_median} over the fluid points of
//  the first frame, solids [{points, lo, hi (m: the box of its points widened by half a
//  spacing, so its surface lies within half a spacing of it), around {points, U_median,
//  k_median} over the fluid points 3 steps out from it, past the no-slip layer}], largest
//  first, at most max_solids, and solids_total}. Throws lrigid::Error (BadInput) as read_grid does.
nlohmann::json grid_info(const std::string& path, size_t max_solids = 20);

}  // namespace lrigid
