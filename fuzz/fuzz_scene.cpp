// libFuzzer target: the scene parser. Any input must either parse into a scene or throw
// lrigid::Error (bad input); any other exception, crash or sanitizer report is a finding.
#include <cstdint>
#include <string>

#include "fuzz_util.h"
#include "io/scene_json.h"
#include "util/error.h"

// a valid mesh (a tetrahedron) for scenes that name m.obj
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  const std::string m = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";
  lrigid::fuzz::write_scratch("m.obj", reinterpret_cast<const uint8_t*>(m.data()), m.size());
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // relative paths in the scene (meshes, grids) resolve against the scratch directory
  const std::string path = lrigid::fuzz::scratch() + "/scene.json";
  try {
    const lrigid::Scene s =
        lrigid::parse_scene(std::string(reinterpret_cast<const char*>(data), size), path);
    (void)s;
  } catch (const lrigid::Error&) {
  }
  return 0;
}
