#include "view_sim.h"

#include <algorithm>
#include <cmath>

#include "compile/compile_model.h"
#include "integrate/simulation.h"

namespace lrigid::app {

namespace {

// a stretch of steps lasts about this long, so the window gets fresh frames and the controls act
// at once
constexpr double kStretchSeconds = 0.03;
// realtime pace: further behind the wall clock than this, the simulation is "behind" and the
// clock waits for it (no catching up in a burst afterwards)
constexpr double kMaxLag = 0.25;  // s
// rates are measured over windows this long
constexpr double kRateWindow = 1.0;  // s

double seconds(std::chrono::steady_clock::duration d) {
  return std::chrono::duration<double>(d).count();
}

}  // namespace

const char* pace_name(Pace p) {
  switch (p) {
    case Pace::RealTime: return "realtime";
    case Pace::Fast: return "fast";
    case Pace::Fixed: return "fixed";
  }
  return "?";
}

ViewSimulation::ViewSimulation(Scene scene, Model model, int threads, Pace pace, bool loop)
    : scene_(std::move(scene)), model_(std::move(model)), threads_(threads), loop_(loop),
      pace_(pace) {
  total_steps_ = static_cast<uint64_t>(std::llround(model_.duration / model_.dt));
  reset_state();
  publish();
}

ViewSimulation::~ViewSimulation() { stop(); }

void ViewSimulation::start() {
  if (worker_.joinable()) return;
  worker_ = std::thread([this] {
    try {
      loop();
    } catch (...) {
      std::lock_guard<std::mutex> lk(mu_);
      failure_ = std::current_exception();
      quit_ = true;
      done_cv_.notify_all();
    }
  });
}

void ViewSimulation::stop() {
  {
    std::lock_guard<std::mutex> lk(mu_);
    quit_ = true;
  }
  cv_.notify_all();
  done_cv_.notify_all();
  if (worker_.joinable()) worker_.join();
}

void ViewSimulation::toggle_pause() {
  std::lock_guard<std::mutex> lk(mu_);
  paused_ = !paused_;
  // the published frame says so at once (the worker may be busy with a stretch)
  frame_.paused = paused_;
  ++frame_.version;
  cv_.notify_all();
  done_cv_.notify_all();
}

void ViewSimulation::scale_mean_flow(double factor) {
  std::lock_guard<std::mutex> lk(mu_);
  flow_factor_ *= factor;
  cv_.notify_all();
}

void ViewSimulation::scale_turbulence(double factor) {
  std::lock_guard<std::mutex> lk(mu_);
  turb_factor_ *= factor;
  cv_.notify_all();
}

void ViewSimulation::restart() {
  std::lock_guard<std::mutex> lk(mu_);
  restart_ = true;
  cv_.notify_all();
}

void ViewSimulation::set_pace(Pace p) {
  std::lock_guard<std::mutex> lk(mu_);
  pace_ = p;
  pending_steps_ = 0;
  served_ = requested_;
  frame_.pace = p;
  frame_.behind = false;
  ++frame_.version;
  cv_.notify_all();
  done_cv_.notify_all();
}

void ViewSimulation::advance_and_wait(double secs) {
  std::unique_lock<std::mutex> lk(mu_);
  if (paused_ || frame_.finished || quit_) return;
  const uint64_t steps = std::max<uint64_t>(1, uint64_t(std::llround(secs / model_.dt)));
  pending_steps_ += steps;
  const uint64_t ticket = ++requested_;
  cv_.notify_all();
  done_cv_.wait(lk, [&] { return served_ >= ticket || quit_ || paused_; });
}

bool ViewSimulation::latest(ViewFrame* f) {
  std::lock_guard<std::mutex> lk(mu_);
  if (frame_.version == f->version) return false;
  *f = frame_;
  return true;
}

void ViewSimulation::rethrow_failure() {
  std::lock_guard<std::mutex> lk(mu_);
  if (failure_) std::rethrow_exception(failure_);
}

void ViewSimulation::reset_state() {
  state_ = initial_state(model_, scene_);
  finished_ = false;
  behind_ = false;
  reanchor();
  window_start_ = Clock::now();
  window_t0_ = 0;
  window_integrate_ = 0;
  window_body_steps_ = 0;
}

void ViewSimulation::reanchor() {
  anchor_t_ = state_.t;
  anchor_wall_ = Clock::now();
}

void ViewSimulation::apply_controls() {
  // the scales only multiply what the step samples (integrate/dynamics.h, batch_lanes.h), read
  // afresh by every simulate() call: changing them between stretches is safe
  model_.mean_flow_scale *= flow_factor_;
  model_.turbulence_scale *= turb_factor_;
  flow_factor_ = turb_factor_ = 1;
  if (restart_) {
    restart_ = false;
    model_.seed += 1;  // initial_state and the noise are keyed by the model's seed
    reset_state();
  }
}

void ViewSimulation::publish() {
  // outside the lock: the copy of what is drawn
  ViewFrame f;
  const size_t n = state_.size();
  f.t = state_.t;
  f.duration = model_.duration;
  f.x = state_.x;
  f.q = state_.q;
  f.type = state_.type;
  f.status = state_.status;
  f.speed.resize(n);
  f.state.resize(n);
  for (size_t i = 0; i < n; ++i) {
    f.speed[i] = float(state_.v[i].norm());
    f.state[i] = state_.state_code(i);
    const BodyStatus s = state_.status[i];
    f.flying += s == BodyStatus::Moving;
    f.resting += s == BodyStatus::Landed || s == BodyStatus::Sleeping;
    f.exited += s == BodyStatus::Exited || s == BodyStatus::Failed;
  }
  f.body_steps_per_second = rate_body_steps_;
  f.busy = rate_busy_;
  f.sim_speed = rate_speed_;
  f.mean_flow_scale = model_.mean_flow_scale;
  f.turbulence_scale = model_.turbulence_scale;
  f.seed = model_.seed;
  f.finished = finished_;
  std::lock_guard<std::mutex> lk(mu_);
  f.behind = behind_ && pace_ == Pace::RealTime;
  f.paused = paused_;
  f.pace = pace_;
  f.version = frame_.version + 1;
  frame_ = std::move(f);
}

void ViewSimulation::loop() {
  Pace last_pace = Pace::RealTime;
  bool was_running = false;
  for (;;) {
    Pace pace;
    uint64_t pending;
    bool changed;
    {
      std::unique_lock<std::mutex> lk(mu_);
      if (quit_) return;
      changed = flow_factor_ != 1 || turb_factor_ != 1 || restart_ || pace_ != last_pace;
      apply_controls();
      pace = pace_;
      pending = pending_steps_;
      const bool idle = paused_ || finished_ || (pace == Pace::Fixed && pending == 0);
      if (idle) {
        if (pace == Pace::Fixed && served_ < requested_) {
          served_ = requested_;  // nothing to take (finished)
          done_cv_.notify_all();
        }
        // paused or at the end: the clock and the rates start afresh on resuming (not between
        // the frames of the fixed pace)
        if (paused_ || finished_) was_running = false;
        const bool stale = changed || frame_.paused != paused_ || frame_.pace != pace_;
        lk.unlock();
        if (stale) publish();
        lk.lock();
        cv_.wait_for(lk, std::chrono::milliseconds(100));
        continue;
      }
    }
    if (!was_running || pace != last_pace) {
      // (re)started: the clock and the rates start here
      reanchor();
      window_start_ = anchor_wall_;
      window_t0_ = state_.t;
      window_integrate_ = 0;
      window_body_steps_ = 0;
    }
    was_running = true;
    last_pace = pace;
    if (changed) publish();

    const uint64_t step = state_.step;
    const uint64_t stretch = std::max<uint64_t>(
        1, uint64_t(steps_per_second_ * kStretchSeconds));
    uint64_t end = total_steps_;
    if (pace == Pace::Fixed) {
      end = std::min(end, step + pending);
    } else if (pace == Pace::RealTime) {
      const auto now = Clock::now();
      double target = anchor_t_ + seconds(now - anchor_wall_);
      if (target - state_.t > kMaxLag) {
        // too slow for the wall clock: run flat out; the clock waits (no burst to catch up)
        behind_ = true;
        anchor_t_ = state_.t + kMaxLag;
        anchor_wall_ = now;
        target = anchor_t_;
      } else if (target - state_.t < 0.5 * kMaxLag) {
        behind_ = false;
      }
      const auto target_step = uint64_t(std::max(0.0, std::floor(target / model_.dt)));
      if (target_step <= step) {
        // ahead of the wall clock: wait until the next step is due (or a control arrives)
        const double due = (double(step + 1) * model_.dt - anchor_t_);
        std::unique_lock<std::mutex> lk(mu_);
        cv_.wait_until(lk, anchor_wall_ + std::chrono::duration_cast<Clock::duration>(
                                              std::chrono::duration<double>(due)));
        continue;
      }
      end = std::min(end, target_step);
    }
    end = std::min(end, step + stretch);

    RunOptions opt;
    opt.threads = threads_;
    opt.every = double(total_steps_ + 1) * model_.dt;  // no outputs (none is set anyway)
    model_.duration = double(end) * model_.dt;
    const RunStats st = simulate(model_, &state_, opt);
    model_.duration = double(total_steps_) * model_.dt;
    const uint64_t taken = state_.step - step;
    if (st.wall_seconds > 0) steps_per_second_ = double(taken) / st.wall_seconds;
    totals_.body_steps += st.body_steps;
    totals_.integrate_seconds += st.wall_seconds;
    totals_.simulated_seconds += double(taken) * model_.dt;
    window_integrate_ += st.wall_seconds;
    window_body_steps_ += st.body_steps;
    const auto now = Clock::now();
    const double span = seconds(now - window_start_);
    if (span >= kRateWindow) {
      rate_body_steps_ = window_integrate_ > 0 ? double(window_body_steps_) / window_integrate_ : 0;
      rate_busy_ = window_integrate_ / span;
      rate_speed_ = (state_.t - window_t0_) / span;
      window_start_ = now;
      window_t0_ = state_.t;
      window_integrate_ = 0;
      window_body_steps_ = 0;
    }
    if (state_.step >= total_steps_) {
      if (loop_) {
        model_.seed += 1;
        reset_state();
      } else {
        finished_ = true;
      }
    }
    {
      std::lock_guard<std::mutex> lk(mu_);
      if (pace == Pace::Fixed) {
        pending_steps_ -= std::min(pending_steps_, taken);
        if (pending_steps_ == 0 || finished_) {
          pending_steps_ = 0;
          served_ = requested_;
        }
      }
    }
    publish();
    if (pace == Pace::Fixed) done_cv_.notify_all();
  }
}

}  // namespace lrigid::app
