// Disk cache of Kirchhoff tensors computed by the boundary element method, so a scene with a
// mesh body starts at once the second time. One small JSON file per (geometry, panels):
//   <cache dir>/added_mass-<16 hex digits>.json
// The cache dir is $LRIGID_CACHE_DIR, else $XDG_CACHE_HOME/lrigid, else ~/.cache/lrigid.
// The key hashes a format version, the shape type, the geometry (box sizes, or the exact bits of
// every mesh vertex and face) and the panel target; the file repeats the key text so a hash
// collision is detected. Tensors are stored per unit fluid density and scaled on load.
// Unreadable or corrupt files are ignored and rewritten (atomically).
#pragma once
#include <string>

#include "body/added_mass.h"

namespace lrigid {

// Same result as added_mass(shape, fluid_density, panels). Analytic shapes (sphere, ellipsoid)
// are computed directly (instant); BEM results are read from or written to the cache. A cache
// that cannot be written only costs time: a warning goes to stderr.
AddedMass cached_added_mass(const Shape& shape, double fluid_density, int panels = 0);

// The cache directory that cached_added_mass uses (from the environment, see above).
std::string added_mass_cache_dir();

// The key text and the file path for a shape and panel target (0 = default), for tests/tools.
std::string added_mass_cache_key(const Shape& shape, int panels);
std::string added_mass_cache_file(const Shape& shape, int panels);

}  // namespace lrigid
