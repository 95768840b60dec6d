#include "integrate/simulation.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "contact/bodies.h"
#include "contact/sleep.h"
#include "integrate/integrators.h"
#include "integrate/rigid_batch.h"
#include "integrate/step_end.h"

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

// Advances body i (scalar step) from step `first` to `last`; returns the steps it took.
uint64_t advance_body(const Model& model, State& st, int64_t i, uint64_t first, uint64_t last) {
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
    if (end.next == AfterStep::Stopped) break;
    if (end.next == AfterStep::Asleep) {
      // asleep until its watch wakes it, in this stretch or a later one
      wake = end.wake;
      if (wake >= last) break;
    }
  }
  store_body(b, size_t(i), &st);
  return body_steps;
}

// The bodies a stretch advances: those still moving in [n0, n) and those a gust watch wakes
// before its end (integrate/impacts.h), the batched step's types in
// blocks of kBatch bodies of one type, the others one by one. Rebuilt for every stretch, so
// bodies that stopped leave the blocks.
struct WorkList {
  std::vector<std::vector<uint32_t>> blocks;
  std::vector<int64_t> scalar;
};

WorkList work_list(const Model& model, const State& st, const std::vector<StepKind>& kinds,
                   int64_t n0, int64_t n, uint64_t last) {
  WorkList w;
  std::vector<std::vector<uint32_t>> open(model.types.size());
  for (int64_t i = n0; i < n; ++i) {
    if (st.status[i] != BodyStatus::Moving && !wakes_before(st, size_t(i), last)) continue;
    const uint16_t t = st.type[i];
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

  while (st.step < total_steps) {
    const uint64_t first = st.step;
    const uint64_t next_output = (first / stride + 1) * stride;
    const uint64_t last = stream_stretch_end(
        model, first,
        std::min({total_steps, next_output,
                  first + (model.body_contact ? 1 : kStretchSteps), next_release}));
    if (model.body_contact) pair_scratch.rest_before = st.rest_steps;
    model.field.prepare(static_cast<double>(first) * model.dt, stream_window_end(model, last));
    uint64_t body_steps = 0, handoffs = 0, newton = 0;
    const auto t0 = std::chrono::steady_clock::now();
    // sleeping bodies: woken by a changed flow or their gust watch, the watches advanced (each
    // body's own, so chunks of bodies go to the threads)
    constexpr int64_t kWakeChunk = 256;
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1) if (n - n0 > kWakeChunk)
    for (int64_t c = n0; c < n; c += kWakeChunk)
      wake_bodies(model, &st, size_t(c), size_t(std::min(n, c + kWakeChunk)), first, last);
    const WorkList work = work_list(model, st, kinds, n0, n, last);
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
                                                 static_cast<int>(blk.size()), first, last);
        body_steps += b.body_steps;
        handoffs += b.scalar_steps;
        newton += b.newton_steps;
      }
#pragma omp for schedule(static)
      for (int64_t k = 0; k < nscalar; ++k)
        body_steps += advance_body(model, st, work.scalar[k], first, last);
    }
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    stats.body_steps += body_steps;
    stats.scalar_handoffs += handoffs;
    stats.newton_steps += newton;
    st.step = last;
    st.t = static_cast<double>(last) * model.dt;
    if (model.body_contact) {
      // the contacts between bodies, after every body has taken the step (contact/bodies.h)
      const auto tp = std::chrono::steady_clock::now();
      const BodyContactStats pc =
          body_contacts(model, &st, &pair_scratch, size_t(n0), size_t(n), threads);
      wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - tp).count();
      stats.pair_steps += pc.touching;
      stats.pair_wakes += pc.woken;
    }
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
