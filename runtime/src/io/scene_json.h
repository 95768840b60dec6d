// Reads a scene file (JSON, schema v1, docs/scene-format.md) into a validated Scene.
// Every error names the file, the key path (e.g. bodies[2].shape.radius) and the bad value;
// unknown keys are errors; malformed JSON reports line and column. Throws lrigid::Error
// (ExitCode::BadInput).
#pragma once
#include <string>

#include "model/scene.h"

namespace lrigid {

Scene read_scene(const std::string& path);
// Parses text as if it were the file `path` (relative paths resolve against its directory).
Scene parse_scene(const std::string& text, const std::string& path);
// Parses text as one body's "shape" object (the Python module's added_mass); errors name `path`
// and the key shape.<key>. *panels: the shape's "panels" (0 when absent).
Shape parse_shape(const std::string& text, const std::string& path, int* panels);

}  // namespace lrigid
