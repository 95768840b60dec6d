// Contacts between bodies (scene key body_contact "collide"; docs/contacts.md "Bodies against
// each other"): after each step of every body, one stage finds the pairs that touch and solves
// them with the contacts against the ground and the walls, island by island.
//
//   broad phase   a uniform grid of cells over each body's bounding box (pair_aabb) widened by
//                 what the body closes in one step, and the narrow phase (contact/pair_geometry.h
//                 collide) on the overlapping pairs
//   waking        a sleeping body touched by one that is not resting wakes, with every sleeping
//                 body that touches it (its island); a sleeping body otherwise is a static surface
//   islands       bodies joined by touching pairs; each island's points (pairs, and each body's
//                 points on the ground and the walls, contact/touching.h gather) go to one
//                 projected Gauss-Seidel (contact/island.h island_resolve), which starts from the
//                 impulses of the last step's nearest point of the same pair (the warm start,
//                 State::pair_impulses) and leaves its own there for the next step
//   positions     the step's position update takes the velocity change as contact_pass does;
//                 half of what remains of the island's penetrations beyond a slop (50 um, less
//                 for thin bodies) is removed by Gauss-Seidel
//                 sweeps on the bodies' displacements (island_resolve's moves; positions only:
//                 no energy is added)
//   resting       a body whose every point stands still rests; an island whose bodies have all
//                 rested for Model::sleep_time, and that the flow as it is cannot move, sleeps
//
// The bodies' state is all there is: nothing is carried from one step to the next but what the
// state holds (the impulses of the warm start included, sorted by pair), so a resumed run and any
// thread count give the same results.
#pragma once
#include <cstdint>
#include <utility>
#include <vector>

#include "model/model.h"
#include "model/state.h"

namespace lrigid {

// The pair's material from the two bodies' "contact": the larger restitution, the geometric mean
// of the frictions, the larger rolling resistance (Box2D's mixing rules; docs/contacts.md).
struct PairMaterial {
  double restitution, friction, rolling;
};
PairMaterial pair_material(const ContactParams& a, const ContactParams& b);

// A point off a body by less than this (m) still counts as touching for waking and resting
// bodies and as a speculative point for one at rest.
constexpr double kPairSkin = 1e-4;

struct BodyContactStats {
  uint64_t touching = 0;      // pairs with contact points
  uint64_t woken = 0;         // sleeping bodies woken by a contact
};

// What the stage keeps between steps that is not state: the bodies' rest counts before the
// step (the step's own contact pass restarts them for bodies off the ground), and scratch.
struct BodyContactScratch {
  std::vector<uint32_t> rest_before;
};

// The stage after every body has taken step `step` - 1 (so that the state is at time step * dt).
// Bodies [n0, n) that are moving or sleeping take part; threads for the narrow phase and the
// islands (results do not depend on it).
BodyContactStats body_contacts(const Model& model, State* st, BodyContactScratch* scratch,
                               size_t n0, size_t n, int threads);
// The same for the bodies of a list (increasing): the stage restricted to them, as if the others
// were not there.
BodyContactStats body_contacts(const Model& model, State* st, BodyContactScratch* scratch,
                               const std::vector<uint32_t>& bodies, int threads);

// Whether body i takes part in the stage (moving or sleeping, not hidden).
bool in_body_contacts(const State& st, size_t i);

// The margin (m) the stage widens a moving body's box and narrow phase by: kPairSkin plus what
// it closes in one step of dt at speed |v| (m/s) and spin |w| (rad/s), its farthest point at
// type.reach from its centre of mass. A body that does not move gets kPairSkin alone.
inline double pair_margin(const BodyType& type, double speed, double spin, double dt) {
  return kPairSkin + (speed + spin * type.reach) * dt;
}

// For stretches of several steps (integrate/simulation.cpp): a box that holds every box the
// stage may give a body at the steps of a stretch, and whether the body moves in the stretch (a
// body asleep throughout is a static surface there).
struct PairBox {
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();  // world, m
  bool moving = false;
};
// The box the stage gives body i when it does not move: its shape's box at its pose widened by
// kPairSkin.
PairBox still_pair_box(const Model& model, const State& st, size_t i);
// The pairs (a < b, indices into boxes, sorted) whose boxes overlap with at least one of the two
// moving: the stage's broad phase (two bodies that do not move do not meet).
std::vector<std::pair<int, int>> overlapping_pair_boxes(const std::vector<PairBox>& boxes);
// Whether the stage finds contact points between two bodies of types type_a and type_b at poses
// (xa, qa) and (xb, qb) with margins margin_a and margin_b (m: kPairSkin, plus what a moving body
// closes in a step): their boxes widened by the margins overlap and the narrow phase
// (contact/pair_geometry.h collide) gives a point. A pair that has none is left alone by the
// stage; larger margins only add points.
bool pair_touches(const Model& model, uint16_t type_a, const Vec3& xa, const Quat& qa,
                  double margin_a, uint16_t type_b, const Vec3& xb, const Quat& qb,
                  double margin_b);

// The deepest penetration (m) between any two bodies of the state that are not stopped or
// hidden, and the pair (i < j) where it is (-1: none touch). For tests and studies.
double deepest_pair_overlap(const Model& model, const State& st, int* i_out = nullptr,
                            int* j_out = nullptr);

}  // namespace lrigid
