// Loading a scene's flow and checking it fits in memory: shared by `lrigid run` and `lrigid view`.
#pragma once
#include <string>

#include "fluid/field.h"
#include "model/scene.h"

namespace lrigid::app {

// The scene's fluid field: uniform, or its grid file. A .pvd series is streamed (only the frames
// bracketing the current time in memory) with `stream` "on", or with "auto" when all its frames
// would take more than half the memory. Warns (unless quiet) when the grid's viscosity differs
// from the scene's.
FluidField load_field(const Scene& scene, const std::string& stream, bool quiet);

// Throws lrigid::Error(ExitCode::Resource) naming the scene when its bodies would not fit in
// 80 % of the physical memory.
void check_memory(const Scene& scene);

}  // namespace lrigid::app
