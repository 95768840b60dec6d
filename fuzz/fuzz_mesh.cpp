// libFuzzer target: the mesh reader and the mesh checks. The first byte chooses the format
// (.obj or .stl); the rest is the file. A mesh that reads is also turned into a Shape (closed,
// manifold, oriented, positive volume checks, mass properties). Any input must either succeed
// or throw lrigid::Error.
#include <cstdint>
#include <memory>
#include <string>

#include "body/shape.h"
#include "fuzz_util.h"
#include "io/mesh_io.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const bool stl = data[0] & 1;
  const std::string path =
      lrigid::fuzz::write_scratch(stl ? "in.stl" : "in.obj", data + 1, size - 1);
  try {
    auto mesh = std::make_shared<lrigid::TriangleMesh>(lrigid::read_mesh(path));
    const lrigid::Shape s = lrigid::Shape::from_mesh(mesh, path);
    (void)s;
  } catch (const lrigid::Error&) {
  }
  return 0;
}
