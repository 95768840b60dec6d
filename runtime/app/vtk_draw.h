// Drawing pieces shared by `lrigid render` (cmd_render.cpp, a finished run, offscreen) and
// `lrigid view` (cmd_view.cpp, a live simulation in a window): the X display check, body type
// colours and drawing scales, the context (ground, solids, a slice of the grid), the camera and
// screenshots. VTK/OpenGL; the runtime core stays VTK-free.
#pragma once
#include <limits>
#include <vtkSmartPointer.h>

#include <string>
#include <vector>

#include "body/shape.h"
#include "util/types.h"

class vtkImageData;
class vtkRenderer;
class vtkRenderWindow;

namespace lrigid::app {

// VTK's X window aborts the process when it cannot open a display: this checks first and throws
// lrigid::Error(ExitCode::Runtime) with a hint to run `xvfb-run -a lrigid <command> ...`.
void require_display(const std::string& command);

// Colour of body type i (a palette of 6 that stays readable over the context, no blue), RGB
// 0..255.
void type_colour(size_t i, unsigned char rgb[3]);

struct Bounds {
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  void add(const Vec3& p) { lo = lo.cwiseMin(p), hi = hi.cwiseMax(p); }
  bool empty() const { return lo.x() > hi.x(); }
  double diag() const { return empty() ? 0.0 : (hi - lo).norm(); }
};

// Drawing scale of each body type (surfaces in the body frame, m): `fixed` > 0 for all, else
// enlarged so a body of the type covers about 5 pixels of a view `width` pixels wide over
// `extent` m (never shrunk). Sets *reach to the largest drawn half size, m.
std::vector<double> body_draw_scales(const std::vector<const TriangleMesh*>& surfaces,
                                     double extent, int width, double fixed, double* reach);

// The first (or only) .vti of a grid file: a .pvd names its files relative to itself. `key`
// names where the path came from, for the error message.
std::string first_vti(const std::string& field, const std::string& key);

// The grid file's first frame (U, k, epsilon, valid, ...), with an added point array "|U|" (m/s).
vtkSmartPointer<vtkImageData> read_grid_image(const std::string& field, const std::string& key);

// A square of ground at height z (m) under [lo, hi] widened by 15 %; adds its corners to *box.
void add_ground(vtkRenderer* ren, double z, Bounds* box);

// Solids (buildings, tank walls): the surface where the grid's `valid` mask drops to 0.
// False when the grid has no mask.
bool add_solids(vtkRenderer* ren, vtkImageData* img);

// A horizontal slice of point array `array` ("k", "|U|", ...) at height z (m), pale to deep blue,
// with a scalar bar titled `title` no taller than `bar_height` pixels. Drawn at height draw_z (m;
// NaN: at z), e.g. under the bodies lying on the floor, which a translucent slice above them
// would fade. False when the grid has no such array.
bool add_slice(vtkRenderer* ren, vtkImageData* img, const std::string& array, double z,
               const std::string& title, int bar_height,
               double draw_z = std::numeric_limits<double>::quiet_NaN());

// Looks at box from the front-left and above (Z up), the whole box in view.
void aim_camera(vtkRenderer* ren, const Bounds& box);

// Writes what the window shows to a PNG (temporary name, then rename). Throws
// lrigid::Error(ExitCode::Output) naming the path when it cannot.
void write_png(vtkRenderWindow* win, const std::string& png);

}  // namespace lrigid::app
