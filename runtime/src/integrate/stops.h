// When a body stops moving: the rules the scalar loop (simulation.cpp) and the batched steps
// (batch_lanes.h) share.
#pragma once
#include <string>

#include "integrate/integrators.h"
#include "model/model.h"

namespace lrigid {

// the body's lowest point (of its bounding box) is on or below the ground
bool touches_ground(const Model& m, const BodyType& type, const BodyState& s);

// A step from b that left the fluid would take the body onto a colliding ground (its
// predicted position touches it): the caller tries speculative_ground_contact and the step again.
bool heads_into_ground(const Model& m, const BodyType& type, const BodyState& b);

// Stops body i after its step from t did not succeed (out: Exited or Failed; `failure`: why it
// failed), with b its state at the start of that step: a step that would take it onto the ground
// lands it at t + dt (the caller sets it at rest), otherwise it exited or failed at t, with the
// reason (for an exit: where one more step would have taken it). With "outside": "remove", a
// body that left the grid is hidden from then on (st->hidden). Writes st's status, t_stop,
// reason and hidden; returns the status.
BodyStatus stop_body(const Model& m, const BodyType& type, size_t i, double t, StepOutcome out,
                     const std::string& failure, const BodyState& b, State* st);

}  // namespace lrigid
