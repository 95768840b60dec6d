#include "vtk_annotate.h"

#include <vtkActor.h>
#include <vtkImageData.h>
#include <vtkLegendBoxActor.h>
#include <vtkNew.h>
#include <vtkOutlineSource.h>
#include <vtkPlaneSource.h>
#include <vtkCellArray.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <string>


namespace lrigid::app {

vtkLegendBoxActor* add_legend(vtkRenderer* ren, const std::vector<LegendEntry>& entries,
                              int width, int height) {
  if (entries.empty()) return nullptr;
  vtkNew<vtkLegendBoxActor> legend;
  legend->SetNumberOfEntries(int(entries.size()));
  // a filled square swatch: drawn flat, in exactly the entry's colour
  vtkNew<vtkPlaneSource> square;
  square->Update();
  // lines without a swatch: a single point (VTK refuses a null or empty symbol)
  vtkNew<vtkPolyData> blank;
  vtkNew<vtkPoints> dot;
  dot->InsertNextPoint(0, 0, 0);
  vtkNew<vtkCellArray> vert;
  const vtkIdType first = 0;
  vert->InsertNextCell(1, &first);
  blank->SetPoints(dot);
  blank->SetVerts(vert);
  size_t longest = 0;
  for (size_t i = 0; i < entries.size(); ++i) {
    const LegendEntry& e = entries[i];
    double c[3] = {e.rgb[0] / 255.0, e.rgb[1] / 255.0, e.rgb[2] / 255.0};
    longest = std::max(longest, e.label.size());
    legend->SetEntry(int(i), e.swatch ? square->GetOutput() : blank.GetPointer(), e.label.c_str(), c);
  }
  legend->UseBackgroundOn();
  legend->SetBackgroundColor(1, 1, 1);
  legend->SetBackgroundOpacity(0.8);
  legend->BorderOff();
  legend->GetEntryTextProperty()->SetColor(0.1, 0.1, 0.15);
  legend->GetEntryTextProperty()->SetFontSize(std::max(10, height / 36));
  legend->LockBorderOff();
  // size in the viewport's normalised units: about one text line per entry, as wide as the
  // longest label (a character is about 0.6 of the font size)
  const double line = std::max(14.0, height / 28.0);
  const double w = std::min(0.6, (1.8 * line + 0.6 * line * double(longest)) / width);
  const double h = std::min(0.5, line * double(entries.size()) * 1.3 / height);
  legend->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  legend->GetPositionCoordinate()->SetValue(0.01, 0.99 - h);
  legend->GetPosition2Coordinate()->SetCoordinateSystemToNormalizedViewport();
  legend->GetPosition2Coordinate()->SetValue(w, h);
  ren->AddActor2D(legend);
  return legend;
}

void add_domain(vtkRenderer* ren, vtkImageData* grid, bool water) {
  double b[6];
  grid->GetBounds(b);
  vtkNew<vtkOutlineSource> outline;
  outline->SetBounds(b);
  vtkNew<vtkPolyDataMapper> om;
  om->SetInputConnection(outline->GetOutputPort());
  vtkNew<vtkActor> oa;
  oa->SetMapper(om);
  oa->GetProperty()->SetColor(0.2, 0.2, 0.25);
  oa->GetProperty()->SetLineWidth(2);
  oa->GetProperty()->LightingOff();
  ren->AddActor(oa);
  if (!water) return;
  // the tank: walls and floor (the grid's box without its top), seen through
  auto panel = [&](const double o[3], const double p1[3], const double p2[3], const double c[3],
                   double opacity) {
    vtkNew<vtkPlaneSource> p;
    p->SetOrigin(o[0], o[1], o[2]);
    p->SetPoint1(p1[0], p1[1], p1[2]);
    p->SetPoint2(p2[0], p2[1], p2[2]);
    vtkNew<vtkPolyDataMapper> m;
    m->SetInputConnection(p->GetOutputPort());
    vtkNew<vtkActor> a;
    a->SetMapper(m);
    a->GetProperty()->SetColor(c[0], c[1], c[2]);
    a->GetProperty()->SetOpacity(opacity);
    a->GetProperty()->LightingOff();
    ren->AddActor(a);
  };
  const double wall[3] = {0.75, 0.8, 0.85}, surface[3] = {0.2, 0.55, 0.85};
  const double x0 = b[0], x1 = b[1], y0 = b[2], y1 = b[3], z0 = b[4], z1 = b[5];
  const double v[8][3] = {{x0, y0, z0}, {x1, y0, z0}, {x0, y1, z0}, {x1, y1, z0},
                          {x0, y0, z1}, {x1, y0, z1}, {x0, y1, z1}, {x1, y1, z1}};
  panel(v[0], v[1], v[2], wall, 0.25);  // floor
  panel(v[0], v[1], v[4], wall, 0.15);  // y = y0
  panel(v[2], v[3], v[6], wall, 0.15);  // y = y1
  panel(v[0], v[2], v[4], wall, 0.15);  // x = x0
  panel(v[1], v[3], v[5], wall, 0.15);  // x = x1
  panel(v[4], v[5], v[6], surface, 0.3);  // the water surface: the grid's top
}

void fit_caption(vtkTextActor* text, vtkRenderer* ren, int width, int margin) {
  vtkTextProperty* p = text->GetTextProperty();
  auto fits = [&] {
    double bb[4];
    text->GetBoundingBox(ren, bb);  // x0, x1, y0, y1 in pixels
    return bb[1] - bb[0] <= width - 2 * margin;
  };
  // smaller, down to 10 points; then one line per part (parts are separated by 3 spaces),
  // smaller again down to 8
  while (!fits() && p->GetFontSize() > 10) p->SetFontSize(p->GetFontSize() - 1);
  if (fits()) return;
  std::string s = text->GetInput() ? text->GetInput() : "";
  for (size_t at; (at = s.find("   ")) != std::string::npos;) s.replace(at, 3, "\n");
  text->SetInput(s.c_str());
  while (!fits() && p->GetFontSize() > 8) p->SetFontSize(p->GetFontSize() - 1);
}

}  // namespace lrigid::app
