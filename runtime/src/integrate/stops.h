// When a body stops moving: the rules the scalar loop (simulation.cpp) and the batched sphere
// step (sphere_batch.cpp) share.
#pragma once
#include <string>

#include "integrate/integrators.h"
#include "model/model.h"

namespace lrigid {

// the body's lowest point (of its bounding box) is on or below the ground
bool touches_ground(const Model& m, const BodyType& type, const BodyState& s);

// where one more step would take the body: its world velocity R v, plus the turbulent velocity
// u' for the body turbulence model (which carries the body directly; for the seen model u' is
// the fluid's and acts through the forces)
Vec3 predicted_position(const Model& m, const BodyType& type, const BodyState& b);

// where a body that could not be sampled went: where one more step would take it
std::string exit_reason(const Model& m, const BodyType& type, const BodyState& b);

}  // namespace lrigid
