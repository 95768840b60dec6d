// Test helpers: scenes built inline, models compiled with the analytic/BEM added mass (no disk
// cache), and Eigen comparisons that print the mismatching entries.
#pragma once
#include <gtest/gtest.h>

#include <string>

#include "body/added_mass.h"
#include "model/model.h"
#include "model/state.h"

namespace lrigid::test {

// A scene with one body type of `count` spheres at the origin, fluid at rest, no effects.
inline Scene sphere_scene(double radius, double density, double fluid_density, double nu,
                          int count = 1) {
  Scene s;
  s.file = "<test>";
  s.fluid_density = fluid_density;
  s.kinematic_viscosity = nu;
  s.uniform_field = true;
  BodySpec b;
  b.name = "sphere";
  b.shape = Shape::sphere(radius);
  b.density = density;
  b.count = count;
  s.bodies.push_back(b);
  return s;
}

inline EffectSet effects(std::initializer_list<Effect> list) {
  EffectSet e;
  for (Effect x : list) e.add(x);
  return e;
}

inline Model compile(const Scene& s) {
  FluidField f = FluidField::uniform(s.uniform_U, s.uniform_k, s.uniform_epsilon,
                                     s.kinematic_viscosity, s.drift);
  return compile_model(s, std::move(f), [](const Shape& sh, double rho, int panels) {
    return added_mass(sh, rho, panels);
  });
}

inline Model compile(const Scene& s, FluidField f) {
  return compile_model(s, std::move(f), [](const Shape& sh, double rho, int panels) {
    return added_mass(sh, rho, panels);
  });
}

template <typename A, typename B>
::testing::AssertionResult near(const A& a, const B& b, double tol) {
  const double err = (a - b).cwiseAbs().maxCoeff();
  if (err <= tol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "max |a - b| = " << err << " > " << tol << "\na =\n"
                                       << a << "\nb =\n"
                                       << b;
}

}  // namespace lrigid::test
