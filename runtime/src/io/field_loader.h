// The fluid field a scene names, loaded once for every command (lrigid run, explain, bench, and
// the Python module): the uniform field, a steady .vti grid, or a .pvd series held in memory or
// streamed (only the frames bracketing the current time in memory).
#pragma once
#include <string>

#include "fluid/field.h"
#include "model/scene.h"

namespace lrigid {

// "auto": a series is streamed when all its frames would take more than half the physical
// memory; "on": always (series of more than 2 frames); "off": never.
enum class StreamMode { Auto, On, Off };
// "auto", "on" or "off"; throws lrigid::Error (usage) naming the flag otherwise
StreamMode stream_mode_from(const std::string& word);

// quiet: no warnings or notes on stderr (a viscosity that differs from the grid's, streaming)
FluidField load_field(const Scene& scene, StreamMode stream = StreamMode::Auto, bool quiet = false);

// physical memory of this machine, bytes
double physical_memory();

}  // namespace lrigid
