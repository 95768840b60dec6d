// Scenes of bodies meeting the ground and the grid's solids, shared by the tests of the contact
// pass (runtime/contact/pass_test.cpp), its events (events_test.cpp), the touching points
// (touching_test.cpp) and the impacts located inside a step (runtime/integrate/impacts_test.cpp).
#pragma once
#include <cmath>

#include "support/fixture.h"

namespace lrigid::test {

inline constexpr double kG = 9.81;

// A sphere of radius 5 cm dropped from 1 m onto the ground, gravity alone (the fluid's forces off),
// friction 0.3, restitution e, stepped at 0.1 ms for 2.5 s.
inline Scene bounce_scene(double e, bool batched) {
  Scene s = sphere_scene(0.05, 1000, 1.2, 1.5e-5);
  s.effects = effects({Effect::Gravity});  // the fluid's forces off
  s.bodies[0].position = Vec3(0, 0, 1.0);
  s.bodies[0].contact.restitution = e;
  s.bodies[0].contact.friction = 0.3;
  s.has_ground = true;
  s.ground_z = 0;
  s.dt = 1e-4;
  s.duration = 2.5;
  s.batched = batched;
  return s;
}

// A grid whose wall distance is the inclined plane n.(x - p0) (n unit, pointing into the fluid):
// fluid at rest, points below the plane invalid.
inline FluidField inclined_wall_grid(const Vec3& n, const Vec3& p0) {
  const GridGeometry g = grid_geometry(21, 5, 21, Vec3(-1, -0.2, -1), Vec3(0.1, 0.1, 0.1));
  RawGridFrame f = grid_frame(g, [&](const Vec3& x, Vec3*, double* k, double* eps) {
    *k = 1e-6;
    *eps = 1e-6;
    return n.dot(x - p0) >= 0;
  });
  f.wall_distance.resize(g.points());
  for (size_t p = 0; p < g.points(); ++p) {
    const size_t i = p % size_t(g.n[0]), j = (p / size_t(g.n[0])) % size_t(g.n[1]);
    const size_t l = p / (size_t(g.n[0]) * size_t(g.n[1]));
    const Vec3 x = g.origin + Vec3(double(i), double(j), double(l)).cwiseProduct(g.spacing);
    f.wall_distance[p] = float(n.dot(x - p0));
  }
  return FluidField::grid(g, {f}, 1.5e-5, Drift::Stationary, TimeMode::Clamp);
}

// A 5 cm sphere thrown at 2 m/s straight down from 0.3 m onto the inclined wall of
// inclined_wall_grid (normal n), gravity off, friction 0, restitution e, for 0.3 s at step dt.
inline Scene wall_throw_scene(double e, double dt, bool batched) {
  Scene s = sphere_scene(0.05, 1000, 1.2, 1.5e-5);
  s.uniform_field = false;
  s.effects = effects({Effect::Gravity});
  s.gravity = Vec3::Zero();
  s.bodies[0].position = Vec3(0, 0, 0.3);
  s.bodies[0].velocity = Vec3(0, 0, -2);
  s.bodies[0].contact.restitution = e;
  s.bodies[0].contact.friction = 0;
  s.dt = dt;
  s.duration = 0.3;
  s.batched = batched;
  return s;
}

}  // namespace lrigid::test
