// The simulation behind `lrigid view` (cmd_view.cpp): a worker thread that advances a scene's
// bodies in short stretches with the ordinary step (integrate/simulation.h), at the pace the
// window asks for, and publishes after each stretch a copy of what the window draws. Between
// stretches it applies the controls: pause, the art-direction scales (Model::mean_flow_scale,
// Model::turbulence_scale), restart with a new seed, the pace. The Model is the worker's own
// copy; nothing else touches it while the worker runs.
#pragma once
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "model/scene.h"
#include "model/state.h"

namespace lrigid::app {

// realtime: simulated time follows the wall clock (when the simulation cannot keep up it runs
// as fast as it can and says it is behind); fast: as fast as it can; fixed: the window asks for
// a fixed simulated interval per drawn frame and waits for it (reproducible movies).
enum class Pace { RealTime, Fast, Fixed };
const char* pace_name(Pace p);

// What the window draws, copied from the worker's state after a stretch.
struct ViewFrame {
  uint64_t version = 0;          // increases with every published frame
  double t = 0;                  // simulated time, s
  double duration = 0;           // the scene's duration, s
  std::vector<Vec3> x;           // (nbody) m
  std::vector<Quat> q;           // (nbody) body -> world
  std::vector<uint16_t> type;    // (nbody)
  std::vector<BodyStatus> status;  // (nbody)
  std::vector<uint8_t> state;    // (nbody) State::state_code: flying, sliding, resting, ...
  std::vector<float> speed;      // (nbody) |v|, m/s
  size_t flying = 0, resting = 0, exited = 0;  // moving; landed; exited or failed
  double body_steps_per_second = 0;  // while integrating (over the last ~second)
  double busy = 0;               // fraction of wall time spent integrating (last ~second)
  double sim_speed = 0;          // simulated seconds per wall second (last ~second)
  bool behind = false;           // realtime pace not kept (the simulation is too slow)
  double mean_flow_scale = 1, turbulence_scale = 1;
  uint64_t seed = 0;
  bool paused = false, finished = false;
  Pace pace = Pace::RealTime;
};

class ViewSimulation {
 public:
  // `model` compiled from `scene`; threads 0 = OpenMP's default; with `loop` the scene restarts
  // (next seed) when it reaches its duration, else it stops there.
  ViewSimulation(Scene scene, Model model, int threads, Pace pace, bool loop);
  ~ViewSimulation();
  ViewSimulation(const ViewSimulation&) = delete;
  ViewSimulation& operator=(const ViewSimulation&) = delete;

  void start();
  void stop();

  // controls (any thread; applied between stretches)
  void toggle_pause();
  void scale_mean_flow(double factor);   // multiplies Model::mean_flow_scale
  void scale_turbulence(double factor);  // multiplies Model::turbulence_scale
  void restart();                        // seed + 1, bodies back to their initial state
  void set_pace(Pace p);

  // Fixed pace: advance by `seconds` of simulated time (whole steps, at least one) and wait
  // until it is done and published (returns at once when paused or finished).
  void advance_and_wait(double seconds);

  // Copies the newest frame into *f when it is newer than f->version; true when it did.
  bool latest(ViewFrame* f);
  // Totals since start(), for the summary at exit (read after stop()).
  struct Totals {
    uint64_t body_steps = 0;
    double integrate_seconds = 0;  // wall time inside the step
    double simulated_seconds = 0;  // simulated time advanced (over restarts)
  };
  Totals totals() const { return totals_; }
  // The worker's failure, rethrown on the caller's thread (nothing when it did not fail).
  void rethrow_failure();

 private:
  using Clock = std::chrono::steady_clock;
  void loop();
  void apply_controls();  // worker thread, mu_ held
  void reset_state();     // worker thread
  void publish();         // worker thread
  void reanchor();        // realtime: simulated time of now := state_.t

  Scene scene_;
  Model model_;
  State state_;
  int threads_;
  bool loop_;
  uint64_t total_steps_;
  std::thread worker_;

  // guarded by mu_
  std::mutex mu_;
  std::condition_variable cv_;      // controls changed, or (fixed pace) a request
  std::condition_variable done_cv_; // (fixed pace) a request was served
  bool quit_ = false;
  bool paused_ = false;
  double flow_factor_ = 1, turb_factor_ = 1;  // pending scale changes
  bool restart_ = false;
  Pace pace_;
  uint64_t pending_steps_ = 0;      // fixed pace: steps asked for and not yet taken
  uint64_t served_ = 0, requested_ = 0;
  ViewFrame frame_;
  std::exception_ptr failure_;

  // worker thread only
  bool finished_ = false, behind_ = false;
  double anchor_t_ = 0;
  Clock::time_point anchor_wall_;
  double steps_per_second_ = 0;     // time steps per second of integration (for stretch sizes)
  // the last ~second, for rates
  Clock::time_point window_start_;
  double window_t0_ = 0, window_integrate_ = 0;
  uint64_t window_body_steps_ = 0;
  double rate_body_steps_ = 0, rate_busy_ = 0, rate_speed_ = 0;
  Totals totals_;
};

}  // namespace lrigid::app
