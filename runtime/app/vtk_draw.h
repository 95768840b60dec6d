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
#include "camera.h"
#include "util/types.h"

class vtkImageData;
class vtkLookupTable;
class vtkRenderer;
class vtkScalarBarActor;
class vtkRenderWindow;

namespace lrigid::app {

// VTK's X window aborts the process when it cannot open a display: this checks first and throws
// lrigid::Error(ExitCode::Runtime) with a hint to run `xvfb-run -a lrigid <command> ...`.
void require_display(const std::string& command);

// Colour of body type i (a palette of 6 that stays readable over the context, no blue), RGB
// 0..255.
void type_colour(size_t i, unsigned char rgb[3]);

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

// Puts the renderer's camera at c (position, target, up, vertical field of view).
void apply_camera(vtkRenderer* ren, const CameraPose& c);

// The colours of speed, blue (slow) to red (fast), over [0, vmax] m/s, and its colour bar
// ("speed (m/s)", no taller than `bar_height` pixels, on the right).
void speed_colours(vtkLookupTable* lut, double vmax);
void speed_bar(vtkScalarBarActor* bar, vtkLookupTable* lut, int bar_height);

// Writes what the window shows to a PNG (temporary name, then rename). Throws
// lrigid::Error(ExitCode::Output) naming the path when it cannot.
void write_png(vtkRenderWindow* win, const std::string& png);

}  // namespace lrigid::app
