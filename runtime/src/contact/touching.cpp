#include "contact/touching.h"

#include <algorithm>
#include <cmath>

namespace lrigid {

void gather(const Model& m, const BodyType& type, const BodyState& b, const Mat3& R, double t,
            double ahead, Touching* out, WallClearance* clearance, double slack,
            double spec) {
  const ContactParams& k = *type.contact;
  const Mat3 Rt = R.transpose();
  // how far off a surface a speculative point can be: spec times the slowest approach of an
  // impact (faster points are impacts, taken where they happen)
  const double reach_spec = spec > 0 ? spec * m.rest_speed : 0.0;
  // a point at depth d < 0 (off the surface) approaching it at `approach` m/s: speculative
  auto speculative = [&](double d, double approach) {
    return d < 0 && approach <= m.rest_speed && d + spec * approach >= 0;
  };
  // points on the ground need no wall check: the grid's floor is the ground, twice the same
  // constraint would only cost
  uint8_t on_ground[kContactMaxPoints * 4] = {};
  // (-> Vec3: an Eigen expression returned by a lambda would refer to the cross product's
  // temporary after it is gone, and ground_depth read that stack garbage, times 0 when not ahead:
  // a NaN there dropped a touching point at random)
  auto point_velocity = [&](const Vec3& rb) -> Vec3 { return R * (b.v + b.w.cross(rb)); };
  if (m.ground_collides() && b.x.z() - type.reach <= m.ground_z + slack + reach_spec) {
    const Vec3 ez(0, 0, 1);
    // only the point's height: the last row of R (and its velocity only when looking ahead)
    const Vec3 rz = R.row(2).transpose();
    auto ground_depth = [&](const Vec3& rb) {
      double z = b.x.z() + rz.dot(rb);
      if (ahead != 0) z += ahead * rz.dot(b.v + b.w.cross(rb));
      return m.ground_z - z;
    };
    if (k.support) {
      const Vec3 nb = Rt * ez;
      Vec3 rb;
      ellipsoid_support_point(k, nb.data(), rb.data());
      const double d = ground_depth(rb);
      if (d >= -slack)
        out->add(rb, nb, std::max(d, 0.0)), out->ground = true;
      else if (spec > 0 && speculative(d, -point_velocity(rb).z()))
        out->add(rb, nb, d);
    } else {
      const Vec3 nb = Rt * ez;
      for (size_t p = 0; p < k.count(); ++p) {
        // a box edge's point between two corners on the ground: on it too, and implied by them
        // (the depth and the normal velocity are linear along the edge)
        if (k.on_edge(p) && on_ground[k.edge_ends[2 * p]] && on_ground[k.edge_ends[2 * p + 1]]) {
          if (p < sizeof on_ground) on_ground[p] = 1;
          continue;
        }
        const Vec3 rb(k.points[3 * p], k.points[3 * p + 1], k.points[3 * p + 2]);
        const double d = ground_depth(rb);
        if (d >= -slack) {
          out->add(rb, nb, std::max(d, 0.0));
          out->ground = true;
          if (p < sizeof on_ground) on_ground[p] = 1;
        } else if (spec > 0 && speculative(d, -point_velocity(rb).z())) {
          // (an edge's point between a touching and a speculative corner, or two speculative
          // ones, is implied by them as well: the gap too is linear along the edge)
          out->add(rb, nb, d);
          if (p < sizeof on_ground) on_ground[p] = 1;
        }
      }
    }
  }
  if (!m.walls_collide()) return;
  // a body near a colliding ground that is the grid's floor, away from every other wall: the
  // ground above was the only surface it could touch (touching or not)
  if (m.ground_collides() &&
      m.field.only_floor_near(b.x, type.reach + slack + reach_spec, m.ground_z, t))
    return;
  if (clearance && clearance->radius >= 0 && (b.x - clearance->x).norm() < clearance->radius)
    return;
  double dc;
  Vec3 gc;
  const bool inside = m.field.wall_distance(b.x, t, &dc, &gc);
  if (clearance) {
    clearance->x = b.x;
    clearance->radius = inside ? (dc - type.reach - reach_spec) / std::sqrt(3.0) : -1;
  }
  if (!inside || dc > type.reach + slack + reach_spec) return;
  // a point touches where the wall distance is <= 0; its normal is the distance's gradient
  auto wall = [&](const Vec3& rb, Vec3* nw) {
    Vec3 p = b.x + R * rb;
    if (ahead != 0) p += ahead * point_velocity(rb);
    double d;
    Vec3 g;
    if (!m.field.wall_distance(p, t, &d, &g) || d > slack + reach_spec) return -HUGE_VAL;
    const double gn = g.norm();
    if (!(gn > 0)) return -HUGE_VAL;
    *nw = g / gn;
    return -d;
  };
  // a wall's point at depth d (< -slack: off the wall), normal nw (world): speculative?
  auto wall_speculative = [&](const Vec3& rb, double d, const Vec3& nw) {
    return spec > 0 && d > -HUGE_VAL && speculative(d, -point_velocity(rb).dot(nw));
  };
  Vec3 nw;
  if (k.support) {
    // the support point against the wall's normal at the centre
    const double gn = gc.norm();
    if (!(gn > 0)) return;
    // the grid's floor under a body already on the ground: the same constraint
    if (out->ground && gc.z() > 0.99 * gn) return;
    const Vec3 nb = Rt * (gc / gn);
    Vec3 rb;
    ellipsoid_support_point(k, nb.data(), rb.data());
    const double d = wall(rb, &nw);
    if (d >= -slack)
      out->add(rb, Rt * nw, std::max(d, 0.0));
    else if (wall_speculative(rb, d, nw))
      out->add(rb, Rt * nw, d);
  } else {
    for (size_t p = 0; p < k.count(); ++p) {
      if (p < sizeof on_ground && on_ground[p]) continue;
      const Vec3 rb(k.points[3 * p], k.points[3 * p + 1], k.points[3 * p + 2]);
      const double d = wall(rb, &nw);
      if (d >= -slack)
        out->add(rb, Rt * nw, std::max(d, 0.0));
      else if (wall_speculative(rb, d, nw))
        out->add(rb, Rt * nw, d);
    }
  }
}

// The smallest signed distance (m; > 0: apart) of the shape's contact points (a box's corners),
// the body at x with rotation R at time t, to the colliding surfaces: the ground plane's height
// and the wall distance. Far from the walls (the centre's wall distance beyond the body's reach)
// the walls count with that distance less the reach, a bound that keeps the function continuous
// enough for a root finder.
double surface_gap(const Model& m, const BodyType& type, const Vec3& x, const Mat3& R, double t) {
  const ContactParams& k = *type.contact;
  const Mat3 Rt = R.transpose();
  double gap = HUGE_VAL;
  auto point = [&](size_t p) {
    return Vec3(k.points[3 * p], k.points[3 * p + 1], k.points[3 * p + 2]);
  };
  // a box edge's inner points lie between its corners: on the ground never lower than both; on
  // a wall they matter only where a solid's corner pokes between two of them, which the
  // contact at the located time still finds (it is deeper there): corners only, a fifth of the
  // wall queries of a leaf
  if (m.ground_collides()) {
    if (k.support) {
      const Vec3 nb = Rt * Vec3::UnitZ();
      Vec3 rb;
      ellipsoid_support_point(k, nb.data(), rb.data());
      gap = (x + R * rb).z() - m.ground_z;
    } else {
      for (size_t p = 0; p < k.count(); ++p)
        if (!k.on_edge(p)) gap = std::min(gap, (x + R * point(p)).z() - m.ground_z);
    }
  }
  if (!m.walls_collide()) return gap;
  // near a colliding ground that is the grid's floor, away from every other wall: the ground
  // was the only surface (as in gather)
  if (m.ground_collides() && m.field.only_floor_near(x, type.reach, m.ground_z, t)) return gap;
  double dc;
  Vec3 gc;
  if (!m.field.wall_distance(x, t, &dc, &gc)) return gap;
  if (dc > type.reach) return std::min(gap, dc - type.reach);
  auto wall_at = [&](const Vec3& rb) {
    double d;
    Vec3 g;
    return m.field.wall_distance(x + R * rb, t, &d, &g) ? d : HUGE_VAL;
  };
  if (k.support) {
    const double gn = gc.norm();
    if (!(gn > 0)) return gap;
    const Vec3 nb = Rt * (gc / gn);
    Vec3 rb;
    ellipsoid_support_point(k, nb.data(), rb.data());
    return std::min(gap, wall_at(rb));
  }
  for (size_t p = 0; p < k.count(); ++p)
    if (!k.on_edge(p)) gap = std::min(gap, wall_at(point(p)));
  return gap;
}

}  // namespace lrigid
