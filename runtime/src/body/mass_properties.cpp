#include "body/mass_properties.h"

#include <cmath>
#include <sstream>
#include <string>

#include "util/error.h"

namespace lrigid {

namespace {

// Uniform polyhedron by signed tetrahedra (o, a, b, c) over the faces, o a reference point.
// For a tetrahedron with vertices p0..p3 and volume V:  int x dV = V/4 sum p_k and
// int x x^T dV = V/20 (sum p_k p_k^T + (sum p_k)(sum p_k)^T); with p0 = 0 only a, b, c remain.
MassProperties mesh_properties(const TriangleMesh& mesh, const std::string& source) {
  if (mesh.faces.empty()) throw Error(ExitCode::BadInput, where(source, "", "mesh has no faces"));
  const Vec3 o = mesh.vertices.at(mesh.faces[0][0]);  // nearby origin limits round-off
  double volume = 0;
  Vec3 first = Vec3::Zero();
  Mat3 second = Mat3::Zero();
  for (const auto& f : mesh.faces) {
    const Vec3 a = mesh.vertices.at(f[0]) - o, b = mesh.vertices.at(f[1]) - o,
               c = mesh.vertices.at(f[2]) - o;
    const double v = a.dot(b.cross(c)) / 6.0;
    const Vec3 s = a + b + c;
    volume += v;
    first += v / 4.0 * s;
    second +=
        v / 20.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  if (!(volume > 0))
    throw Error(ExitCode::BadInput, where(source, "",
                                          "mesh volume is not positive (" + std::to_string(volume) +
                                              " m^3): inverted or not closed"));
  MassProperties mp;
  mp.volume = volume;
  const Vec3 rel = first / volume;
  mp.centroid = o + rel;
  const Mat3 cov = second - volume * rel * rel.transpose();  // second moment about the centroid
  mp.inertia = cov.trace() * Mat3::Identity() - cov;
  mp.inertia = 0.5 * (mp.inertia + mp.inertia.transpose());
  return mp;
}

}  // namespace

MassProperties mass_properties(const Shape& shape) {
  const Vec3 h = shape.half_extents;
  MassProperties mp;
  switch (shape.type) {
    case ShapeType::Sphere:
    case ShapeType::Ellipsoid: {
      // I_xx = V (b^2 + c^2) / 5
      mp.volume = 4.0 / 3.0 * M_PI * h.prod();
      const Vec3 q = h.cwiseAbs2();
      mp.inertia =
          (mp.volume / 5.0 * Vec3(q.y() + q.z(), q.z() + q.x(), q.x() + q.y())).asDiagonal();
      return mp;
    }
    case ShapeType::Box: {
      // I_xx = V (ly^2 + lz^2) / 12 with l = 2 h
      mp.volume = 8.0 * h.prod();
      const Vec3 q = h.cwiseAbs2();
      mp.inertia =
          (mp.volume / 3.0 * Vec3(q.y() + q.z(), q.z() + q.x(), q.x() + q.y())).asDiagonal();
      return mp;
    }
    case ShapeType::Mesh:
      if (!shape.mesh)
        throw Error(ExitCode::BadInput, where(shape.source, "", "mesh shape without a mesh"));
      return mesh_properties(*shape.mesh, shape.source);
  }
  return mp;
}

MassProperties mass_properties(const TriangleMesh& mesh) { return mesh_properties(mesh, ""); }

double projected_area(const TriangleMesh& mesh, int axis) {
  double twice = 0;  // sum of |(b - a) x (c - a)| along the axis: twice the projected areas
  for (const auto& f : mesh.faces) {
    const Vec3& a = mesh.vertices[f[0]];
    twice += std::abs((mesh.vertices[f[1]] - a).cross(mesh.vertices[f[2]] - a)[axis]);
  }
  return 0.25 * twice;  // each point of the shadow is covered twice (entering and leaving)
}

std::string offset_outside_shape(const Shape& shape, const Vec3& offset) {
  const Vec3& h = shape.half_extents;
  auto vec = [](const Vec3& v) {
    std::ostringstream o;
    o << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
    return o.str();
  };
  bool inside = true;
  std::string what;
  switch (shape.type) {
    case ShapeType::Sphere:
    case ShapeType::Ellipsoid:
      inside = offset.cwiseQuotient(h).squaredNorm() < 1.0;
      if (shape.type == ShapeType::Sphere) {
        std::ostringstream o;
        o << "the sphere's radius " << h.x() << " m";
        what = o.str();
      } else {
        what = "the ellipsoid's semi-axes " + vec(h) + " m";
      }
      break;
    case ShapeType::Box:
      inside = (offset.cwiseAbs().array() < h.array()).all();
      what = "the box's half extents " + vec(h) + " m";
      break;
    case ShapeType::Mesh: {
      // the bounding box's centre is not the centroid: the offset from the centroid within it
      const Vec3 c = mass_properties(shape).centroid;
      Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
      for (const Vec3& v : shape.mesh->vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
      const Vec3 p = c + offset;
      inside = (p.array() > lo.array()).all() && (p.array() < hi.array()).all();
      what = "the mesh's bounding box " + vec(lo - c) + " to " + vec(hi - c) +
             " m from its centroid";
      break;
    }
  }
  if (inside && offset.allFinite()) return "";
  return vec(offset) + " m from the volume centroid puts the centre of mass outside the body (" +
         what + "); the centre of mass of a solid body lies inside it";
}

}  // namespace lrigid
