// The end of a step, written once for both drivers: the scalar loop (simulation.cpp
// advance_body) and the batched block driver (batch_lanes.h drive_block) call these two
// functions for every body after its step, so a body meets the ground, a wall or a stop by the
// same rules whichever driver stepped it.
//
//   retry_into_ground  a step that left the fluid heading into a colliding ground (often the
//                      grid's floor): the impact located inside the step, or the speculative
//                      contact and the step taken again (integrate/impacts.h, contact/pass.h)
//   finish_step        a step that failed or exited stops the body (stops.h stop_body); one that
//                      succeeded takes the contact pass (impacts inside the step, impulses,
//                      resting, sleep: impacts.h contact_after_step) and the first touchdown's
//                      location, or lands on a "stop" ground at its located touchdown
#pragma once
#include <cstdint>
#include <string>

#include "contact/touching.h"
#include "model/body_state.h"
#include "model/model.h"
#include "model/state.h"

namespace lrigid {

// A step of body i from time t (step k) from the state *b that exited the fluid: when it heads
// into a colliding ground, the impact through the floor located inside the step (*floor_impact
// true, *b at the step's end; the step has no start state for the contact pass), or else the
// speculative contact at the start of the step and step_body again from there (*start becomes
// the state that step starts from). Returns the step's outcome after that: Exited unchanged, with
// *b the state at the start of the step, when neither applies. *retaken: the step was taken
// again (an impact through the floor or a second step_body).
StepOutcome retry_into_ground(const Model& model, const BodyType& type, size_t i, uint64_t k,
                              double t, BodyState* b, BodyState* start, std::string* reason,
                              State* st, bool* floor_impact, bool* retaken);

// What the driver does with the body after finish_step.
enum class AfterStep : uint8_t {
  Moving,   // it takes the next step
  Asleep,   // it fell asleep: stepped again from StepEnd::wake (if before the stretch's end)
  Stopped,  // landed, exited or failed: not stepped again
};

struct StepEnd {
  AfterStep next = AfterStep::Moving;
  uint64_t wake = 0;   // Asleep: the step its gust watch wakes it at (watch_sleeper)
  bool moved = false;  // the contact pass or a landing moved the body (a batched lane resamples)
};

// The end of step k of body i from time t, which ended in `out` (`reason` for a failure): *b is
// its state after the step (Ok) or at its start (otherwise). start: the state at the start of
// the step, or null (a step already split at an impact through the floor). near: the body may
// touch a colliding surface (the scalar driver passes true and lets `clearance` skip the wall
// query; the batched driver its one comparison per surface, and a body far from every surface
// is only marked flying). landed: whether *b touches the ground (stops.h touches_ground) as the
// driver found it, or null to test it here. A first ground touchdown that the contact pass
// records is moved to where it happened inside the step (record_touchdown from *start); on a
// "stop" ground a body that touches it lands where it first touched it (locate_touchdown).
// `last`: the end of the stretch of steps (a sleeper's watch is advanced to it).
StepEnd finish_step(const Model& model, const BodyType& type, size_t i, double t, uint64_t last,
                    StepOutcome out, const std::string& reason, bool near, const bool* landed,
                    const BodyState* start, WallClearance* clearance, BodyState* b, State* st);

// Whether finish_step has nothing to do but mark the body flying: a step that succeeded, far
// from every colliding surface, not landing on a "stop" ground. The batched driver asks this
// first, so that a lane in free flight is not taken out of its block.
inline bool step_end_is_quiet(const Model& model, StepOutcome out, bool near, bool landed) {
  return out == StepOutcome::Ok && !(model.contacts() && near) &&
         !(model.has_ground && !model.ground_collides() && landed);
}

}  // namespace lrigid
