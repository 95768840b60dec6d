// The contact pass after each step (docs/contacts.md): a body near a surface gets the solver's
// impulses (contact/solver.h contact_resolve, through its generalized 6x6 mass) and a position
// correction; it is then flying, sliding or resting, and a body that rested long enough sleeps
// (contact/sleep.h). The scalar step (integrate/simulation.cpp) and the batched steps
// (integrate/batch_lanes.h drive_block) call it through integrate/impacts.h contact_after_step,
// which hands it the impact located inside the step, so the contact is written once; the
// batched steps call it only for the lanes their one comparison finds near a surface.
#pragma once
#include <cstddef>

#include "contact/touching.h"
#include "model/body_state.h"
#include "model/model.h"
#include "model/state.h"

namespace lrigid {

// Sweeps of the projected Gauss-Seidel over a body's touching points.
constexpr int kContactPasses = 12;
// A body rests when each of its touching points moves slower than this fraction of
// Model::rest_speed (and sleeps after Model::sleep_time of rest).
constexpr double kRestFraction = 0.1;

// An impact located inside the step, taken by the layer that steps bodies (integrate/impacts.h
// impact_inside_step): take(ctx, b, st) takes the step again split where the impact happened,
// leaves b at the step's end and counts the impact; false (b untouched) where it cannot.
struct InStepImpact {
  bool (*take)(const void* ctx, BodyState* b, State* st) = nullptr;
  const void* ctx = nullptr;
};

// The contact pass on body i after a step to t_end that succeeded, with b its new state:
// gathers the shape's points that reach the ground plane (ground.contact "collide") or a wall
// distance <= 0 (walls.contact "collide"; the normal is the normalised gradient of the wall
// distance), resolves them with contact_resolve, and moves the body out of the surface. The
// trapezoidal position update of the splitting step (x += h/2 (V0 + V1)) used the velocity
// before the impulse: it is moved by h/2 times the velocity change (h/2 Δw for the rotation), so
// a body held still by friction does not creep by g h^2 / 2 a step; what remains of the
// penetration after that is removed along the deepest point's normal. Updates st's contact
// state, rest counter, impact count and first ground touchdown; a body that has rested for
// model.sleep_time is put to sleep (status Sleeping, at rest). Returns true when it fell asleep
// (the caller stops stepping it).
// impact: null, or the impact inside the step: a body that was flying and hits a surface faster
// than Model::rest_speed has it taken where it happened (impact->take), not at the step's end.
bool contact_pass(const Model& model, const BodyType& type, size_t i, double t_end, BodyState* b,
                  State* st, WallClearance* clearance = nullptr,
                  const InStepImpact* impact = nullptr);

// A step from b that left the fluid below the grid while heading into the ground (the ground
// often is the grid's bottom): the contact at the start of the step with the points' positions
// one step ahead (velocity only, a speculative contact), so that the step can be taken again.
// Returns true when an impulse was applied.
bool speculative_ground_contact(const Model& model, const BodyType& type, BodyState* b);

// Marks body i as flying (no surface near it after its step): one comparison when it already is.
inline void mark_flying(State* st, size_t i) {
  if (st->contact[i] != ContactState::Flying) {
    st->contact[i] = ContactState::Flying;
    st->rest_steps[i] = 0;
  }
}

}  // namespace lrigid
