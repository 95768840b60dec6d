// The fluid field of a scene as `lrigid run` loads it (shared with the Python module): the
// uniform field, or the grid (.vti or .pvd series) read whole or streamed frame by frame.
#pragma once
#include <string>

#include "fluid/field.h"
#include "model/scene.h"

namespace lrigid {

// stream: "on", "off" or "auto" (streamed when all frames would take more than half the
// memory). Unless quiet, warns on stderr when the grid's viscosity differs from the scene's and
// says when it streams. Throws lrigid::Error (BadInput) naming the grid file.
FluidField load_scene_field(const Scene& scene, const std::string& stream, bool quiet);

// Bytes of physical memory on this machine.
double physical_memory();

}  // namespace lrigid
