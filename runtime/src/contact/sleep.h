// Sleeping and waking (docs/contacts.md "Resting, sleeping, waking"): a body that rested long
// enough on a surface sleeps where the flow as it is cannot move it (flow_can_move, the effects'
// wrench on it held still), and is not stepped until its flow changes or its gust watch (the
// turbulence it would see, followed without stepping it) reaches a gust that could move it.
#pragma once
#include <cstddef>
#include <cstdint>

#include "model/body_state.h"
#include "model/model.h"
#include "model/state.h"
#include "util/types.h"

namespace lrigid {

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

// Body i, resting in b on a surface of world normal n after the step that ends at t_end, falls
// asleep unless the flow moves it as it is (returns false: it stays awake). Where the type keeps
// a gust watch, the watch starts from the u' the body sees now.
bool fall_asleep(const Model& model, const BodyType& type, size_t i, double t_end,
                 const Vec3& n, BodyState* b, State* st);

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

}  // namespace lrigid
