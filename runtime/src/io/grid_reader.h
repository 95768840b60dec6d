// Reads foam2grid's grid files (docs/grid-format.md): one .vti, or a .pvd series of .vti files.
// Checks everything the runtime relies on and names the file, array and point that is wrong:
// at least 2 points per axis, arrays U (3 components), k and epsilon present with one value per
// point, values finite, k >= 0 and epsilon >= 0 at valid points; the optional wall_distance
// (1 component, finite). Throws lrigid::Error (BadInput).
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

// A grid opened for reading frame by frame (streamed fields): the .pvd's entries and the first
// frame's geometry; load(i) reads entry i, with the checks above plus the same geometry as the
// first frame. Throws lrigid::Error (BadInput) naming the series, entry and file.
struct GridSeries {
  std::string path;                   // the .pvd (or .vti)
  bool is_series = false;             // a .pvd
  std::vector<double> times;          // s, increasing
  std::vector<std::string> files;     // one .vti per time
  GridGeometry geometry;
  double kinematic_viscosity = 0;     // from the first frame's field data (0 if absent), m^2/s
  // the first frame has the point array wall_distance; every frame must agree
  bool has_wall_distance = false;
  RawGridFrame load(size_t i) const;
};

// Reads the entries and the first frame (returned in *first when given).
GridSeries open_grid_series(const std::string& path, RawGridFrame* first = nullptr);

}  // namespace lrigid
