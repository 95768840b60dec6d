// Mass properties of a shape of uniform unit density (1 kg/m^3): scale by the density.
// The volume centroid is also the centre of buoyancy. A body whose mass is not uniform (e.g. a
// weighted keel) keeps this centroid as its centre of buoyancy; the model applies the offset of
// its centre of mass.
#pragma once
#include <string>

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

// Why a centre of mass `offset` (m, shape axes) from the volume centroid cannot be the shape's:
// empty when it lies strictly inside the shape (spheres, ellipsoids and boxes exactly; a mesh:
// inside its bounding box), else what is wrong, for the scene's error message. The centre of mass
// of a solid body lies inside it; one outside would make a body whose buoyancy torque no real
// body has.
std::string offset_outside_shape(const Shape& shape, const Vec3& offset);

// Exact polyhedral volume integrals of a closed, outward-oriented triangle surface (signed
// tetrahedra). Throws lrigid::Error(ExitCode::BadInput) if the enclosed volume is not positive.
MassProperties mass_properties(const TriangleMesh& mesh);

// Area of a closed triangle surface's shadow on the plane normal to the shape axis `axis`
// (0, 1, 2): half the sum of the triangles' projected areas, exact for a surface that every line
// along the axis crosses twice (a convex body, a flat plate of any outline: its planform), m^2
double projected_area(const TriangleMesh& mesh, int axis);

}  // namespace lrigid
