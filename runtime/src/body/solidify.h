// A single-sided surface (a leaf, a petal, a card, as DCC tools export them: open, one layer of
// faces) made into the thin closed body it stands for: the surface offset by half the thickness
// to either side along its vertex normals, the two layers joined along the surface's boundary.
// The body's mass, inertia, added mass and plate forces then follow from the closed mesh as for
// any other (docs/scene-format.md, shape "thickness").
#pragma once
#include <string>

#include "body/shape.h"

namespace lrigid {

// Number of edges of `mesh` that belong to one face only (0: the surface is closed).
int boundary_edge_count(const TriangleMesh& mesh);

// The closed thin body of the open surface `surface` with thickness `thickness` (m, > 0): each
// vertex p with unit normal n (the angle-weighted mean of its faces' normals) gives p + t/2 n and
// p - t/2 n; the faces are kept on the + side, reversed on the - side, and each boundary edge
// gets a side wall of two triangles. The faces' winding gives the + side. Throws lrigid::Error
// (ExitCode::BadInput, "<source>: surface ...") for a surface with no boundary, an edge of more
// than two faces, neighbouring faces of opposite orientation, two sheets meeting at a vertex, or
// a vertex whose faces' normals cancel. The result is checked as any closed mesh afterwards
// (body/mesh_check.h): a thickness larger than the surface's bends makes it cross itself.
TriangleMesh solidify_surface(const TriangleMesh& surface, double thickness,
                              const std::string& source);

}  // namespace lrigid
