// Body shapes: the geometry of a body type, in its own (shape) frame.
// Analytic shapes are centred at the origin with their axes along x, y, z.
// Meshes keep the coordinates of the file; their volume centroid need not be at the origin.
#pragma once
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "util/types.h"

namespace lrigid {

enum class ShapeType { Sphere, Ellipsoid, Box, Mesh };

const char* shape_type_name(ShapeType t);

// Closed, outward-oriented triangle surface (counter-clockwise seen from outside).
struct TriangleMesh {
  std::vector<Vec3> vertices;             // (nvert) m
  std::vector<std::array<int, 3>> faces;  // (nface) vertex indices
  // (nface) or empty: the texture coordinates (u, v) of each face's corners, in the faces'
  // order (an OBJ's "vt"); carried for the DCC outputs, never read by the physics
  std::vector<std::array<Vec2, 3>> uv;
  bool has_uv() const { return !uv.empty() && uv.size() == faces.size(); }
};

struct Shape {
  ShapeType type = ShapeType::Sphere;
  // Sphere: (r, r, r); ellipsoid: semi-axes (a, b, c); box: half sizes (lx/2, ly/2, lz/2).
  // Mesh: half extents of the axis-aligned bounding box. m
  Vec3 half_extents = Vec3::Ones();
  std::shared_ptr<const TriangleMesh> mesh;  // Mesh only
  std::string source;                        // Mesh only: the file it came from
  double scale = 1;      // Mesh only: the factor the file's coordinates were multiplied by
  double thickness = 0;  // Mesh only: > 0: the file is a single-sided surface made into this
                         // body of that thickness, m (body/solidify.h); 0: a closed mesh

  static Shape sphere(double radius);
  static Shape ellipsoid(double a, double b, double c);
  static Shape box(double lx, double ly, double lz);  // full edge lengths
  static Shape from_mesh(std::shared_ptr<const TriangleMesh> mesh, std::string source);
};

}  // namespace lrigid
