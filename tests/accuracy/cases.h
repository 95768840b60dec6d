// The smooth cases of the accuracy tests (convergence_test.cpp, strang_test.cpp, events_test.cpp):
// each scheme's order is measured on them.
#pragma once
#include "support/fixture.h"

namespace lrigid::accuracy {

// 1 mm glass spheres in water thrown sideways: gravity, buoyancy, added mass and nonlinear drag
// (the relative speed never passes through zero, so the right-hand side is smooth)
inline Scene sinking_sphere(int count = 4) {
  Scene s = test::sphere_scene(1e-3, 2500, 998.2, 1e-6, count);
  s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::AddedMass, Effect::Drag});
  s.bodies[0].velocity = Vec3(0.1, 0.02, 0.05);
  s.duration = 0.08;  // about four drag relaxation times
  return s;
}

// prolate 2:1:1 ellipsoids slightly heavier than water (density kg/m^3), tilted and spinning:
// added mass with its Munk moment, rotation on SO(3). No drag: the drag of a non-spherical body
// depends on |direction cosines| of the relative velocity, which is not smooth, and rk4 then
// measures below order 4 (slope 0.7 on this case with drag; see docs/accuracy.md).
inline Scene tumbling_ellipsoid(double density = 1100, int count = 1) {
  Scene s = test::sphere_scene(1e-3, density, 998.2, 1e-6, count);
  s.bodies[0].shape = Shape::ellipsoid(0.01, 0.005, 0.005);
  s.bodies[0].orientation = Quat(Eigen::AngleAxisd(0.4, Vec3(0.3, 1, 0.2).normalized()));
  s.bodies[0].velocity = Vec3(0.05, 0, -0.02);
  s.bodies[0].angular_velocity = Vec3(0.5, -1.0, 2.0);
  s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::AddedMass});
  s.duration = 0.5;
  return s;
}

}  // namespace lrigid::accuracy
