// One body's state as a step takes it (a copy out of the State, structure of arrays), how a step
// ended, and the rotation every step and the contact pass apply to an orientation.
#pragma once
#include <cstddef>

#include "model/state.h"
#include "util/types.h"

namespace lrigid {

struct BodyState {
  Vec3 x;        // world, m
  Quat q;        // body -> world
  Vec3 v;        // body frame, m/s
  Vec3 w;        // body frame, rad/s
  Vec3 u_seen;   // world, m/s
  double* history = nullptr;  // Basset history in State (BassetKernel::stride()), or null
};

// Body i of a State as a BodyState (its history pointer into the State), and back.
BodyState load_body(State& st, size_t i);
void store_body(const BodyState& b, size_t i, State* st);

enum class StepOutcome { Ok, Exited, Failed };

// q exp(theta): rotation by the body-frame rotation vector theta (rad)
Quat rotate_body(const Quat& q, const Vec3& theta);

}  // namespace lrigid
