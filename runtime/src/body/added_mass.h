// The fluid part of the Kirchhoff (added-mass) tensor of a body type.
// 6x6, symmetric positive semi-definite, in the shape axes, about the shape's volume centroid,
// rows/columns ordered (v_x, v_y, v_z, w_x, w_y, w_z): generalized momentum (P; L) = K (v; w).
// Units: kg in the linear block, kg m in the coupling blocks, kg m^2 in the angular block.
// Equations, sources and measured accuracy: docs/physics/added-mass.md.
#pragma once
#include <string>

#include "body/shape.h"

namespace lrigid {

// Panel count used when `panels` is 0: sphere/ellipsoid meshes get 1280 panels (-0.5 %), a cube
// 1536 (+1.0 %), a 1 % thick square plate 1792 (+2.3 %); 0.2-0.6 s on one core (LU-bound).
constexpr int kDefaultPanels = 1500;

struct AddedMass {
  Mat6 tensor = Mat6::Zero();
  std::string method;  // "analytic" or "bem"
  int panels = 0;      // BEM panels used (0 for analytic)
};

// Sphere and ellipsoid: exact (Lamb). Box and mesh: boundary element method with about
// `panels` panels (0 = kDefaultPanels; boxes are tessellated, meshes split by edge midpoints
// until near the target, never coarsened). Throws lrigid::Error for fluid_density < 0 or
// panels < 0, and as bem_added_mass() does.
AddedMass added_mass(const Shape& shape, double fluid_density, int panels = 0);

// Always the boundary element method, for any shape (spheres and ellipsoids are tessellated);
// used to validate the panel method against the exact results. A process keeps its last 64
// panel solutions: the same geometry (type, extents, a mesh's vertices and faces) and panel
// target again gives the same tensor without a new solve.
AddedMass added_mass_bem(const Shape& shape, double fluid_density, int panels = 0);

// How many panel solutions this process has made (the other calls reused one).
int bem_solve_count();

// Lamb's ellipsoid constants alpha0, beta0, gamma0 (sum 2) for semi-axes (a, b, c):
// alpha0 = a b c int_0^inf dl / ((a^2 + l) sqrt((a^2 + l)(b^2 + l)(c^2 + l))), etc.
Vec3 ellipsoid_constants(const Vec3& semi_axes);

// Carlson's symmetric elliptic integral R_D(x, y, z) = 3/2 int_0^inf dt /
// ((t + z) sqrt((t + x)(t + y)(t + z))), x, y >= 0 (not both 0), z > 0.
double carlson_rd(double x, double y, double z);

}  // namespace lrigid
