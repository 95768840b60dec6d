// The lengths a shape may have (radius, semi-axes, edges, a mesh's extent), m: outside them the
// added-mass integrals underflow (a radius of 1e-200 m) or the boundary elements never finish (a
// box of 1e160 m). body/shape.cpp enforces them; the scene's parser (io/scene_json.cpp) checks
// the same ranges first, naming the key.
#pragma once

namespace lrigid {

constexpr double kMinShapeLength = 1e-9, kMaxShapeLength = 1e6;
// A box's longest edge over its shortest: at 1e6 the boundary elements' tensor is no longer
// positive (a sheet of 1 m x 1 m x 1 um); 1e5 still solves to the thin-plate limit.
constexpr double kMaxBoxAspect = 1e5;

}  // namespace lrigid
