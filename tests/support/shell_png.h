// For tests that run the lrigid program and look at the PNGs it draws (tests/render/):
// a shell command's exit status and output, and a PNG read into memory.
#pragma once
#include <sys/wait.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>

#include <cstdio>
#include <string>
#include <vector>

namespace lrigid::test {

// runs a shell command; returns its exit status (-1 when it did not exit) and stdout+stderr
inline int sh(const std::string& cmd, std::string* out = nullptr) {
  std::string text;
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return -1;
  char buf[512];
  while (fgets(buf, sizeof buf, p)) text += buf;
  const int st = pclose(p);
  if (out) *out = text;
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

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
