// The planform of a flat body: what the plate model (effects/plate.h) and the added mass of a
// flat body type (compile/compile_model.cpp) know of its outline, the same for every shape
// (docs/physics/lift.md, "The planform").
//
// The outline seen along the plate normal has an area S and a tightest (minimum-area) bounding
// rectangle, of half sides h1, h2 along its sides e1, e2 in the plate's plane (body/outline.h:
// the convex hull of the outline, rotating calipers). Its rectangularity R = S / (4 h1 h2) is the
// share of that rectangle it fills (Rosin 1999, "Measuring rectangularity", Machine Vision and
// Applications 11: 191-196, R_MBR): 1 for a rectangle, pi/4 for an ellipse, 0.7865 for a
// regular 48-gon, less for pointed outlines (a diamond 1/2). The rectangle, and so R, turns with
// the outline: a square drawn turned by 45 degrees in its file is the same square. The plate model
// knows two planforms with closed forms, the rectangle and the ellipse; a planform takes them both
// at its area S and side ratio h1 / h2, along e1 and e2 (the rectangle of half sides
// c = h sqrt(R), the ellipse of semi-axes a = h sqrt(4 R / pi)), weighted by
//   w = clamp((R - pi/4) / (1 - pi/4), 0, 1)
// of the rectangle and 1 - w of the ellipse: every coefficient that differs between the two
// (broadside drag, aspect ratio, strip integrals, width, chord, added mass) is
// w x rectangle's + (1 - w) x ellipse's. A box is w = 1 (its own half sizes), an ellipsoid w = 0
// (its own semi-axes), exactly, both along their own axes; a mesh takes R, e1 and e2 from its
// outline (projected_area and the rectangle of its vertices seen along the normal), so a square
// OBJ at any turn is the box turned the same way and a polygon disk (R within 0.2 % of pi/4 from
// 48 sides) the ellipse of its area. Outlines less rectangular than an ellipse take the ellipse's.
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
  // the in-plane axes of h1, c1, a1 and h2, c2, a2 (the tightest rectangle's sides) as unit
  // vectors of the shape frame, e1 x e2 along the normal axis: the shape axes (normal_axis + 1)
  // % 3 and (normal_axis + 2) % 3 exactly for a box, a sphere, an ellipsoid and a mesh drawn along
  // them; turned about the normal by `angle` otherwise
  Vec3 e1 = Vec3::UnitX(), e2 = Vec3::UnitY();
  double angle = 0;  // from the shape axis (normal_axis + 1) % 3 to e1 about the normal, rad,
                     // in (-pi/4, pi/4]
};

// The rectangle's weight w of a planform of rectangularity R (above)
double planform_weight(double rectangularity);

// The planform of `shape` seen along its axis `normal_axis` (0, 1, 2). A box's is its rectangle
// (R = 1), a sphere's or an ellipsoid's its ellipse (R = pi/4), both along the shape axes
// (normal_axis + 1) % 3 and (normal_axis + 2) % 3; a mesh's its outline: the area of its shadow
// (projected_area, exact for a flat plate of any outline) and the tightest rectangle around its
// vertices seen along the normal, whose sides give e1, e2 and h1, h2.
Planform planform_of(const Shape& shape, int normal_axis);

}  // namespace lrigid
