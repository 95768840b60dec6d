// Reads foam2grid's grid files (docs/grid-format.md): one .vti, or a .pvd series of .vti files.
// Checks everything the runtime relies on and names the file, array and point that is wrong:
// at least 2 points per axis, arrays U (3 components), k and epsilon present with one value per
// point, values finite, k >= 0 and epsilon >= 0 at valid points. Throws lrigid::Error (BadInput).
#pragma once
#include <string>
#include <vector>

#include "fluid/field.h"

namespace lrigid {

struct GridFile {
  GridGeometry geometry;
  std::vector<RawGridFrame> frames;   // sorted by time
  double kinematic_viscosity = 0;     // from the file's field data (0 if absent), m^2/s
};

GridFile read_grid(const std::string& path);

}  // namespace lrigid
