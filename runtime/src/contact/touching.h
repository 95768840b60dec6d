// The touching points of a body (docs/contacts.md): the shape's contact points (contact/points.h)
// that reach the ground plane or a wall of the grid's solids, with their normals and depths, and
// the smallest gap of those points to the surfaces. The contact pass (contact/pass.h) and the
// impacts located inside a step (integrate/impacts.h) gather them the same way.
#pragma once
#include "contact/solver.h"
#include "model/body_state.h"
#include "model/model.h"
#include "util/types.h"

namespace lrigid {

// What the last wall query of a body found: its centre x and the wall distance d there. The
// grid's wall distance is trilinear in node values that differ by at most the spacing between
// neighbouring nodes (an exact distance), so each of its partial derivatives is at most 1 and its
// gradient at most sqrt(3): while the centre stays within (d - reach) / sqrt(3) of x, no point of
// the body can reach a wall, and the scalar step skips the query (the batched steps compare the
// wall distance their samples carry instead). Not valid across the sign jump where a grid box
// reaches beyond a non-rectangular mesh (docs/grid-format.md); bodies there leave the grid.
struct WallClearance {
  Vec3 x = Vec3::Zero();
  double radius = -1;  // m; < 0: no query yet
};

// The touching points of one body: body-frame offsets from the centre of mass, body-frame unit
// normals (from the surface into the fluid) and depths (m; >= 0 for a point that touches, < 0
// for a speculative point: minus its gap to the surface, which it closes within the next step).
struct Touching {
  double r[3 * kContactMaxPoints];
  double n[3 * kContactMaxPoints];
  double depth[kContactMaxPoints];
  int count = 0;
  int touching = 0;     // of them, the points that touch (depth >= 0)
  bool ground = false;  // a touching point is on the ground
  void add(const Vec3& rb, const Vec3& nb, double d) {
    if (count == kContactMaxPoints) return;
    for (int a = 0; a < 3; ++a) r[3 * count + a] = rb[a], n[3 * count + a] = nb[a];
    touching += d >= 0;
    depth[count++] = d;
  }
};

// The shape's points that reach a surface, with the positions `ahead` seconds ahead at the
// points' current velocities (0: where they are). slack >= 0: points up to slack (m) off the
// surface count too, with depth 0 (an impact located inside a step: the points that touch there).
// spec > 0 (s): the points off the surface that approach it slower than Model::rest_speed and
// reach it within spec at their velocity count too, as speculative points (depth: minus the
// gap): a body lying on a surface tilted by less than what one step closes then has its other
// edge in the contact problem too (docs/contacts.md "Speculative points").
void gather(const Model& m, const BodyType& type, const BodyState& b, const Mat3& R, double t,
            double ahead, Touching* out, WallClearance* clearance = nullptr, double slack = 0,
            double spec = 0);

// The smallest signed distance (m; > 0: apart) of the shape's contact points (a box's corners),
// the body at x with rotation R at time t, to the colliding surfaces: the ground plane's height
// and the wall distance. Far from the walls (the centre's wall distance beyond the body's reach)
// the walls count with that distance less the reach, a bound that keeps the function continuous
// enough for a root finder.
double surface_gap(const Model& m, const BodyType& type, const Vec3& x, const Mat3& R, double t);

}  // namespace lrigid
