// The surface of a grid's solids as the grid resolves it: each pair of a fluid point (valid) and
// a solid neighbour (not valid) one spacing away along an axis, the wall lying half way between
// them (field.h). Bodies spawned on the solids' surface (scene key bodies[i].spawn) start on the
// face between such a pair, moved an offset into the fluid.
#pragma once
#include <cstdint>
#include <vector>

#include "fluid/field.h"

namespace lrigid {

// The indices (i, j, k) of grid point p (x fastest).
void grid_point_indices(const GridGeometry& g, size_t p, int c[3]);

struct SurfaceSite {
  uint32_t point = 0;  // the fluid grid point (x-fastest index)
  uint8_t axis = 0;    // the axis of its solid neighbour
  int8_t side = 1;     // +1: the neighbour is at a higher index along it, -1: lower
};

// The sites of the first frame whose fluid point lies in [lo, hi] (m, world); empty on a uniform
// field.
std::vector<SurfaceSite> solid_surface_sites(const FluidField& field, const Vec3& lo,
                                             const Vec3& hi);

// Where a body drawn at `site` starts: on the face half way between the fluid point and the solid
// one, at (a, b) in [0, 1)^2 across it (each within half a spacing of the line joining them),
// then `offset` (m) along the axis into the fluid.
Vec3 surface_site_position(const GridGeometry& g, const SurfaceSite& site, double offset,
                           double a, double b);

}  // namespace lrigid
