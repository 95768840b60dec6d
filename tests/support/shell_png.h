// For tests that run the lrigid program and look at the PNGs it draws (tests/render/):
// a shell command's exit status and output, and a PNG read into memory.
#pragma once
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>

#include <cstdio>
#include <string>
#include <vector>

#include "support/shell.h"

namespace lrigid::test {

// pixels row by row, bottom row first (VTK's order), `comps` bytes each
struct Image {
  int w = 0, h = 0, comps = 0;
  std::vector<unsigned char> px;
  const unsigned char* at(int x, int y) const { return &px[(size_t(y) * w + x) * comps]; }
};

// empty (w = h = 0) when the file cannot be read
inline Image read_png(const std::string& path) {
  vtkNew<vtkPNGReader> r;
  r->SetFileName(path.c_str());
  r->Update();
  Image im;
  int dims[3];
  r->GetOutput()->GetDimensions(dims);
  auto* a = vtkUnsignedCharArray::SafeDownCast(r->GetOutput()->GetPointData()->GetScalars());
  if (!a) return im;
  im.w = dims[0], im.h = dims[1];
  im.comps = a->GetNumberOfComponents();
  im.px.assign(a->GetPointer(0), a->GetPointer(0) + a->GetNumberOfValues());
  return im;
}

}  // namespace lrigid::test
