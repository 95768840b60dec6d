// The planform of a flat body: what the plate model (effects/plate.h) and the added mass of a
// flat body type (compile/compile_model.cpp) know of its outline, the same for every shape
// (docs/physics/lift.md, "The planform").
//
// The outline seen along the plate normal has an area S and half extents h1, h2 along the two
// in-plane shape axes. Its rectangularity R = S / (4 h1 h2) is the share of its bounding
// rectangle it fills (Rosin 1999, "Measuring rectangularity", Machine Vision and Applications
// 11: 191-196, with the rectangle along the shape axes): 1 for a rectangle, pi/4 for an ellipse,
// 0.783 for a 48-gon, less for pointed outlines (a diamond 1/2). The plate model knows two
// planforms with closed forms, the rectangle and the ellipse; a planform takes them both at its
// area S and side ratio h1 / h2 (the rectangle of half sides c = h sqrt(R), the ellipse of
// semi-axes a = h sqrt(4 R / pi)), weighted by
//   w = clamp((R - pi/4) / (1 - pi/4), 0, 1)
// of the rectangle and 1 - w of the ellipse: every coefficient that differs between the two
// (broadside drag, aspect ratio, strip integrals, width, chord, added mass) is
// w x rectangle's + (1 - w) x ellipse's. A box is w = 1 (its own half sizes), an ellipsoid w = 0
// (its own semi-axes), exactly; a mesh takes R from its outline (projected_area), so a square
// OBJ is the box and a polygon disk (R <= pi/4) the ellipse of its area. Outlines less
// rectangular than an ellipse take the ellipse's.
#pragma once
#include "body/shape.h"

namespace lrigid {

struct Planform {
  double area = 0;            // S, the outline's area, m^2
  double h1 = 0, h2 = 0;      // the outline's half extents along the in-plane axes, m
  double rectangularity = 0;  // R = S / (4 h1 h2)
  double w = 0;               // the rectangle's weight (above), 0..1
  double c1 = 0, c2 = 0;      // half sides of the rectangle of area S and side ratio h1 / h2, m
  double a1 = 0, a2 = 0;      // semi-axes of the ellipse of area S and side ratio h1 / h2, m
};

// The rectangle's weight w of a planform of rectangularity R (above)
double planform_weight(double rectangularity);

// The planform of `shape` seen along its axis `normal_axis` (0, 1, 2); the in-plane axes are
// (normal_axis + 1) % 3 and (normal_axis + 2) % 3. A box's is its rectangle (R = 1), a sphere's
// or an ellipsoid's its ellipse (R = pi/4), a mesh's its outline: the area of its shadow
// (projected_area, exact for a flat plate of any outline) and its bounding box's half extents.
Planform planform_of(const Shape& shape, int normal_axis);

}  // namespace lrigid
