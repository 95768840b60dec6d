// A point cache for Houdini (houdini_points.csv, docs/outputs.md): one row per visible body and
// output frame, with Houdini's attribute names, a vector's components in consecutive columns
// named after it (Px, Py, Pz), so that a Table Import SOP maps each attribute from its first
// column and tuple size.
#pragma once
#include <string>

#include "io/gltf_writer.h"

namespace lrigid {

// The header of the cache, in column order.
constexpr const char* kHoudiniHeader =
    "frame,time,id,entry,variant,state,Px,Py,Pz,orientx,orienty,orientz,orientw,vx,vy,vz,wx,wy,"
    "wz";

// Writes the frames of `a` (velocities required) to `path` (temporary name, then rename):
// frame is the output frame from 1 (Houdini's first frame), time in s, P in m, orient the
// orientation body -> world as x, y, z, w (Houdini's quaternion order), v in m/s and w in
// rad/s in world axes, state its name (flying, ...), entry the scene body entry's name.
// Hidden bodies are left out. Throws lrigid::Error as write_gltf.
void write_houdini_csv(const std::string& path, const GltfAnimation& a);

}  // namespace lrigid
