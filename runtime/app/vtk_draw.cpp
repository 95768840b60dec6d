#include "vtk_draw.h"

#include <dlfcn.h>
#include <unistd.h>
#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkContourFilter.h>
#include <vtkCutter.h>
#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPlane.h>
#include <vtkPlaneSource.h>
#include <vtkPointData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkTextProperty.h>
#include <vtkWindowToImageFilter.h>
#include <vtkXMLImageDataReader.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "util/error.h"

namespace lrigid::app {

namespace fs = std::filesystem;

void require_display(const std::string& command) {
  const char* d = std::getenv("DISPLAY");
  const std::string hint = "lrigid " + command +
                           " draws with VTK/OpenGL and needs an X display; without one run it "
                           "under a virtual display: xvfb-run -a lrigid " +
                           command + " ...";
  if (!d || !*d) throw Error(ExitCode::Runtime, "no X display (DISPLAY is not set). " + hint);
  void* x11 = dlopen("libX11.so.6", RTLD_LAZY | RTLD_LOCAL);
  if (!x11) return;  // let VTK try
  using OpenFn = void* (*)(const char*);
  using CloseFn = int (*)(void*);
  auto open = reinterpret_cast<OpenFn>(dlsym(x11, "XOpenDisplay"));
  auto close = reinterpret_cast<CloseFn>(dlsym(x11, "XCloseDisplay"));
  bool ok = true;
  if (open && close) {
    void* dpy = open(nullptr);
    ok = dpy != nullptr;
    if (dpy) close(dpy);
  }
  dlclose(x11);
  if (!ok)
    throw Error(ExitCode::Runtime, std::string("cannot open X display \"") + d + "\". " + hint);
}

void type_colour(size_t i, unsigned char rgb[3]) {
  // no blue: the slices of k and |U| are blue
  static const unsigned char kPalette[][3] = {{230, 140, 50}, {70, 170, 70}, {200, 50, 90},
                                              {150, 90, 200}, {235, 200, 40}, {120, 80, 40}};
  for (int k = 0; k < 3; ++k) rgb[k] = kPalette[i % 6][k];
}

std::string first_vti(const std::string& field, const std::string& key) {
  if (fs::path(field).extension() != ".pvd") return field;
  std::ifstream in(field);
  if (!in) fail_input(field, "", "cannot be read (" + key + ")");
  std::stringstream ss;
  ss << in.rdbuf();
  std::smatch m;
  const std::string text = ss.str();
  if (!std::regex_search(text, m, std::regex("file=\"([^\"]+)\"")))
    fail_input(field, "", "no DataSet file in the collection");
  return (fs::path(field).parent_path() / m[1].str()).string();
}

vtkSmartPointer<vtkImageData> read_grid_image(const std::string& field, const std::string& key) {
  const std::string vti = first_vti(field, key);
  if (!fs::exists(vti)) fail_input(vti, "", "grid file not found (" + key + ")");
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(vti.c_str());
  reader->Update();
  auto img = vtkSmartPointer<vtkImageData>::New();
  img->ShallowCopy(reader->GetOutput());
  if (img->GetNumberOfPoints() == 0) fail_input(vti, "", "no grid points could be read");
  if (vtkDataArray* U = img->GetPointData()->GetArray("U"); U && U->GetNumberOfComponents() == 3) {
    vtkNew<vtkFloatArray> mag;
    mag->SetName("|U|");
    mag->SetNumberOfTuples(U->GetNumberOfTuples());
    for (vtkIdType i = 0; i < U->GetNumberOfTuples(); ++i) {
      const double* u = U->GetTuple3(i);
      mag->SetValue(i, float(std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2])));
    }
    img->GetPointData()->AddArray(mag);
  }
  return img;
}

void add_ground(vtkRenderer* ren, double z, Bounds* box) {
  const Vec3 d = box->hi - box->lo;
  const double m = 0.15 * std::max({d.x(), d.y(), 1e-3});
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(box->lo.x() - m, box->lo.y() - m, z);
  plane->SetPoint1(box->hi.x() + m, box->lo.y() - m, z);
  plane->SetPoint2(box->lo.x() - m, box->hi.y() + m, z);
  plane->SetResolution(10, 10);
  vtkNew<vtkPolyDataMapper> pm;
  pm->SetInputConnection(plane->GetOutputPort());
  vtkNew<vtkActor> pa;
  pa->SetMapper(pm);
  pa->GetProperty()->SetColor(0.78, 0.80, 0.74);
  pa->GetProperty()->LightingOff();
  pa->GetProperty()->EdgeVisibilityOn();
  pa->GetProperty()->SetEdgeColor(0.62, 0.64, 0.58);
  ren->AddActor(pa);
  const Vec3 lo = box->lo, hi = box->hi;
  box->add(Vec3(lo.x() - m, lo.y() - m, z));
  box->add(Vec3(hi.x() + m, hi.y() + m, z));
}

bool add_solids(vtkRenderer* ren, vtkImageData* img) {
  if (!img->GetPointData()->GetArray("valid")) return false;
  vtkNew<vtkContourFilter> c;
  c->SetInputData(img);
  c->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "valid");
  c->SetValue(0, 0.5);
  c->ComputeScalarsOff();
  vtkNew<vtkPolyDataMapper> m;
  m->SetInputConnection(c->GetOutputPort());
  m->ScalarVisibilityOff();
  vtkNew<vtkActor> a;
  a->SetMapper(m);
  a->GetProperty()->SetColor(0.72, 0.70, 0.66);
  ren->AddActor(a);
  return true;
}

bool add_slice(vtkRenderer* ren, vtkImageData* img, const std::string& array, double z,
               const std::string& title, int bar_height, double draw_z) {
  vtkDataArray* values = img->GetPointData()->GetArray(array.c_str());
  if (!values) return false;
  double gb[6];
  img->GetBounds(gb);
  vtkNew<vtkPlane> plane;
  plane->SetOrigin(0.5 * (gb[0] + gb[1]), 0.5 * (gb[2] + gb[3]), z);
  plane->SetNormal(0, 0, 1);
  vtkNew<vtkCutter> cut;
  cut->SetCutFunction(plane);
  cut->SetInputData(img);
  cut->Update();
  cut->GetOutput()->GetPointData()->SetActiveScalars(array.c_str());
  double range[2];
  values->GetRange(range);
  vtkNew<vtkLookupTable> lut;
  // pale to deep blue: the body colours (orange, green, red) stay readable on top
  lut->SetHueRange(0.58, 0.62);
  lut->SetSaturationRange(0.05, 0.85);
  lut->SetValueRange(0.97, 0.5);
  lut->SetTableRange(range);
  lut->Build();
  vtkNew<vtkPolyDataMapper> m;
  m->SetInputConnection(cut->GetOutputPort());
  m->SetLookupTable(lut);
  m->SetScalarRange(range);
  m->SetScalarModeToUsePointData();
  vtkNew<vtkActor> actor;
  actor->SetMapper(m);
  actor->GetProperty()->SetOpacity(0.85);
  actor->GetProperty()->LightingOff();
  if (draw_z == draw_z) actor->SetPosition(0, 0, draw_z - z);
  ren->AddActor(actor);
  vtkNew<vtkScalarBarActor> bar;
  bar->SetLookupTable(lut);
  bar->SetTitle(title.c_str());
  bar->SetNumberOfLabels(4);
  bar->SetMaximumWidthInPixels(90);
  bar->SetMaximumHeightInPixels(bar_height);
  bar->GetTitleTextProperty()->SetColor(0.1, 0.1, 0.15);
  bar->GetLabelTextProperty()->SetColor(0.1, 0.1, 0.15);
  ren->AddActor2D(bar);
  return true;
}

void apply_camera(vtkRenderer* ren, const CameraPose& c) {
  vtkCamera* cam = ren->GetActiveCamera();
  cam->SetFocalPoint(c.target.data());
  cam->SetPosition(c.position.data());
  cam->SetViewUp(c.up.data());
  cam->SetViewAngle(c.fov_deg);
  ren->ResetCameraClippingRange();
}

void speed_colours(vtkLookupTable* lut, double vmax) {
  lut->SetHueRange(0.66, 0.0);  // blue (slow) to red (fast)
  lut->SetTableRange(0, std::max(vmax, 1e-3));
  lut->Build();
}

void speed_bar(vtkScalarBarActor* bar, vtkLookupTable* lut, int bar_height) {
  bar->SetLookupTable(lut);
  bar->SetTitle("speed (m/s)");
  bar->SetNumberOfLabels(4);
  bar->SetMaximumWidthInPixels(80);
  bar->SetMaximumHeightInPixels(bar_height);
  bar->SetPosition(0.9, 0.55);
  bar->GetTitleTextProperty()->SetColor(0.1, 0.1, 0.15);
  bar->GetLabelTextProperty()->SetColor(0.1, 0.1, 0.15);
}

void write_png(vtkRenderWindow* win, const std::string& png) {
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(win);
  grab->ReadFrontBufferOff();
  grab->Update();
  const std::string tmp = png + ".tmp" + std::to_string(::getpid()) + ".png";
  vtkNew<vtkPNGWriter> w;
  w->SetFileName(tmp.c_str());
  w->SetInputConnection(grab->GetOutputPort());
  w->Write();
  std::error_code ec;
  if (!fs::exists(tmp) || fs::file_size(tmp, ec) == 0) {
    fs::remove(tmp, ec);
    throw Error(ExitCode::Output, where(png, "", "cannot write the image"));
  }
  fs::rename(tmp, png, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw Error(ExitCode::Output, where(png, "", "cannot move into place: " + ec.message()));
  }
}

}  // namespace lrigid::app
