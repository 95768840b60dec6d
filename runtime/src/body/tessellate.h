// Triangle surfaces of shapes: used by the boundary element method, tests, and rendering/export.
#pragma once
#include "body/shape.h"

namespace lrigid {

// A closed, outward-oriented triangle surface of `shape` in its own frame with about
// `target_faces` faces (the nearest count the construction allows):
//  - sphere/ellipsoid: icosphere with 20 * 4^k faces, vertices on the exact surface (an
//    inscribed polyhedron), scaled by the semi-axes; symmetric under the three coordinate mirrors;
//  - box: each face divided into a grid of cells (cosine spacing, finer towards the edges), each
//    split into 4 triangles around its centre (so the mesh keeps every mirror symmetry of the box);
//  - mesh: the mesh itself, split k times by edge midpoints (geometry unchanged), k >= 0 chosen
//    so the face count is nearest to the target.
// Throws lrigid::Error(ExitCode::Usage) for target_faces < 1.
TriangleMesh tessellate(const Shape& shape, int target_faces);

// Splits every face into 4 at its edge midpoints; shared edges share their midpoint, so a
// closed mesh stays closed.
TriangleMesh subdivide(const TriangleMesh& mesh);

}  // namespace lrigid
