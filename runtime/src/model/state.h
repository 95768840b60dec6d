// The mutable state of a run (the mjData of this project), one entry per body, structure of
// arrays. The step reads the constant Model and writes only this.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "model/model.h"

namespace lrigid {

// Moving: stepped (flying, sliding or resting: ContactState); Sleeping: resting where the flow
// cannot move it, not stepped until it changes (contact/sleep.h); Landed: stopped at the
// ground (ground.contact "stop"); Exited: left the grid (hidden from then on with "outside":
// "remove") or stopped at a solid (walls.contact "stop"); Failed: a non-finite state;
// Unreleased: waiting for its release time (bodies[i].release, Model::release_step), not
// stepped and hidden until then.
enum class BodyStatus : uint8_t {
  Moving = 0, Landed = 1, Exited = 2, Failed = 3, Sleeping = 4, Unreleased = 5
};
const char* body_status_name(BodyStatus s);
// How a moving body meets the surfaces after its last step (contact/pass.h).
enum class ContactState : uint8_t { Flying = 0, Sliding = 1, Resting = 2 };

// A sleeping body's gust watch (contact/sleep.h, docs/contacts.md "Resting, sleeping,
// waking"): the turbulent velocity u' it would see, kept evolving by its Ornstein-Uhlenbeck
// process while the body sleeps, and the gust along the mean flow that would move it. The body
// wakes at the first step where u' reaches the gust. The watch follows u' along the mean flow
// only (ua); the other two components, independent of it, are drawn at the wake.
struct GustWatch {
  static constexpr uint64_t kNever = ~uint64_t(0);
  Vec3 u = Vec3::Zero();  // u' (world frame, m/s) when the body fell asleep; at the wake, once
                          // the watch has found it
  double ua = 0;          // u' along the mean flow at t = step dt, m/s
  double gust = 0;        // m/s along the mean flow; +infinity: no gust the watch follows can
  uint64_t start = 0;     // the step the body fell asleep at
  uint64_t step = 0;      // the step the watch has reached (it may pass the one asked for)
  uint64_t wake = kNever; // the step the body wakes at, once the watch has found it
  uint8_t valid = 0;      // 1: set when the body fell asleep
};

// One contact point's impulses at the end of the last step's contacts between bodies
// (contact/bodies.h): the next step's projected Gauss-Seidel starts from them (warm start).
struct PairImpulse {
  static constexpr uint32_t kSurface = ~uint32_t(0);
  uint32_t a = 0, b = 0;  // the bodies, a < b; b = kSurface: a's point on the ground or a wall
  double r[3] = {};       // the point from a's centre of mass, world frame, m
  double jn = 0;          // normal impulse, N s (> 0)
  double jt[3] = {};      // tangential impulse on a, world frame, N s
};

struct State {
  double t = 0;                 // simulated time, s
  uint64_t step = 0;            // steps taken
  std::vector<Vec3> x;          // (nbody) centre of mass, world frame, m
  std::vector<Quat> q;          // (nbody) orientation, body -> world, unit
  std::vector<Vec3> v;          // (nbody) velocity of the centre of mass, body frame, m/s
  std::vector<Vec3> w;          // (nbody) angular velocity, body frame, rad/s
  std::vector<Vec3> u_seen;     // (nbody) turbulent fluid velocity seen, world frame, m/s
  std::vector<uint16_t> type;   // (nbody) index into Model::types
  std::vector<BodyStatus> status;  // (nbody)
  std::vector<double> t_stop;   // (nbody) time the body stopped (landed, exited, failed), s
  std::vector<std::string> reason;  // (nbody) why a body failed (empty otherwise)
  // contacts (contact/pass.h)
  std::vector<ContactState> contact;  // (nbody) after the body's last step
  std::vector<uint32_t> rest_steps;   // (nbody) steps it has rested in a row
  std::vector<uint32_t> impacts;      // (nbody) contact events: impacts after flying, faster
                                      // than Model::rest_speed
  std::vector<double> t_touch;        // (nbody) first touchdown on the ground, s (NaN: none)
  std::vector<Vec3> x_touch;          // (nbody) where (centre of mass), world, m
  std::vector<uint8_t> hidden;        // (nbody) 1: left the grid, "outside" is "remove"; or
                                      // not released yet
  std::vector<GustWatch> watch;       // (nbody, or 0 without contacts) sleeping bodies' gust
                                      // watches
  // contacts between bodies (contact/bodies.h): the points that carried an impulse in the last
  // step's islands, sorted by (a, b), a pair's points in the order they were solved in
  std::vector<PairImpulse> pair_impulses;
  // Basset history (effects/basset.h), only for body types with the effect:
  // body i owns history[history_offset[i], + model.types[type[i]].basset.stride())
  std::vector<double> history;        // (sum of strides)
  std::vector<size_t> history_offset; // (nbody)
  double* history_of(size_t i) {
    return history_offset[i] == kNoHistory ? nullptr : history.data() + history_offset[i];
  }
  static constexpr size_t kNoHistory = ~size_t(0);
  size_t size() const { return x.size(); }
  // What the outputs call the body's state: flying, sliding, resting, sleeping, exited, landed,
  // failed or unreleased.
  const char* state_name(size_t i) const;
  // the same as a number for the .pvd: 0 flying, 1 sliding, 2 resting, 3 sleeping, 4 exited,
  // 5 landed, 6 failed, 7 unreleased
  uint8_t state_code(size_t i) const;
};

// The names of the state codes, in code order (State::state_code).
constexpr int kStateCount = 8;
extern const char* const kStateNames[kStateCount];
// The code of a state name; -1 for a name that is none.
int state_code_from_name(const std::string& name);

}  // namespace lrigid
