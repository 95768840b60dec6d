// Reading grid files back in the foam2grid tests.
#pragma once
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLImageDataReader.h>

#include <string>

namespace foam2grid_test {

inline vtkSmartPointer<vtkImageData> read_vti(const std::string& path) {
  auto r = vtkSmartPointer<vtkXMLImageDataReader>::New();
  r->SetFileName(path.c_str());
  r->Update();
  vtkSmartPointer<vtkImageData> im = r->GetOutput();
  return im;
}

/// Coordinates of point id of an image.
inline void point_of(vtkImageData* im, vtkIdType id, double x[3]) { im->GetPoint(id, x); }

}  // namespace foam2grid_test
