// Triangle mesh files: Wavefront OBJ and STL (binary and ASCII). Units: the file's coordinates
// are taken as metres.
#pragma once
#include <string>

#include "body/shape.h"

namespace lrigid {

// Reads `path` by its extension (.obj or .stl, any case). OBJ: "v x y z" and "f i j k ..." lines
// (polygons are fan-triangulated; "i/t/n", negative and forward indices accepted; other records
// ignored); "vt u v" texture coordinates become TriangleMesh::uv when every face corner names
// one. STL: binary if the size matches the triangle count in the header, else ASCII
// ("solid ... facet ... vertex x y z ... endsolid"); facet normals are ignored (the vertex order
// defines the orientation) and identical vertices are merged so the surface is connected.
// Only parses: validity (closed, manifold, ...) is checked by Shape::from_mesh.
// Throws lrigid::Error(ExitCode::BadInput, "<path>: line N: ...") for unreadable files.
TriangleMesh read_mesh(const std::string& path);

// Writes an ASCII STL (atomically); used by tests and for exporting tessellated shapes.
void write_stl_ascii(const std::string& path, const TriangleMesh& mesh, const std::string& name);

// Writes a binary STL (atomically, float32 coordinates).
void write_stl_binary(const std::string& path, const TriangleMesh& mesh);

// Writes a Wavefront OBJ (atomically, 1-based indices, coordinates with 17 digits).
void write_obj(const std::string& path, const TriangleMesh& mesh);

}  // namespace lrigid
