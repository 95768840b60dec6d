#include "integrate/simulation.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "integrate/integrators.h"

namespace lrigid {

uint64_t output_stride(const Model& model, double every) {
  const double r = std::round(every / model.dt);
  return r < 1 ? 1 : static_cast<uint64_t>(r);
}

namespace {

// the body's lowest point is on or below the ground
bool touches_ground(const Model& m, const BodyType& type, const BodyState& s) {
  const Mat3 R = s.q.toRotationMatrix();
  double reach = 0;
  for (int a = 0; a < 3; ++a) reach += std::abs(R(2, a)) * type.half_extents[a];
  return s.x.z() - reach <= m.ground_z;
}

// where one more step would take the body: its world velocity R v, plus the turbulent velocity
// u' for the body turbulence model (which carries the body directly; for the seen model u' is
// the fluid's and acts through the forces)
Vec3 predicted_position(const Model& m, const BodyType& type, const BodyState& b) {
  Vec3 velocity = b.q * b.v;
  if (type.effects.has(Effect::Turbulence) && m.turbulence_model == TurbulenceModel::Body)
    velocity += b.u_seen;
  return b.x + m.dt * velocity;
}

// the last time a stretch of steps ending at step `last` samples: an RK4 stage at t + dt may
// round a little beyond last * dt
double stream_window_end(const Model& m, uint64_t last) {
  return static_cast<double>(last) * m.dt * (1 + 1e-12) + 1e-9 * m.dt;
}

// where a body that could not be sampled went: where one more step would take it
std::string exit_reason(const Model& m, const BodyType& type, const BodyState& b) {
  const Vec3 next = predicted_position(m, type, b);
  if (m.field.in_box(next) && m.field.in_box(b.x))
    return "hit a solid: no valid grid point around it (a wall, a building, an obstacle)";
  return "left the grid";
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

}  // namespace

RunStats simulate(const Model& model, State* state, const RunOptions& options) {
  RunStats stats;
  State& st = *state;
  const uint64_t total_steps =
      static_cast<uint64_t>(std::llround(model.duration / model.dt));
  const uint64_t stride = output_stride(model, options.every);
  if (options.on_output) options.on_output(st);
  const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  const auto n = static_cast<int64_t>(std::min(st.size(), options.body_end));
  const auto n0 = static_cast<int64_t>(std::min(st.size(), options.body_begin));
  double wall = 0;

  while (st.step < total_steps) {
    const uint64_t first = st.step;
    const uint64_t next_output = (first / stride + 1) * stride;
    const uint64_t last = stream_stretch_end(model, first, std::min(total_steps, next_output));
    model.field.prepare(static_cast<double>(first) * model.dt, stream_window_end(model, last));
    uint64_t body_steps = 0;
    const auto t0 = std::chrono::steady_clock::now();
#pragma omp parallel for schedule(static) num_threads(threads) reduction(+ : body_steps)
    for (int64_t i = n0; i < n; ++i) {
      if (st.status[i] != BodyStatus::Moving) continue;
      const BodyType& type = model.types[st.type[i]];
      BodyState b{st.x[i], st.q[i], st.v[i], st.w[i], st.u_seen[i], st.history_of(size_t(i))};
      for (uint64_t k = first; k < last; ++k) {
        const double t = static_cast<double>(k) * model.dt;
        std::string reason;
        const StepOutcome out = step_body(model, type, static_cast<uint32_t>(i), k, t, &b, &reason);
        if (out == StepOutcome::Exited && model.has_ground) {
          // a step that would cross the ground (often also the grid's bottom) lands the body,
          // even when a stage of it sampled below the grid first
          BodyState next = b;
          next.x = predicted_position(model, type, b);
          if (touches_ground(model, type, next)) {
            st.status[i] = BodyStatus::Landed;
            st.t_stop[i] = t + model.dt;
            b.v.setZero();
            b.w.setZero();
            break;
          }
        }
        if (out != StepOutcome::Ok) {
          st.status[i] = out == StepOutcome::Exited ? BodyStatus::Exited : BodyStatus::Failed;
          st.t_stop[i] = t;
          st.reason[i] = out == StepOutcome::Exited ? exit_reason(model, type, b) : reason;
          break;
        }
        ++body_steps;
        if (model.has_ground && touches_ground(model, type, b)) {
          st.status[i] = BodyStatus::Landed;
          st.t_stop[i] = t + model.dt;
          b.v.setZero();
          b.w.setZero();
          break;
        }
      }
      st.x[i] = b.x;
      st.q[i] = b.q;
      st.v[i] = b.v;
      st.w[i] = b.w;
      st.u_seen[i] = b.u_seen;
    }
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    stats.body_steps += body_steps;
    st.step = last;
    st.t = static_cast<double>(last) * model.dt;
    if (last % stride == 0 || last == total_steps) {
      if (options.on_sync) options.on_sync(st, last == total_steps);
      if (options.on_output) options.on_output(st);
    }
    if (options.on_progress) options.on_progress(st, double(last) / double(total_steps));
  }
  stats.steps = st.step;
  stats.wall_seconds = wall;
  for (const BodyStatus s : st.status) {
    if (s == BodyStatus::Landed) ++stats.landed;
    if (s == BodyStatus::Exited) ++stats.exited;
    if (s == BodyStatus::Failed) ++stats.failed;
  }
  return stats;
}

}  // namespace lrigid
