// What every cache for DCC tools (animation.glb, points_houdini.csv, bodies.usda;
// docs/outputs.md) takes from a GltfAnimation, written once: the checks of its sizes, each body
// type's label and material, the surfaces' normals, the orientations made continuous, each
// body's state changes.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "io/gltf_writer.h"
#include "model/scene.h"

namespace lrigid {

// The caches for DCC tools, each a name of output.formats and the file it writes; the one list
// the scene's formats, the results writer and the summary take them from.
struct DccFormat {
  const char* format;  // in output.formats
  const char* file;    // in the results folder
  bool velocities;     // needs GltfAnimation::v and w
  void (*write)(const std::string& path, const GltfAnimation& a);
  bool OutputSpec::*enabled;
};
extern const DccFormat kDccFormats[4];

// Throws lrigid::Error(ExitCode::Usage) naming `path` when `a` has no frames or its arrays do
// not match bodies x frames; with `velocities`, a.v and a.w must be there too.
void check_animation(const std::string& path, const GltfAnimation& a, bool velocities);

// The body type's name as the caches write it: the entry's name, and ".<variant>" when the entry
// has more than one variant ("leaf.3").
std::string type_label(const GltfAnimation& a, size_t type);

// The scene's body entries the types belong to, in order of their first type: one material
// each, named after the entry. material[t] is type t's index in `entries`.
struct DccEntries {
  std::vector<std::string> names;
  std::vector<size_t> material;  // (ntype)
};
DccEntries dcc_entries(const GltfAnimation& a);

// The unit normal of each face corner (3 per face, faces' order), split where the surface
// folds: a corner takes the area-weighted mean of the normals of its vertex's faces that turn
// less than kSmoothAngle from its own face. So a curved leaf shades smoothly, while the two
// sides of a thin body, and a box's faces, keep their own normals (a vertex normal shared by
// both sides of a leaf would average to nothing and render black).
constexpr double kSmoothAngleDeg = 60;
std::vector<Vec3> corner_normals(const TriangleMesh& m);

// Each sample's orientation, unit, with each body's consecutive samples in one hemisphere
// (q and -q are one rotation; interpolating between them otherwise goes the long way round).
// Frame-major as a.q.
std::vector<Quat> continuous_orientations(const GltfAnimation& a);

// Body b's state at the first frame and at each frame where it changes: (t, state code).
// Empty when the animation carries no states.
std::vector<std::pair<double, uint8_t>> state_changes(const GltfAnimation& a, size_t b);

// Appends x with 9 significant digits (std::to_chars, as trajectories.csv writes its numbers).
void append_number(std::string* out, double x);

}  // namespace lrigid
