// Writes a small grid file in foam2grid's format (VTK XML ImageData with point arrays U, k,
// epsilon, valid, optionally wall_distance, and field data kinematic_viscosity, time; docs/grid-format.md) for tests that
// need one on disk. `fill` sets U, k and epsilon at point p (x fastest) at position x.
#pragma once
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLImageDataWriter.h>

#include <array>
#include <functional>
#include <string>

namespace lrigid::test {

struct VtiGrid {
  std::array<int, 3> dims{2, 2, 2};
  std::array<double, 3> origin{0, 0, 0};
  std::array<double, 3> spacing{1, 1, 1};
  double time = 0;
  double nu = 1.5e-5;  // m^2/s
  bool with_epsilon = true;
  // points where it returns true are solid (valid = 0); empty: all points are fluid
  std::function<bool(const std::array<double, 3>& x)> solid;
  // the point array wall_distance (m) at x; empty: not written (a grid of an older foam2grid)
  std::function<float(const std::array<double, 3>& x)> wall_distance;
};

using VtiFill = std::function<void(int p, const std::array<double, 3>& x, float U[3], float* k,
                                   float* epsilon)>;

// true when VTK wrote the file
inline bool write_vti(const std::string& path, const VtiGrid& g, const VtiFill& fill) {
  vtkNew<vtkImageData> img;
  img->SetDimensions(g.dims[0], g.dims[1], g.dims[2]);
  img->SetOrigin(g.origin.data());
  img->SetSpacing(g.spacing.data());
  const int n = g.dims[0] * g.dims[1] * g.dims[2];
  vtkNew<vtkFloatArray> U, k, eps;
  vtkNew<vtkUnsignedCharArray> valid;
  vtkNew<vtkFloatArray> wall;
  wall->SetName("wall_distance");
  wall->SetNumberOfTuples(n);
  U->SetName("U");
  U->SetNumberOfComponents(3);
  U->SetNumberOfTuples(n);
  k->SetName("k");
  k->SetNumberOfTuples(n);
  eps->SetName("epsilon");
  eps->SetNumberOfTuples(n);
  valid->SetName("valid");
  valid->SetNumberOfTuples(n);
  for (int p = 0; p < n; ++p) {
    const int i = p % g.dims[0], j = (p / g.dims[0]) % g.dims[1], l = p / (g.dims[0] * g.dims[1]);
    const std::array<double, 3> x{g.origin[0] + i * g.spacing[0], g.origin[1] + j * g.spacing[1],
                                  g.origin[2] + l * g.spacing[2]};
    float u[3] = {0, 0, 0}, kv = 0, ev = 0;
    fill(p, x, u, &kv, &ev);
    U->SetTypedTuple(p, u);
    k->SetValue(p, kv);
    eps->SetValue(p, ev);
    valid->SetValue(p, g.solid && g.solid(x) ? 0 : 1);
    if (g.wall_distance) wall->SetValue(p, g.wall_distance(x));
  }
  img->GetPointData()->AddArray(U);
  img->GetPointData()->AddArray(k);
  if (g.with_epsilon) img->GetPointData()->AddArray(eps);
  img->GetPointData()->AddArray(valid);
  if (g.wall_distance) img->GetPointData()->AddArray(wall);
  vtkNew<vtkDoubleArray> nu, time;
  nu->SetName("kinematic_viscosity");
  nu->InsertNextValue(g.nu);
  time->SetName("time");
  time->InsertNextValue(g.time);
  img->GetFieldData()->AddArray(nu);
  img->GetFieldData()->AddArray(time);
  vtkNew<vtkXMLImageDataWriter> w;
  w->SetFileName(path.c_str());
  w->SetInputData(img);
  return w->Write() == 1;
}

}  // namespace lrigid::test
