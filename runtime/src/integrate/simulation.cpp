#include "integrate/simulation.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numeric>
#include <string>

#include "contact/bodies.h"
#include "contact/pair_geometry.h"
#include "contact/sleep.h"
#include "integrate/integrators.h"
#include "integrate/rigid_batch.h"
#include "integrate/step_end.h"
#include "integrate/sweep.h"

namespace lrigid {

uint64_t output_stride(const Model& model, double every) {
  const double r = std::round(every / model.dt);
  return r < 1 ? 1 : static_cast<uint64_t>(r);
}

namespace {

// the last time a stretch of steps ending at step `last` samples: an RK4 stage at t + dt may
// round a little beyond last * dt
double stream_window_end(const Model& m, uint64_t last) {
  return static_cast<double>(last) * m.dt * (1 + 1e-12) + 1e-9 * m.dt;
}

// a streamed field's frames change at frame times: a stretch of steps ends before the next one
// (or is the single step crossing it), so at most 3 frames are resident
uint64_t stream_stretch_end(const Model& m, uint64_t first, uint64_t last) {
  if (!m.field.is_streamed()) return last;
  const double t_next = m.field.next_frame_time(static_cast<double>(first) * m.dt);
  uint64_t end = first + 1;
  while (end < last && stream_window_end(m, end + 1) < t_next) ++end;
  return end;
}

// The longest stretch of steps between two rebuilds of the work list: bodies that stopped or
// fell asleep leave their blocks at the next stretch (a block steps all its lanes), so without a
// bound a body asleep right after an output would cost its lane until the next output, or to
// the end of a run that writes only there. Measured (bench/contacts/run.py, 200 bodies, 20 s,
// outputs every 5 s): see docs/contacts.md; a stretch's own cost is loading and sampling its
// blocks once, under 1 % of 256 steps.
constexpr uint64_t kStretchSteps = 256;

// With contacts between bodies: the most steps of a speculative stretch (ContactStretches below;
// the steps to the next output are cut into equal stretches: 2 of 25 steps between the leaves
// scene's outputs). Measured on the leaves scene's bodies x5 in flight, 1 thread: stretches of 25
// steps took 13 % less time than stretches of 16 (a stretch's start, its broad phase and loading
// its blocks) and 9 % less than stretches of 50 (more bodies met another, taken again).
constexpr uint64_t kContactStretchSteps = 32;

// Advances body i (scalar step) from step `first` to `last`; returns the steps it took. sweep:
// null, or the stretch's record of the bodies' motion (sweep.h), which gets the body's.
uint64_t advance_body(const Model& model, State& st, int64_t i, uint64_t first, uint64_t last,
                      StretchSweep* sweep) {
  uint64_t body_steps = 0;
  const BodyType& type = model.types[st.type[i]];
  BodyState b = load_body(st, size_t(i));
  const bool keep_start = model.has_ground || model.contacts();
  WallClearance clearance;
  // the state at the start of the step, for an event located inside it (step_end.h)
  BodyState start;
  // a sleeping body that its gust watch wakes in this stretch is stepped from its wake on
  uint64_t wake = st.status[i] == BodyStatus::Sleeping ? st.watch[i].wake : first;
  for (uint64_t k = first; k < last; ++k) {
    if (k < wake) k = wake;
    if (k >= last) break;
    if (k == wake && st.status[i] == BodyStatus::Sleeping) b.u_seen = wake_sleeper(&st, size_t(i));
    const double t = static_cast<double>(k) * model.dt;
    std::string reason;
    if (keep_start) start = b;
    StepOutcome out = step_body(model, type, static_cast<uint32_t>(i), k, t, &b, &reason);
    bool floor_impact = false, retaken = false;
    if (out == StepOutcome::Exited)
      out = retry_into_ground(model, type, size_t(i), k, t, &b, &start, &reason, &st,
                              &floor_impact, &retaken);
    if (out == StepOutcome::Ok) ++body_steps;
    const StepEnd end = finish_step(model, type, size_t(i), t, last, out, reason, true, nullptr,
                                    floor_impact ? nullptr : &start, &clearance, &b, &st);
    if (end.next == AfterStep::Stopped) {
      if (sweep) sweep->stop(size_t(i), k);
      break;
    }
    if (sweep && end.next == AfterStep::Moving) sweep->set(size_t(i), k, b);
    if (end.next == AfterStep::Asleep) {
      if (sweep) {
        sweep->slept[i] = 1;
        sweep->hold(size_t(i), k, b);
      }
      // asleep until its watch wakes it, in this stretch or a later one
      wake = end.wake;
      if (wake >= last) break;
    }
  }
  store_body(b, size_t(i), &st);
  if (sweep) sweep->steps[i] += uint32_t(body_steps);
  return body_steps;
}

// The bodies a stretch advances: those still moving in [n0, n) and those a gust watch wakes
// before its end (integrate/impacts.h), the batched step's types in
// blocks of kBatch bodies of one type (or of types that step alike, BodyType::steps_as), the
// others one by one. Rebuilt for every stretch, so
// bodies that stopped leave the blocks.
struct WorkList {
  std::vector<std::vector<uint32_t>> blocks;
  std::vector<int64_t> scalar;
};

WorkList work_list(const Model& model, const State& st, const std::vector<StepKind>& kinds,
                   const std::vector<uint32_t>& bodies, uint64_t last) {
  WorkList w;
  std::vector<std::vector<uint32_t>> open(model.types.size());
  for (const uint32_t i : bodies) {
    if (st.status[i] != BodyStatus::Moving && !wakes_before(st, size_t(i), last)) continue;
    const uint16_t t = model.types[st.type[i]].steps_as;
    if (kinds[t] == StepKind::Scalar) {
      w.scalar.push_back(i);
      continue;
    }
    open[t].push_back(static_cast<uint32_t>(i));
    if (open[t].size() == size_t(kBatch)) {
      w.blocks.push_back(std::move(open[t]));
      open[t].clear();
    }
  }
  for (auto& b : open)
    if (!b.empty()) w.blocks.push_back(std::move(b));
  return w;
}

struct StepCounts {
  uint64_t body_steps = 0, handoffs = 0, newton = 0;
};

// The work list's bodies through steps [first, last), on `threads` threads (the results do not
// depend on them); sweep: null, or the record of their motion (sweep.h).
StepCounts advance_work(const Model& model, State& st, const WorkList& work, uint64_t first,
                        uint64_t last, int threads, StretchSweep* sweep) {
  uint64_t body_steps = 0, handoffs = 0, newton = 0;
  const auto nblocks = static_cast<int64_t>(work.blocks.size());
  const auto nscalar = static_cast<int64_t>(work.scalar.size());
  // (one thread for a single unit of work: a stretch of one step, with contacts between
  // bodies, would otherwise wake the threads for nothing)
#pragma omp parallel num_threads(threads) reduction(+ : body_steps, handoffs, newton) \
    if (nblocks + nscalar > 1)
  {
#pragma omp for schedule(dynamic, 4) nowait
    for (int64_t k = 0; k < nblocks; ++k) {
      const std::vector<uint32_t>& blk = work.blocks[k];
      const uint16_t t = st.type[blk[0]];
      const BlockStats b = advance_rigid_block(model, model.types[t], &st, blk.data(),
                                               static_cast<int>(blk.size()), first, last, sweep);
      body_steps += b.body_steps;
      handoffs += b.scalar_steps;
      newton += b.newton_steps;
    }
#pragma omp for schedule(static)
    for (int64_t k = 0; k < nscalar; ++k)
      body_steps += advance_body(model, st, work.scalar[k], first, last, sweep);
  }
  return {body_steps, handoffs, newton};
}

// Sleeping bodies of the list woken by a changed flow or their gust watch at the start of the
// stretch [first, last), the others' watches advanced (each body's own, so chunks of bodies go
// to the threads)
void wake_list(const Model& model, State& st, const std::vector<uint32_t>& bodies, uint64_t first,
               uint64_t last, int threads) {
  constexpr int64_t kWakeChunk = 256;
  const auto nb = static_cast<int64_t>(bodies.size());
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1) if (nb > kWakeChunk)
  for (int64_t c = 0; c < nb; c += kWakeChunk)
    for (int64_t k = c; k < std::min(nb, c + kWakeChunk); ++k)
      wake_bodies(model, &st, bodies[k], bodies[k] + 1, first, last);
}

// A stretch [first, last) with contacts between bodies ends where the lockstep would wake a
// sleeping body because its flow changed (sleep.h wake_bodies: at the first step whose start
// time reaches the next frame time after the body fell asleep), so that the next stretch wakes it
// at its start as the lockstep does.
uint64_t flow_wake_end(const Model& model, const State& st, uint64_t first, uint64_t last) {
  if (model.field.frame_count() < 2 && !model.field.is_streamed()) return last;
  double t_wake = HUGE_VAL;
  for (size_t i = 0; i < st.size(); ++i) {
    if (st.status[i] != BodyStatus::Sleeping) continue;
    const double t = model.field.next_frame_time(st.t_stop[i]);
    if (!(t <= st.t)) t_wake = std::min(t_wake, t);  // (else it wakes at this stretch's start)
  }
  uint64_t end = first + 1;
  while (end < last && !(t_wake <= static_cast<double>(end) * model.dt)) ++end;
  return end;
}

// Contacts between bodies in speculative stretches of several steps (docs/contacts.md, "Bodies
// against each other"). The lockstep, every body one step at a time with the stage
// (contact/bodies.h) after each step, loads and samples each body's block every step; instead
// every body takes the stretch's steps as it would without the stage, from a copy of the state at
// the stretch's start, while the drivers record the space each sweeps (sweep.h). The stage does
// nothing to a body whose box (the one the stage gives it: its shape's box widened by what it
// closes in a step) meets no other box (a body touching another at the start, without a colliding
// ground or wall, is marked flying by it: such a body is taken again below): a body whose boxes
// over the stretch (PairBox) meet no other body's took exactly the lockstep's steps, and keeps
// them. The others, and each body whose boxes their new motion reaches, are taken back to the
// copy and take the stretch again in lockstep with the stage restricted to them, until no new
// body is reached (the set only grows, so this ends). The state is then the lockstep's, bitwise: a
// block's lane does not depend on the other lanes (BatchLanes.ABlockEndsWhereItsBodiesEnd...),
// and a block with a sweep takes between two steps what a store and a load do to a lane.
class ContactStretches {
  // bodies taken again in lockstep from which its steps go to the threads
  static constexpr size_t kParallelBodies = 256;
  // A moving body's box over the stretch, as first taken, is widened by this much of its
  // bounding radius: a body taken again whose new motion stays within it meets only the bodies
  // that box met (measured on the leaves scene's bodies x5: without it a third of the bodies
  // taken again leave their box, with 0.5 of the radius 2 %, each then tested against every body)
  static constexpr double kSlack = 0.5;

 public:
  ContactStretches(const Model& model, const std::vector<StepKind>& kinds, size_t n,
                   uint64_t max_steps, int threads)
      : model_(model), kinds_(kinds), threads_(threads), all_(n) {
    std::iota(all_.begin(), all_.end(), 0u);
    sweep_.resize(n, max_steps);
    scratch_.rest_before.assign(n, 0);
    moving_.assign(n, 0);
    again_.assign(n, 0);
    box_.assign(n, PairBox{});
    near_.resize(n);
  }

  // Every body through the stretch [first, last) (the state at step `first`); adds the steps
  // taken to *counts and the stage's counts to *pairs. Returns whether the stretch was taken in
  // lockstep from its start: where at least half the moving bodies pressed against another in
  // the last step (a pile, a heap: their speculative steps would be thrown away). The choice is
  // the state's (its impulses, State::pair_impulses), so a resumed run makes it again.
  bool run(State* state, uint64_t first, uint64_t last, StepCounts* counts,
           BodyContactStats* pairs) {
    if (crowded(*state)) {
      run_lockstep(state, first, last, counts, pairs);
      return true;
    }
    State& st = *state;
    start_ = st;
    wake_list(model_, st, all_, first, last, threads_);
    const WorkList work = work_list(model_, st, kinds_, all_, last);
    sweep_.begin(first, last);
    boxed_.clear();
    for (const uint32_t i : all_) {
      if (!in_body_contacts(st, i)) continue;
      boxed_.push_back(i);
      moving_[i] = st.status[i] == BodyStatus::Moving || wakes_before(st, i, last);
      // (the stage would mark it flying after its first step)
      again_[i] = moving_[i] && !model_.contacts() && st.contact[i] != ContactState::Flying;
      begin_body(st, i);
    }
    StepCounts c = advance_work(model_, st, work, first, last, threads_, &sweep_);
    // a body that fell asleep in a changing flow: the lockstep may wake it inside the stretch
    const bool flow_changes = model_.field.frame_count() >= 2 || model_.field.is_streamed();
    for (const uint32_t i : boxed_)
      if (flow_changes && sweep_.slept[i]) again_[i] = 1;
    find_touching(st);
    std::vector<uint32_t> redo;
    for (const uint32_t i : boxed_)
      if (again_[i]) redo.push_back(i);
    for (const uint32_t i : redo) forget(i, &c);
    // the islands' impulses after the stretch's last step (the next step's warm start): every
    // body of an island then is taken again, so those the last lockstep leaves, and none without
    if (redo.empty()) st.pair_impulses.clear();
    while (!redo.empty()) {
      StepCounts rc;
      BodyContactStats rp;
      lockstep(&st, redo, first, last, true, &rc, &rp);
      c.newton += rc.newton;
      // the bodies kept so far that the new motion reaches: a body's new box within its box
      // before meets only bodies that box met (a body taken again may be woken by the stage, and
      // wake the sleeping bodies touching it: pairs of two bodies asleep count here)
      std::vector<uint32_t> reached;
      for (const uint32_t i : redo) {
        const PairBox b = stretch_box(st, i);
        auto reach = [&](uint32_t j) {
          if (!again_[j] && overlap(b, box_[j]) && touch(st, i, j, true)) reached.push_back(j);
        };
        if (inside(b, box_[i])) {
          for (const uint32_t j : near_[i]) reach(j);
        } else {
          for (const uint32_t j : boxed_) reach(j);
        }
      }
      if (reached.empty()) {
        c.body_steps += rc.body_steps;
        c.handoffs += rc.handoffs;
        pairs->touching += rp.touching;
        pairs->woken += rp.woken;
        break;
      }
      // (and the lockstep is taken again with them)
      for (const uint32_t i : reached)
        if (!again_[i]) {
          again_[i] = 1;
          forget(i, &c);
        }
      redo.clear();
      for (const uint32_t i : boxed_)
        if (again_[i]) redo.push_back(i);
    }
    for (const uint32_t i : boxed_) again_[i] = 0;
    counts->body_steps += c.body_steps;
    counts->handoffs += c.handoffs;
    counts->newton += c.newton;
    return false;
  }

 private:
  // Whether at least half the moving bodies carry an impulse against another body from the last
  // step (run)
  bool crowded(const State& st) {
    size_t pressed = 0;
    for (const PairImpulse& p : st.pair_impulses) {
      if (p.b == PairImpulse::kSurface) continue;
      for (const uint32_t i : {p.a, p.b})
        if (!again_[i] && st.status[i] == BodyStatus::Moving) again_[i] = 1, ++pressed;
    }
    if (pressed == 0) return false;
    for (const PairImpulse& p : st.pair_impulses)
      if (p.b != PairImpulse::kSurface) again_[p.a] = again_[p.b] = 0;
    size_t moving = 0;
    for (const uint32_t i : all_) moving += st.status[i] == BodyStatus::Moving;
    return 2 * pressed >= moving;
  }

  // The stretch [first, last) in lockstep from its start: the bodies taking part in the stage one
  // step at a time with it, the others (hidden) through the stretch at once, as a speculative
  // stretch takes them.
  void run_lockstep(State* state, uint64_t first, uint64_t last, StepCounts* counts,
                    BodyContactStats* pairs) {
    State& st = *state;
    sweep_.begin(first, last);
    boxed_.clear();
    others_.clear();
    for (const uint32_t i : all_) (in_body_contacts(st, i) ? boxed_ : others_).push_back(i);
    wake_list(model_, st, others_, first, last, threads_);
    const WorkList work = work_list(model_, st, kinds_, others_, last);
    const StepCounts c = advance_work(model_, st, work, first, last, threads_, &sweep_);
    counts->body_steps += c.body_steps;
    counts->handoffs += c.handoffs;
    counts->newton += c.newton;
    lockstep(&st, boxed_, first, last, false, counts, pairs);
  }

  // body i (taking part in the stage) at the start of the stretch: no steps yet, and a sleeping
  // body that wakes in the stretch asleep where it is until then (a moving body's steps fill each
  // step of the sweep; one asleep throughout stays in the state, slot())
  void begin_body(const State& st, uint32_t i) {
    if (st.status[i] == BodyStatus::Moving || !moving_[i]) {
      sweep_.start(i, st.x[i]);
      return;
    }
    sweep_.start_asleep(i, still(st, i));
  }

  static BodyState still(const State& st, uint32_t i) {
    BodyState b;
    b.x = st.x[i];
    b.q = st.q[i];
    b.v = b.w = b.u_seen = Vec3::Zero();
    return b;
  }

  // Body i after step k as the stage takes it (StretchSweep::Slot); false: it takes no part then.
  bool slot(const State& st, uint32_t i, uint64_t k, StretchSweep::Slot* s) const {
    if (!moving_[i]) {
      s->x = st.x[i];
      s->q = st.q[i];
      s->v2 = s->w2 = -1;
      return true;
    }
    *s = sweep_.at(i, k);
    return !std::isnan(s->x.x());
  }

  // The margin the stage gives a body of this type in a slot (v2 < 0: asleep), or a little more
  // (it turns the velocities into the world frame first, and a block in single precision gave
  // the squared speeds), m
  double margin(const BodyType& type, double v2, double w2) const {
    if (v2 < 0) return kPairSkin;
    return pair_margin(type, std::sqrt(v2), std::sqrt(w2), model_.dt) * (1 + 1e-6);
  }

  // A box holding body i's boxes in the stage at every step of the stretch: each step's centre,
  // within the shape's bounding radius and the greatest margin (1e-7 m more for the round-off);
  // for a body asleep throughout, its shape's box widened by the skin. An empty box (lo > hi)
  // for a body that stopped in its first step.
  PairBox stretch_box(const State& st, uint32_t i) const {
    PairBox b;
    if (!moving_[i]) {
      b = still_pair_box(model_, st, i);
      b.lo.array() -= 1e-7;
      b.hi.array() += 1e-7;
      return b;
    }
    const BodyType& type = model_.types[st.type[i]];
    const double pad =
        (type.pair->radius + margin(type, std::max(sweep_.v2max[i], 0.0), sweep_.w2max[i])) *
            (1 + 1e-9) +
        1e-7;
    b.lo = sweep_.lo[i].array() - pad;
    b.hi = sweep_.hi[i].array() + pad;
    b.moving = true;
    return b;
  }

  static bool overlap(const PairBox& a, const PairBox& b) {
    return (a.lo.array() <= b.hi.array()).all() && (b.lo.array() <= a.hi.array()).all();
  }
  static bool inside(const PairBox& a, const PairBox& b) {
    return (b.lo.array() <= a.lo.array()).all() && (a.hi.array() <= b.hi.array()).all();
  }

  // Whether the stage would find bodies i and j touching after some step of the stretch
  // (pair_touches), one of them moving then (any: or not)
  bool touch(const State& st, uint32_t i, uint32_t j, bool any) const {
    const BodyType& ti = model_.types[st.type[i]];
    const BodyType& tj = model_.types[st.type[j]];
    for (uint64_t k = sweep_.first; k < sweep_.first + sweep_.len; ++k) {
      StretchSweep::Slot si, sj;
      if (!slot(st, i, k, &si) || !slot(st, j, k, &sj)) continue;
      if (!any && si.v2 < 0 && sj.v2 < 0) continue;
      const double mi = margin(ti, si.v2, si.w2), mj = margin(tj, sj.v2, sj.w2);
      // (their bounding spheres first)
      const double reach = (ti.pair->radius + tj.pair->radius + mi + mj) * (1 + 1e-9) + 1e-7;
      if ((si.x - sj.x).squaredNorm() > reach * reach) continue;
      if (pair_touches(model_, st.type[i], si.x, si.q, mi, st.type[j], sj.x, sj.q, mj)) return true;
    }
    return false;
  }

  // The bodies that may have met another in the stretch, marked in again_: each body's box over
  // the stretch (stretch_box, a moving one's widened by kSlack times its radius: box_) in the
  // stage's broad phase (two bodies asleep throughout too: near_ keeps every pair, for the
  // bodies taken again), then the pairs found there step by step (touch, on the threads).
  void find_touching(const State& st) {
    std::vector<PairBox> boxes(boxed_.size());
    for (size_t k = 0; k < boxed_.size(); ++k) {
      const uint32_t i = boxed_[k];
      near_[i].clear();
      box_[i] = stretch_box(st, i);
      if (moving_[i]) {
        const double slack = kSlack * model_.types[st.type[i]].pair->radius;
        box_[i].lo.array() -= slack;
        box_[i].hi.array() += slack;
      }
      boxes[k] = box_[i];
      boxes[k].moving = true;
    }
    const std::vector<std::pair<int, int>> pairs = overlapping_pair_boxes(boxes);
    std::vector<uint8_t> met(pairs.size(), 0);
    const auto np = static_cast<int64_t>(pairs.size());
#pragma omp parallel for num_threads(threads_) schedule(dynamic, 16) if (np > 64)
    for (int64_t p = 0; p < np; ++p) {
      const uint32_t i = boxed_[pairs[p].first], j = boxed_[pairs[p].second];
      // (the boxes without the slack first)
      met[p] = !(again_[i] && again_[j]) && overlap(stretch_box(st, i), stretch_box(st, j)) &&
               touch(st, i, j, false);
    }
    for (size_t p = 0; p < pairs.size(); ++p) {
      const uint32_t i = boxed_[pairs[p].first], j = boxed_[pairs[p].second];
      near_[i].push_back(j);
      near_[j].push_back(i);
      if (met[p]) again_[i] = again_[j] = 1;
    }
  }

  // body i will be taken again: the steps it took are not counted
  void forget(uint32_t i, StepCounts* c) const {
    c->body_steps -= sweep_.steps[i];
    c->handoffs -= sweep_.handoffs[i];
  }

  // Bodies `redo` (increasing), back to the stretch's start (from_start: they took its steps
  // speculatively), through it in lockstep with the stage restricted to them, recording their
  // motion.
  void lockstep(State* state, const std::vector<uint32_t>& redo, uint64_t first, uint64_t last,
                bool from_start, StepCounts* counts, BodyContactStats* pairs) {
    State& st = *state;
    // (a few bodies on one thread: a parallel region per step costs more than it saves)
    const int threads = redo.size() >= kParallelBodies ? threads_ : 1;
    // (the warm start of the stretch's first step)
    if (from_start) st.pair_impulses = start_.pair_impulses;
    for (const uint32_t i : redo) {
      if (from_start) restore(i, &st);
      moving_[i] = 1;  // (its slots say when it sleeps)
      sweep_.start_asleep(i, still(st, i));
    }
    for (uint64_t k = first; k < last; ++k) {
      st.step = k;
      st.t = static_cast<double>(k) * model_.dt;
      for (const uint32_t i : redo) scratch_.rest_before[i] = st.rest_steps[i];
      wake_list(model_, st, redo, k, k + 1, threads);
      const WorkList work = work_list(model_, st, kinds_, redo, k + 1);
      const StepCounts c = advance_work(model_, st, work, k, k + 1, threads, &sweep_);
      counts->body_steps += c.body_steps;
      counts->handoffs += c.handoffs;
      counts->newton += c.newton;
      st.step = k + 1;
      st.t = static_cast<double>(k + 1) * model_.dt;
      const BodyContactStats pc = body_contacts(model_, &st, &scratch_, redo, threads);
      pairs->touching += pc.touching;
      pairs->woken += pc.woken;
      // (the stage took each body after the step, before its impulses and corrections: what the
      // drivers recorded; an island it put to sleep sleeps where it left it)
      if (k + 1 < last)
        for (const uint32_t i : redo)
          if (st.status[i] == BodyStatus::Sleeping && sweep_.at(i, k).v2 >= 0)
            sweep_.hold(i, k + 1, load_body(st, i));
    }
  }

  // body i as it was at the stretch's start
  void restore(uint32_t i, State* state) const {
    State& st = *state;
    const State& s0 = start_;
    st.x[i] = s0.x[i];
    st.q[i] = s0.q[i];
    st.v[i] = s0.v[i];
    st.w[i] = s0.w[i];
    st.u_seen[i] = s0.u_seen[i];
    st.status[i] = s0.status[i];
    st.t_stop[i] = s0.t_stop[i];
    st.reason[i] = s0.reason[i];
    st.contact[i] = s0.contact[i];
    st.rest_steps[i] = s0.rest_steps[i];
    st.impacts[i] = s0.impacts[i];
    st.t_touch[i] = s0.t_touch[i];
    st.x_touch[i] = s0.x_touch[i];
    st.hidden[i] = s0.hidden[i];
    if (i < st.watch.size()) st.watch[i] = s0.watch[i];
    const size_t h = st.history_offset[i];
    if (h != State::kNoHistory) {
      const size_t stride = model_.types[st.type[i]].basset.stride();
      std::copy(s0.history.begin() + h, s0.history.begin() + h + stride, st.history.begin() + h);
    }
  }

  const Model& model_;
  const std::vector<StepKind>& kinds_;
  int threads_;
  std::vector<uint32_t> all_;  // bodies 0 .. n
  State start_;                // the state at the stretch's start
  StretchSweep sweep_;
  BodyContactScratch scratch_;
  std::vector<uint32_t> boxed_;  // the bodies taking part in the stage
  std::vector<uint32_t> others_;  // (run_lockstep: the bodies that do not)
  // per body: moves in the stretch (else asleep throughout); taken again in lockstep; its box
  // over the stretch as first taken (stretch_box), and the bodies whose boxes that box met
  std::vector<uint8_t> moving_, again_;
  std::vector<PairBox> box_;
  std::vector<std::vector<uint32_t>> near_;
};

// Bodies of [n0, n) whose release step (Model::release_step) has come join the run: moving and
// shown from `step` on, in the state initial_state gave them. Returns the next step a body of
// the range waits for (~0: none), where a stretch of steps ends so that it joins on time.
uint64_t release_due(const Model& model, State& st, int64_t n0, int64_t n, uint64_t step) {
  uint64_t next = ~uint64_t(0);
  if (model.release_step.empty()) return next;
  for (int64_t i = n0; i < n; ++i) {
    if (st.status[i] != BodyStatus::Unreleased) continue;
    if (model.release_step[i] <= step) {
      st.status[i] = BodyStatus::Moving;
      st.hidden[i] = 0;
    } else {
      next = std::min(next, model.release_step[i]);
    }
  }
  return next;
}

}  // namespace

StepKind step_kind(const Model& model, const BodyType& type, std::string* why_not_batched) {
  std::string why;
  if (rigid_batch_eligible(model, type, &why)) return StepKind::Batched;
  if (why_not_batched) *why_not_batched = why;
  return StepKind::Scalar;
}

const char* step_kind_name(StepKind kind) {
  switch (kind) {
    case StepKind::Batched: return "batched";
    case StepKind::Scalar: return "scalar";
  }
  return "scalar";
}

RunStats simulate(const Model& model, State* state, const RunOptions& options) {
  RunStats stats;
  if (options.live_stats) stats = *options.live_stats;
  State& st = *state;
  // states built by hand (tests) may lack the contact arrays
  const size_t nb = st.size();
  if (st.contact.size() != nb) st.contact.assign(nb, ContactState::Flying);
  if (st.rest_steps.size() != nb) st.rest_steps.assign(nb, 0);
  if (st.impacts.size() != nb) st.impacts.assign(nb, 0);
  if (st.t_touch.size() != nb) st.t_touch.assign(nb, std::nan(""));
  if (st.x_touch.size() != nb) st.x_touch.assign(nb, Vec3::Zero());
  if (st.hidden.size() != nb) st.hidden.assign(nb, 0);
  if (model.contacts() && st.watch.size() != nb) st.watch.assign(nb, GustWatch{});
  const uint64_t total_steps =
      static_cast<uint64_t>(std::llround(model.duration / model.dt));
  const uint64_t stride = output_stride(model, options.every);
  const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  // with contacts between bodies every process steps every body (a pair may span two ranks'
  // shares): the same results as one process
  const auto n = static_cast<int64_t>(
      model.body_contact ? st.size() : std::min(st.size(), options.body_end));
  const auto n0 = static_cast<int64_t>(
      model.body_contact ? 0 : std::min(st.size(), options.body_begin));
  BodyContactScratch pair_scratch;
  uint64_t next_release = release_due(model, st, n0, n, st.step);
  if (options.on_output && options.output_at_start) options.on_output(st);
  double wall = stats.wall_seconds;
  // body types that take the batched step (integrate/rigid_batch.h)
  std::vector<StepKind> kinds(model.types.size());
  for (size_t t = 0; t < model.types.size(); ++t)
    kinds[t] = step_kind(model, model.types[t], nullptr);
  std::vector<uint32_t> bodies(size_t(n - n0));
  std::iota(bodies.begin(), bodies.end(), uint32_t(n0));
  // with contacts between bodies: stretches of several steps, taken speculatively
  uint64_t stretch = !model.body_contact ? kStretchSteps
                                         : (options.contact_stretch > 0 ? options.contact_stretch
                                                                        : kContactStretchSteps);
  std::unique_ptr<ContactStretches> speculative;
  if (model.body_contact && stretch > 1)
    speculative = std::make_unique<ContactStretches>(model, kinds, size_t(n), stretch, threads);

  while (st.step < total_steps) {
    const uint64_t first = st.step;
    const uint64_t next_output = (first / stride + 1) * stride;
    const uint64_t to = std::min({total_steps, next_output, next_release});
    uint64_t len = std::min(to - first, stretch);
    if (model.body_contact) {
      // (stretches of equal lengths up to the next output or release)
      const uint64_t parts = (to - first + stretch - 1) / stretch;
      len = (to - first + parts - 1) / parts;
    }
    uint64_t last = stream_stretch_end(model, first, first + len);
    if (model.body_contact) last = flow_wake_end(model, st, first, last);
    model.field.prepare(static_cast<double>(first) * model.dt, stream_window_end(model, last));
    StepCounts counts;
    const auto t0 = std::chrono::steady_clock::now();
    if (model.body_contact && last > first + 1) {
      BodyContactStats pc;
      stats.lockstep_stretches += speculative->run(&st, first, last, &counts, &pc);
      stats.pair_steps += pc.touching;
      stats.pair_wakes += pc.woken;
    } else {
      if (model.body_contact) pair_scratch.rest_before = st.rest_steps;
      // sleeping bodies: woken by a changed flow or their gust watch, the watches advanced
      wake_list(model, st, bodies, first, last, threads);
      const WorkList work = work_list(model, st, kinds, bodies, last);
      counts = advance_work(model, st, work, first, last, threads, nullptr);
      if (model.body_contact) {
        // the contacts between bodies, after every body has taken the step (contact/bodies.h)
        st.step = last;
        st.t = static_cast<double>(last) * model.dt;
        const BodyContactStats pc =
            body_contacts(model, &st, &pair_scratch, size_t(n0), size_t(n), threads);
        stats.pair_steps += pc.touching;
        stats.pair_wakes += pc.woken;
      }
    }
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    stats.body_steps += counts.body_steps;
    stats.scalar_handoffs += counts.handoffs;
    stats.newton_steps += counts.newton;
    st.step = last;
    st.t = static_cast<double>(last) * model.dt;
    if (next_release <= last) next_release = release_due(model, st, n0, n, last);
    if (options.live_stats) {
      *options.live_stats = stats;
      options.live_stats->steps = last;
      options.live_stats->wall_seconds = wall;
    }
    if (last % stride == 0 || last == total_steps) {
      if (options.on_sync) options.on_sync(st, last == total_steps);
      if (options.on_output) options.on_output(st);
    }
    if (options.on_progress) options.on_progress(st, double(last) / double(total_steps));
  }
  stats.steps = st.step;
  stats.wall_seconds = wall;
  stats.resting = 0;
  for (size_t i = 0; i < st.size(); ++i) {
    const BodyStatus s = st.status[i];
    if (s == BodyStatus::Landed) ++stats.landed;
    if (s == BodyStatus::Exited) ++stats.exited;
    if (s == BodyStatus::Failed) ++stats.failed;
    stats.resting += s == BodyStatus::Sleeping ||
                     (s == BodyStatus::Moving && st.contact[i] == ContactState::Resting);
  }
  return stats;
}

}  // namespace lrigid
