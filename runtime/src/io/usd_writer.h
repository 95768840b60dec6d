// The bodies as a USD layer (bodies.usda, text format "#usda 1.0"; docs/outputs.md), written to
// the USD specification (OpenUSD's schemas UsdGeomPointInstancer, UsdGeomMesh, UsdShade):
//   /lrigid                      Xform, the layer's default prim
//   /lrigid/bodies               PointInstancer: protoIndices and ids (one value for all
//                                times), and at each output frame positions (m), orientations
//                                (quath, real part first), velocities (m/s), angularVelocities
//                                (deg/s, as the schema measures them) and invisibleIds (the
//                                hidden bodies)
//   /lrigid/bodies/Prototypes/<type>   Mesh per body type: points, faceVertexIndices, normals
//                                and primvars:st (faceVarying, when the OBJ had "vt"), bound
//                                to its entry's material
//   /lrigid/Materials/<entry>    Material with a UsdPreviewSurface, one per scene body entry
// Time codes are t / (t1 - t0) (the output frames' numbers), timeCodesPerSecond 1 / (t1 - t0);
// upAxis Z, metersPerUnit 1, as the simulation.
#pragma once
#include <string>
#include <vector>

#include "io/gltf_writer.h"

namespace lrigid {

// Writes `a` (velocities required) to `path` (temporary name, then rename). Throws
// lrigid::Error as write_gltf.
void write_usd(const std::string& path, const GltfAnimation& a);

// A USD prim name for `label` (letters, digits, '_'; "leaf.3" -> "leaf_3").
std::string usd_identifier(const std::string& label);
// usd_identifier of each label, made distinct by a suffix "_2", "_3", ... where two are alike
std::vector<std::string> usd_identifiers(const std::vector<std::string>& labels);

}  // namespace lrigid
