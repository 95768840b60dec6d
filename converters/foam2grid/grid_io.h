// Grid files (docs/grid-format.md): VTK XML ImageData (.vti, appended raw binary, zlib) with
// the point arrays U, k, epsilon, nut, valid and the field data kinematic_viscosity, case_name,
// time, converter_version; a .pvd collection for a time series. Written to a temporary name
// in the target directory, then renamed.
#pragma once
#include <ostream>
#include <string>
#include <vector>

#include "interpolate.h"

namespace foam2grid {

/// Metadata stored as field data in each .vti.
struct GridMeta {
  double kinematic_viscosity = 0;  ///< m^2/s
  std::string case_name;
  double time = 0;  ///< OpenFOAM time, s
  std::string converter_version;
};

/// Writes one .vti to path (via a temporary file); throws Error(kOutput) on failure.
void write_vti(const std::string& path, const GridSpec& grid, const std::vector<FieldSpec>& specs,
               GridFields* data, const GridMeta& meta);

/// Writes the .pvd text (DataSet entries with timestep and relative file) via a temporary file.
void write_pvd(const std::string& path, const std::vector<double>& times,
               const std::vector<std::string>& files);

/// Prints a summary of a .vti or .pvd (dimensions, spacing, bounds, per-field min/max/mean over
/// valid points, invalid fraction, field data, times). Throws Error(kBadInput) when unreadable.
void print_info(const std::string& path, std::ostream& os);

/// A temporary name beside path (same directory), unique to this process.
std::string temp_name(const std::string& path);

}  // namespace foam2grid
