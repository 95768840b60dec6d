// Baked animation of the bodies as glTF 2.0 binary (.glb) for DCC tools (Blender, Houdini):
//  - one mesh per body type (its surface in the body frame, origin at the centre of mass, with
//    per-corner normals split where the surface folds, io/dcc_cache.h, and TEXCOORD_0 when the
//    body's OBJ has "vt"), named after its type ("leaf", a variant "leaf.3"), stored once and
//    shared by every body of that type; one material per scene body entry, named after it;
//  - GltfLayout::Animated: one node per body, child of a root node "lrigid_world_z_up", with a
//    translation and a rotation channel sampled at the output times (LINEAR: lerp / slerp
//    between samples), a STEP scale channel (0) for a hidden body, and the body's attributes in
//    its node's extras (id, entry, variant, states: [t, state] at each change);
//  - GltfLayout::Instanced (EXT_mesh_gpu_instancing, required): the extension's instances
//    cannot be animated, so each output frame is a node of its own holding one instanced node
//    per body type (the frame's visible bodies: TRANSLATION, ROTATION, _ID), shown (scale 1)
//    from its time to the next frame's by a STEP scale channel and hidden (scale 0) otherwise;
//  - axes: the simulation is Z-up; glTF is Y-up. Body nodes keep the simulation's world frame
//    (translation = x, rotation = q, metres), and the root node carries a rotation of -90 degrees
//    about x that maps Z-up onto Y-up, so importers that convert Y-up back (Blender) show the
//    scene with z up, as in the simulation.
// See docs/outputs.md for sizes and timings at 10,000 bodies.
#pragma once
#include <string>
#include <vector>

#include "body/shape.h"
#include "util/types.h"

namespace lrigid {

struct GltfBodyType {
  std::string name;
  TriangleMesh surface;  // body frame (origin at the centre of mass), m
  size_t entry = 0;      // index of the scene's body entry (Model BodyType::spec)
  int variant = 0;       // index among that entry's variants ("variation"), 0 without
};

// Frame-major samples: entry [frame * nbody + body].
struct GltfAnimation {
  std::vector<GltfBodyType> types;
  std::vector<int> body_type;  // (nbody) index into types
  std::vector<double> times;   // (nframe) s, increasing
  std::vector<Vec3> x;         // (nframe * nbody) centre of mass, world, m
  std::vector<Quat> q;         // (nframe * nbody) orientation, body -> world
  // (nframe * nbody) world-frame velocity of the centre of mass (m/s) and angular velocity
  // (rad/s), as trajectories.csv writes them; may be empty (the glTF needs neither)
  std::vector<Vec3> v, w;
  // (nframe * nbody) 1: the body is hidden (it left the grid with "outside": "remove"); may be
  // empty (none is)
  std::vector<uint8_t> hidden;
  // (nframe * nbody) the body's state as State::state_code numbers it (flying, sliding, ...);
  // may be empty (not recorded)
  std::vector<uint8_t> state;
  bool hidden_at(size_t frame, size_t body) const {
    const size_t k = frame * bodies() + body;
    return k < hidden.size() && hidden[k] != 0;
  }
  size_t bodies() const { return body_type.size(); }
};

enum class GltfLayout { Animated, Instanced };

// Writes `anim` to `path` (temporary name, then rename). Throws lrigid::Error(ExitCode::Output)
// naming the path on failure, ExitCode::Usage for inconsistent sizes or no frames.
void write_gltf(const std::string& path, const GltfAnimation& anim,
                GltfLayout layout = GltfLayout::Animated);

// The root node's rotation (glTF order x, y, z, w): -90 degrees about x, Z-up -> Y-up.
constexpr double kGltfRootRotation[4] = {-0.70710678118654752, 0, 0, 0.70710678118654752};

}  // namespace lrigid
