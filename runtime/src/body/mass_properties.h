// Mass properties of a shape of uniform unit density (1 kg/m^3): scale by the density.
// The volume centroid is also the centre of buoyancy. A body whose mass is not uniform (e.g. a
// weighted keel) keeps this centroid as its centre of buoyancy; the model applies the offset of
// its centre of mass.
#pragma once
#include "body/shape.h"

namespace lrigid {

struct MassProperties {
  double volume = 0;             // m^3
  Vec3 centroid = Vec3::Zero();  // volume centroid (= centre of buoyancy) in the shape frame, m
  Mat3 inertia = Mat3::Zero();   // about the centroid, shape axes, per unit density, m^5
};

// Exact for every shape type (meshes: polyhedral volume integrals). Throws lrigid::Error for
// degenerate input.
MassProperties mass_properties(const Shape& shape);

// Exact polyhedral volume integrals of a closed, outward-oriented triangle surface (signed
// tetrahedra). Throws lrigid::Error(ExitCode::BadInput) if the enclosed volume is not positive.
MassProperties mass_properties(const TriangleMesh& mesh);

}  // namespace lrigid
