// What makes a picture of `lrigid render` and `lrigid view` read at a glance: a legend of the
// colours, a caption that fits the image, and the domain the bodies are in (the
// grid's outline; for water, the tank's walls and its surface). VTK; used by cmd_render.cpp.
#pragma once
#include <string>
#include <vector>

#include "draw_style.h"

class vtkImageData;
class vtkLegendBoxActor;
class vtkRenderer;
class vtkTextActor;

namespace lrigid::app {

// A legend box in the top-left corner: one line per entry, a flat swatch in its colour (none
// where !swatch) and its label (draw_style.h legend_entries). Its text is sized for an image
// `height` pixels tall. Returns the legend (nullptr when there are no entries).
vtkLegendBoxActor* add_legend(vtkRenderer* ren, const std::vector<LegendEntry>& entries,
                              int width, int height);

// The grid's box as dark lines; with `water`, also its side walls and floor as pale translucent
// panels and the water surface (the grid's top) as a translucent blue sheet.
void add_domain(vtkRenderer* ren, vtkImageData* grid, bool water);

// Shrinks the caption's font until it fits within the window's width (less 2 margins of
// `margin` pixels), down to 10 points; if it still does not fit, puts each of its parts
// (separated by 3 spaces) on a line of its own and shrinks down to 8 points. The renderer must
// be in a window of its final size.
void fit_caption(vtkTextActor* text, vtkRenderer* ren, int width, int margin);

}  // namespace lrigid::app
