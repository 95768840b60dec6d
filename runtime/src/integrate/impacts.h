// Impacts located inside a step (docs/contacts.md): a body that hits a surface within a step has
// the step taken again in two parts, split where it happened, with the contact solver's impulses
// there. They run the step's deterministic part (integrate/integrators.h deterministic_substep,
// step_body_split), so they live with the steps; contact_after_step is the contact pass
// (contact/pass.h) with such an impact handed to it. The scalar step (simulation.cpp) and the
// batched steps (batch_lanes.h drive_block) call the same functions here.
#pragma once
#include <cstddef>

#include "contact/pass.h"
#include "contact/touching.h"
#include "integrate/integrators.h"
#include "model/body_state.h"
#include "model/model.h"
#include "model/state.h"

namespace lrigid {

// The contact pass after a step to t_end that succeeded (contact/pass.h contact_pass), b the new
// state. start: the state at the start of the step, or null. With it, a body that was flying and
// hits a surface faster than Model::rest_speed has the impact taken where it happened inside the
// step (impact_inside_step), not at the step's end. Returns true when the body fell asleep.
bool contact_after_step(const Model& model, const BodyType& type, size_t i, double t_end,
                        BodyState* b, State* st, WallClearance* clearance = nullptr,
                        const BodyState* start = nullptr);

// An impact inside the step (an event located inside the step): the step from a (at
// time t) to b (its end, through the surface, before any contact) is taken again in two parts.
// locate_event finds the first time tau where a contact point reaches the ground or a wall (the
// smallest of their signed distances along the step's Hermite interpolant); the scheme's
// deterministic part (deterministic_substep) goes from a to t + tau, the contact's impulses act
// there (contact_resolve on the points within a nanometre of the surface), and the deterministic
// part goes on from the state after them to the step's end. The turbulence the body sees ends
// as the whole step left it (b's u_seen). The impact is counted, and a first ground touchdown
// recorded at t + tau. So a bounce keeps the scheme's order: without it the impulse acts at the
// step's end, on the velocity the body would have had under the surface, and the depth is
// removed by a position correction, both errors of order dt per impact.
// Returns false and leaves b alone where it cannot (can_split_at_impact false, a already
// touching, a part of the step leaving the fluid): the contact then acts at the step's end.
bool impact_inside_step(const Model& model, const BodyType& type, size_t i, double t,
                        const BodyState& a, BodyState* b, State* st);

// The same for a step from a (time t) that left the fluid through the grid's bottom while
// heading into a colliding ground there (heads_into_ground; the ground is often the grid's
// floor, so the step's end has no sample): the touchdown's time is found by the deterministic
// part alone (deterministic_substep to a trial time, the points' smallest gap there; a trial
// that leaves the fluid is below), and the step is taken again split there (step_body_split).
// Returns true with a at the step's end; false (a untouched) where the step cannot be split or
// its second part leaves the fluid too (a body that does not bounce clear): the caller then
// takes the speculative contact.
bool impact_through_floor(const Model& model, const BodyType& type, size_t i, double t,
                          BodyState* a, State* st);

// Types whose step can be split at an impact: not with the Basset history (its history takes
// whole steps) nor with the body turbulence model (u' carries the body: its part of the motion
// is not the deterministic step's).
bool can_split_at_impact(const Model& model, const BodyType& type);

}  // namespace lrigid
