// What a stretch of several steps records of each body's motion when bodies collide
// (Model::body_contact; simulation.cpp ContactStretches): the drivers (simulation.cpp
// advance_body, batch_lanes.h drive_block) keep each body's pose and squared speeds after each of
// its steps, from which the stretch rebuilds what the contact stage (contact/bodies.h) would have
// taken of the body after that step, and count the steps it took. Indexed by body; the drivers
// write only the bodies they step, each body from one thread.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "model/body_state.h"
#include "util/types.h"

namespace lrigid {

struct StretchSweep {
  // a body after one step of the stretch: its pose (x NaN: it has stopped, landed, left or
  // failed, and takes no part in the stage), |v|^2 ((m/s)^2) and |w|^2 ((rad/s)^2); v2 < 0:
  // asleep (a static surface for the stage)
  struct Slot {
    Vec3 x = Vec3::Zero();
    Quat q = Quat::Identity();
    double v2 = 0, w2 = 0;
  };
  uint64_t first = 0;       // the stretch's first step
  size_t len = 0;           // its steps
  size_t cap = 0;           // slots per body
  std::vector<Slot> slots;  // body i's: [i * cap, i * cap + len)
  // per body over the stretch's slots: the centre's least and greatest coordinates (world, m) and
  // the greatest |v|^2 and |w|^2
  std::vector<Vec3> lo, hi;
  std::vector<double> v2max, w2max;
  std::vector<uint32_t> steps;     // steps taken (RunStats::body_steps)
  std::vector<uint32_t> handoffs;  // of them, steps a batched block handed to the scalar step
  std::vector<uint8_t> slept;      // 1: fell asleep in the stretch

  // for n bodies and stretches of up to `max_steps` steps
  void resize(size_t n, size_t max_steps) {
    cap = max_steps;
    slots.assign(n * cap, Slot{});
    lo.assign(n, Vec3::Zero());
    hi.assign(n, Vec3::Zero());
    v2max.assign(n, 0.0);
    w2max.assign(n, 0.0);
    steps.assign(n, 0);
    handoffs.assign(n, 0);
    slept.assign(n, 0);
  }
  // the stretch [first, last) (last - first <= the max_steps of resize)
  void begin(uint64_t first_step, uint64_t last_step) {
    first = first_step;
    len = size_t(last_step - first_step);
  }
  // body i at the start of the stretch, at x: no steps, no slots yet (lo and hi start at x)
  void start(size_t i, const Vec3& x) {
    steps[i] = handoffs[i] = 0;
    slept[i] = 0;
    lo[i] = hi[i] = x;
    v2max[i] = w2max[i] = 0;
  }
  // ... asleep in b until its steps say otherwise (a sleeping body that wakes in the stretch)
  void start_asleep(size_t i, const BodyState& b) {
    start(i, b.x);
    hold(i, first, b);
  }
  Slot& at(size_t i, uint64_t step) { return slots[i * cap + size_t(step - first)]; }
  const Slot& at(size_t i, uint64_t step) const { return slots[i * cap + size_t(step - first)]; }
  // body i in b after step k
  void set(size_t i, uint64_t k, const BodyState& b) {
    Slot& s = at(i, k);
    s.x = b.x;
    s.q = b.q;
    s.v2 = b.v.squaredNorm();
    s.w2 = b.w.squaredNorm();
    extend(i, s);
  }
  // body i asleep in b after step k and every later step of the stretch (until its steps say
  // otherwise)
  void hold(size_t i, uint64_t k, const BodyState& b) {
    for (uint64_t s = k; s < first + len; ++s) {
      Slot& t = at(i, s);
      t.x = b.x;
      t.q = b.q;
      t.v2 = t.w2 = -1;
    }
    extend(i, at(i, k));
  }
  // body i stopped in step k: no part in the stage from there
  void stop(size_t i, uint64_t k) {
    for (uint64_t s = k; s < first + len; ++s)
      at(i, s).x = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  }

  // body i's extents and greatest squared speeds over some of its slots (a driver's own, which
  // writes its slots with at())
  void extend(size_t i, const Vec3& x_lo, const Vec3& x_hi, double v2, double w2) {
    lo[i] = lo[i].cwiseMin(x_lo);
    hi[i] = hi[i].cwiseMax(x_hi);
    v2max[i] = std::max(v2max[i], v2);
    w2max[i] = std::max(w2max[i], w2);
  }

 private:
  void extend(size_t i, const Slot& s) { extend(i, s.x, s.x, s.v2, s.w2); }
};

}  // namespace lrigid
