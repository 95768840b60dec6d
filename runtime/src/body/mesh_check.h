// Validity checks for closed triangle surfaces (body meshes): every edge shared by exactly two
// faces with opposite directions, every vertex a single fan, no degenerate faces, no two faces
// crossing each other, positive volume.
#pragma once
#include <string>

#include "body/shape.h"

namespace lrigid {

enum class MeshDefect {
  None,
  Empty,         // fewer than 4 faces
  BadIndex,      // a face refers to a vertex that does not exist
  NonFinite,     // a vertex coordinate is NaN or infinite
  Degenerate,    // a face repeats a vertex or has (near) zero area
  Open,          // an edge belongs to one face only (a hole)
  NonManifold,   // an edge with more than two faces, or a vertex whose faces form several fans
  Inconsistent,  // two neighbouring faces have opposite orientation
  Inverted,      // faces point inwards (negative volume) or the volume is zero
  SelfIntersecting,  // two faces cross (an edge of one passes through the other)
};

struct MeshCheck {
  MeshDefect defect = MeshDefect::None;
  std::string message;  // what is wrong and where (face/vertex indices, 0-based); empty when ok
  bool ok() const { return defect == MeshDefect::None; }
};

// Runs all checks and reports the first problem found.
MeshCheck check_mesh(const TriangleMesh& mesh);

// Throws lrigid::Error(ExitCode::BadInput, "<source>: mesh ...") when check_mesh finds a problem.
void check_closed_mesh(const TriangleMesh& mesh, const std::string& source);

}  // namespace lrigid
