// Mass properties of a shape of uniform unit density (1 kg/m^3): scale by the density.
#pragma once
#include "body/shape.h"

namespace lrigid {

struct MassProperties {
  double volume = 0;                         // m^3
  Vec3 centroid = Vec3::Zero();              // volume centroid in the shape frame, m
  Mat3 inertia = Mat3::Zero();               // about the centroid, shape axes, per unit density, m^5
};

// Exact for every shape type (meshes: polyhedral volume integrals). Throws lrigid::Error for
// degenerate input.
MassProperties mass_properties(const Shape& shape);

}  // namespace lrigid
