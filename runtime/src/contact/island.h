// The contact problem of an island of bodies touching each other (docs/contacts.md, "Bodies
// against each other"): projected Gauss-Seidel on the accumulated impulses of every contact
// point between two bodies and between a body and a static surface (the ground, a wall of the
// grid's solids, a sleeping body), each point through the generalized 6x6 inverse masses (body
// plus added mass) of both bodies. The per-point update is contact_point_sweep, the one the
// contacts of a body against surfaces take (contact/solver.h contact_resolve). World frame.
#pragma once
#include <vector>

#include "util/types.h"

namespace lrigid {

struct IslandBody {
  double W[36] = {};  // generalized inverse mass [v; w], world frame, row-major; 0: static
  double v[3] = {};   // velocity of the centre of mass, world, m/s
  double w[3] = {};   // angular velocity, world, rad/s
};

struct IslandPoint {
  int a = 0, b = -1;     // bodies of the island; b < 0: a static surface
  double ra[3] = {}, rb[3] = {};  // the point from each body's centre of mass, world, m
  double n[3] = {};      // unit normal from b towards a, world
  double depth = 0;      // m; >= 0 touching, < 0 a speculative point off by -depth
  double restitution = 0, friction = 0, rolling = 0;  // the pair's material
  double rest_speed = 0; // m/s: a point approaching slower does not bounce
  double slop = 0;       // m: the depth the position correction leaves (island_resolve's moves)
  // the normal and tangential (world) impulses on a, N s: on entry those the solve starts from
  // (the last step's at this point, a warm start; 0: none), on return those the point carries
  double jn = 0;
  double jt[3] = {};
};

// The velocity of point p of a on a relative to b, world (m/s).
void island_point_velocity(const IslandBody* bodies, const IslandPoint& p, double* vc);

// Resolves the island's points (at most `passes` sweeps, fewer once no impulse changes by more
// than kContactTolerance of the largest, or of the impulse that changes a point's velocity by
// its resting speed when that is larger), starting from each point's jn and jt (warm start: the
// normal impulse taken >= 0, the tangential one projected onto the point's tangent plane and
// into its friction cone, both applied before the first sweep; the targets below are those of
// the velocities before it): each point's normal velocity to its target (-e v_n
// approaching faster than rest_speed, 0 slower; a speculative point -gap / horizon), never
// pulling, and Coulomb friction within mu J_n (a speculative point approaching faster than
// rest_speed that closes its gap within the step takes -e v_n too: the impact); with rolling > 0
// the rolling resistance's angular impulse against the relative rotation, at most rolling |r| J_n.
// Velocities are updated in place. Returns the points that carry a normal impulse. With `moves` (3
// per body, world frame, m; 0 for bodies no point names): the position correction. Of each touching
// point's penetration beyond its slop, less what the step's position update takes of its velocity
// change (cw times it: h/2 for the schemes that move the bodies with the mean of the old and new
// velocities, 0 for euler), half is removed by Gauss-Seidel sweeps (at most `passes`, fewer once
// converged as above) on the bodies' displacements, each body moved as a particle of its
// translational inverse mass W_vv (a unit position impulse along n moves a by W_vv,a n and b by
// -W_vv,b n), each point's accumulated correction pushing only: a column of bodies pressed into
// each other and the ground is lifted as one. Velocities are left alone: no energy is added.
// passes_moving >= 0: at most that many sweeps (velocities and positions) when a touching point
// moves faster than its resting speed before the solve (an impact, a body sliding).
int island_resolve(IslandBody* bodies, IslandPoint* pts, int count, int passes, double horizon,
                   double cw = 0, double* moves = nullptr, int passes_moving = -1);

// The generalized inverse mass in the world frame: blockdiag(R, R) Minv blockdiag(R, R)^T, Minv
// the body frame's (symmetric), row-major out.
void world_inverse_mass(const Mat6& Minv_body, const Mat3& R, double* W);

}  // namespace lrigid
