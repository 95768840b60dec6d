// When the bodies of a scene entry are released (key bodies[i].release, docs/scene-format.md):
// by rate, body k of the entry at start + k / rate; or at listed times t_0 < t_1 < ... < t_(n-1),
// the entry's count split into n bursts in order, the first (count % n) bursts one body larger
// than the others (count / n). A body waits, unstepped and hidden, until the first step at or
// after its release time.
#pragma once
#include <cstdint>

#include "model/scene.h"

namespace lrigid {

// The release time of body k (0 <= k < spec.count) of the entry, s; 0 without "release".
double release_time(const BodySpec& spec, int k);

// The first step whose time (step * dt) is at or after t (within 1e-6 of a step: the time a
// rate or a list gives is rounded, 0.1 / 0.002 is 50.000000000000007).
uint64_t first_step_at(double t, double dt);

}  // namespace lrigid
