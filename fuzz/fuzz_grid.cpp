// libFuzzer target: the grid reader. The first byte chooses the format (.vti, or a .pvd
// series whose entries may name the valid grid g.vti written at start-up); the rest is the
// file. Any input must either read or throw lrigid::Error.
#include <vtkObject.h>

#include <cstdint>
#include <string>

#include "fuzz_util.h"
#include "io/grid_reader.h"
#include "util/error.h"

namespace {

// a valid 2x2x2 grid for .pvd entries to point at
const char* kGood = R"(<?xml version="1.0"?>
<VTKFile type="ImageData" version="1.0" byte_order="LittleEndian" header_type="UInt64">
<ImageData WholeExtent="0 1 0 1 0 1" Origin="0 0 0" Spacing="1 1 1">
<Piece Extent="0 1 0 1 0 1"><PointData>
<DataArray type="Float32" Name="U" NumberOfComponents="3" format="ascii">
1 0 0 1 0 0 1 0 0 1 0 0 1 0 0 1 0 0 1 0 0 1 0 0</DataArray>
<DataArray type="Float32" Name="k" format="ascii">1 1 1 1 1 1 1 1</DataArray>
<DataArray type="Float32" Name="epsilon" format="ascii">1 1 1 1 1 1 1 1</DataArray>
<DataArray type="UInt8" Name="valid" format="ascii">1 1 1 1 1 1 1 1</DataArray>
</PointData><CellData></CellData></Piece></ImageData></VTKFile>
)";

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  vtkObject::GlobalWarningDisplayOff();
  const std::string g(kGood);
  lrigid::fuzz::write_scratch("g.vti", reinterpret_cast<const uint8_t*>(g.data()), g.size());
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const bool pvd = data[0] & 1;
  const std::string path =
      lrigid::fuzz::write_scratch(pvd ? "in.pvd" : "in.vti", data + 1, size - 1);
  try {
    const lrigid::GridFile g = lrigid::read_grid(path);
    (void)g;
  } catch (const lrigid::Error&) {
  }
  return 0;
}
