// Bodies meeting the ground and the grid's solids in the steps (docs/contacts.md): after each
// step, a body near a surface gets the contact kernel's impulses (effects/contact.h
// contact_resolve, through its generalized 6x6 mass) and a position correction; it is then
// flying, sliding or resting, and a body that rested long enough sleeps. The scalar step
// (simulation.cpp) and the batched steps (batch_lanes.h drive_block) call the same functions
// here, so the contact is written once; the batched steps call them only for the lanes their
// one comparison finds near a surface.
#pragma once
#include "integrate/integrators.h"
#include "model/model.h"
#include "model/state.h"

namespace lrigid {

// Sweeps of the projected Gauss-Seidel over a body's touching points.
constexpr int kContactPasses = 12;
// A body rests when each of its touching points moves slower than this fraction of
// Model::rest_speed (and sleeps after Model::sleep_time of rest).
constexpr double kRestFraction = 0.1;

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
// What the last wall query of a body found: its centre x and the wall distance d there. The
// grid's wall distance is trilinear in node values that differ by at most the spacing between
// neighbouring nodes (an exact distance), so each of its partial derivatives is at most 1 and its
// gradient at most sqrt(3): while the centre stays within (d - reach) / sqrt(3) of x, no point of
// the body can reach a wall, and the scalar step skips the query (the batched steps compare the
// wall distance their samples carry instead). Not valid across the sign jump where a grid box
// reaches beyond a non-rectangular mesh (docs/grid-format.md); bodies there leave the grid.
struct WallClearance {
  Vec3 x = Vec3::Zero();
  double radius = -1;  // m; < 0: no query yet
};

// start: the state at the start of the step, or null. With it, a body that was flying and hits
// a surface faster than Model::rest_speed has the impact taken where it happened inside the step
// (impact_inside_step), not at the step's end.
bool contact_after_step(const Model& model, const BodyType& type, size_t i, double t_end,
                        BodyState* b, State* st, WallClearance* clearance = nullptr,
                        const BodyState* start = nullptr);

// An impact inside the step (issue 28, events located inside the step): the step from a (at
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

// A step from b that left the fluid below the grid while heading into the ground (the ground
// often is the grid's bottom): the contact at the start of the step with the points' positions
// one step ahead (velocity only, a speculative contact), so that the step can be taken again.
// Returns true when an impulse was applied.
bool speculative_ground_contact(const Model& model, const BodyType& type, BodyState* b);

// Could the flow move body b, lying at rest on a surface of world normal n (from the surface
// into the fluid), at time t, with a gust of `gust` m/s added to the turbulence it sees along the
// mean flow? The effects' wrench on it held still (gravity, buoyancy, drag, lift, the fluid's
// acceleration: effect_wrench): true when it would lift the body off (no force pressing it onto
// the surface) or its tangential part exceeds the friction mu times the pressing force, or (a
// sphere or an ellipsoid with rolling resistance) when its torque about the touching point
// exceeds mu_r |r| times the pressing force, so that it would roll. Tipping over (the torque
// about an edge) is not tested, nor rolling without rolling resistance.
bool flow_can_move(const Model& model, const BodyType& type, const BodyState& b, const Vec3& n,
                   double t, double gust);

// The smallest gust (m/s, along the mean flow) that moves body b at rest (flow_can_move): 0 when
// the flow moves it without one; +infinity when none up to kMaxGustSigmas standard deviations
// of the turbulence at b (sigma, m/s) does. Found by bisection to 1e-4 of that range.
constexpr double kMaxGustSigmas = 6.0;
double wake_gust(const Model& model, const BodyType& type, const BodyState& b, const Vec3& n,
                 double t, double sigma);

// Does a sleeping body of this type keep a gust watch? Those that see the turbulence through
// the "seen" model: their u' is an OU process of the fluid alone, which the watch can follow
// without stepping the body. Others sleep only where a gust of kGustSigmas standard deviations
// could not move them (and then until their flow changes).
constexpr double kGustSigmas = 3.0;
bool keeps_gust_watch(const Model& model, const BodyType& type);

// Sleeping body i's gust watch advanced to step `upto` at least (the OU coefficients at the body
// are those of the flow where and when it fell asleep: the field is steady for it until
// wake_bodies wakes it at the next frame). Returns the step the body wakes at: the first step
// whose u' along the mean flow reaches the watch's gust (the step after the update that reached
// it), or GustWatch::kNever when not by `upto`. u' along the mean flow follows the seen model's
// exact OU update with Thomson's drift for a body at rest, drawn from its own counter-based
// stream (seed, body, step); far below the gust the watch takes many steps in one draw of their
// exact sum, where it cannot reach the gust in between but with a probability below 1e-13
// (kWatchStrideSigmas); the other components of u' are drawn at the wake, exactly. The wake
// step and u' there do not depend on threads, stretches, `upto` or a resumed run.
constexpr double kWatchStrideSigmas = 7.5;
constexpr uint64_t kWatchMaxStride = 1024;
uint64_t watch_sleeper(const Model& model, State* st, size_t i, uint64_t upto);

// Wakes sleeping body i: status Moving, at rest, resting count reset, its watch closed; returns
// the u' its watch followed (the state's u_seen without a watch), which the caller puts into the
// body's state when the watch woke it.
Vec3 wake_sleeper(State* st, size_t i);

// At the start of a stretch of steps [first, last): sleeping bodies whose flow has changed since
// they fell asleep (a time-dependent field has passed a frame time since st.t_stop) wake up, and
// so do those whose gust watch reaches its gust by step `first`; the watches of the others are
// advanced to `last`. Bodies [n0, n).
void wake_bodies(const Model& model, State* st, size_t n0, size_t n, uint64_t first,
                 uint64_t last);

// A sleeping body that its watch wakes inside the stretch ending at `last`: the steps take it
// (as a dormant lane or from its wake step) and wake it then.
inline bool wakes_before(const State& st, size_t i, uint64_t last) {
  return st.status[i] == BodyStatus::Sleeping && i < st.watch.size() && st.watch[i].valid &&
         st.watch[i].wake < last;
}

// Marks body i as flying (no surface near it after its step): one comparison when it already is.
inline void mark_flying(State* st, size_t i) {
  if (st->contact[i] != ContactState::Flying) {
    st->contact[i] = ContactState::Flying;
    st->rest_steps[i] = 0;
  }
}

}  // namespace lrigid
