// The outline of a flat body in its plane: the convex hull of points and the tightest rectangle
// around them, which gives a planform its extents and its in-plane axes whatever way the outline
// is turned in its file (body/planform.h, docs/physics/lift.md "The planform").
#pragma once
#include <vector>

#include "util/types.h"

namespace lrigid {

// The convex hull of points in a plane, counter-clockwise, without repeated or collinear points
// (Andrew's monotone chain, A. M. Andrew, "Another efficient algorithm for convex hulls in two
// dimensions", Information Processing Letters 9, 1979). Fewer than three points come back for
// points that all lie on one line (two: its ends; one: a single point; none: no points).
std::vector<Vec2> convex_hull(std::vector<Vec2> points);

// A rectangle in a plane: the centre, its unit sides axis1 and axis2 = axis1 turned by +90
// degrees, and its half sides along them
struct OutlineRectangle {
  Vec2 centre = Vec2::Zero();
  Vec2 axis1 = Vec2::UnitX(), axis2 = Vec2::UnitY();
  double h1 = 0, h2 = 0;  // half sides along axis1, axis2 (units of the points)
  double area() const { return 4.0 * h1 * h2; }
  double angle() const;   // of axis1 from the x axis, rad, in (-pi/4, pi/4]
};

// The rectangle of least area around points in a plane (its minimum-area bounding rectangle).
// One of its sides lies along an edge of the points' convex hull (Freeman & Shapira,
// "Determining the minimum-area encasing rectangle for an arbitrary closed curve", Comm. ACM
// 18(7), 1975), so it is found among the hull's edges by rotating calipers: the three points
// farthest along an edge, against it and across it move forward with the edges, one turn of the
// hull in all (Toussaint, "Solving geometric problems with the rotating calipers", MELECON 1983).
// Of the rectangle's sides axis1 is the one nearest the x axis (its angle in (-pi/4, pi/4]), so an
// outline drawn along the axes keeps them exactly (axis1 = (1, 0), axis2 = (0, 1)). Of several
// rectangles of the same least area (a square's outline at any turn of a circle's polygon) the
// first found. Points on one line give a rectangle of zero width along the line; no points give
// the default (zero half sides).
OutlineRectangle min_area_rectangle(const std::vector<Vec2>& points);

}  // namespace lrigid
