// Test helpers: scenes built inline, models compiled with the analytic/BEM added mass (no disk
// cache), and Eigen comparisons that print the mismatching entries.
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "body/added_mass.h"
#include "compile/compile_model.h"
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

// A closed, outward prism over a regular n-gon of circumradius r (a vertex on +x), thickness t,
// axis z: a thin one is a flat disk (paper, a coin) as a mesh
inline TriangleMesh polygon_prism(int n, double r, double t) {
  TriangleMesh m;
  for (double z : {-t / 2, t / 2})
    for (int i = 0; i < n; ++i)
      m.vertices.emplace_back(r * std::cos(2 * M_PI * i / n), r * std::sin(2 * M_PI * i / n), z);
  m.vertices.emplace_back(0, 0, -t / 2);
  m.vertices.emplace_back(0, 0, t / 2);
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    m.faces.push_back({2 * n, j, i});              // bottom, facing -z
    m.faces.push_back({2 * n + 1, n + i, n + j});  // top
    m.faces.push_back({i, j, n + j});              // sides
    m.faces.push_back({i, n + j, n + i});
  }
  return m;
}

// A closed, outward rectangular prism of half sides a along x and b along y and thickness t: 8
// vertices and 12 triangles, the file a user exports for a rectangular sheet
inline TriangleMesh rect_prism(double a, double b, double t) {
  TriangleMesh m;
  for (double z : {-t / 2, t / 2})
    for (const Vec2& xy : {Vec2(-a, -b), Vec2(a, -b), Vec2(a, b), Vec2(-a, b)})
      m.vertices.emplace_back(xy.x(), xy.y(), z);
  m.faces = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}};
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    m.faces.push_back({i, j, j + 4});
    m.faces.push_back({i, j + 4, i + 4});
  }
  return m;
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

// A grid geometry: n points per axis from `origin` with `spacing` (m).
inline GridGeometry grid_geometry(int nx, int ny, int nz, const Vec3& origin, const Vec3& spacing) {
  GridGeometry g;
  g.n[0] = nx;
  g.n[1] = ny;
  g.n[2] = nz;
  g.origin = origin;
  g.spacing = spacing;
  return g;
}

// One frame of grid g whose point values come from point(x, &U, &k, &eps), which returns false
// for a point inside a solid (x the point's position; U, k, eps start at zero; SI units).
template <typename PointFn>
RawGridFrame grid_frame(const GridGeometry& g, PointFn point) {
  RawGridFrame f;
  const size_t np = g.points();
  f.U.resize(3 * np);
  f.k.resize(np);
  f.epsilon.resize(np);
  f.valid.resize(np);
  for (size_t p = 0; p < np; ++p) {
    const size_t i = p % size_t(g.n[0]), j = (p / size_t(g.n[0])) % size_t(g.n[1]);
    const size_t l = p / (size_t(g.n[0]) * size_t(g.n[1]));
    const Vec3 x = g.origin + Vec3(double(i), double(j), double(l)).cwiseProduct(g.spacing);
    Vec3 U = Vec3::Zero();
    double k = 0, eps = 0;
    f.valid[p] = point(x, &U, &k, &eps) ? 1 : 0;
    for (int a = 0; a < 3; ++a) f.U[3 * p + a] = float(U[a]);
    f.k[p] = float(k);
    f.epsilon[p] = float(eps);
  }
  return f;
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
