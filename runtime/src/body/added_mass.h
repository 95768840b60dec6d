// The fluid part of the Kirchhoff (added-mass) tensor of a body type.
// 6x6, symmetric positive semi-definite, in the shape axes, about the shape's volume centroid,
// rows/columns ordered (v_x, v_y, v_z, w_x, w_y, w_z): generalized momentum (P; L) = K (v; w).
// Units: kg in the linear block, kg m in the coupling blocks, kg m^2 in the angular block.
#pragma once
#include <string>

#include "body/shape.h"

namespace lrigid {

struct AddedMass {
  Mat6 tensor = Mat6::Zero();
  std::string method;  // "analytic" or "bem"
  int panels = 0;      // BEM panels used (0 for analytic)
};

// Sphere and ellipsoid: exact (Lamb). Box and mesh: boundary element method with about
// `panels` panels (0 = a default that gives ~1-2 % accuracy).
AddedMass added_mass(const Shape& shape, double fluid_density, int panels = 0);

}  // namespace lrigid
