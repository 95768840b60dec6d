// The mutable state of a run (the mjData of this project), one entry per body, structure of
// arrays. The step reads the constant Model and writes only this.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "model/model.h"

namespace lrigid {

enum class BodyStatus : uint8_t { Moving = 0, Landed = 1, Exited = 2, Failed = 3 };
const char* body_status_name(BodyStatus s);

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
  // Basset history (effects/basset.h), only for body types with the effect:
  // body i owns history[history_offset[i], + model.types[type[i]].basset.stride())
  std::vector<double> history;        // (sum of strides)
  std::vector<size_t> history_offset; // (nbody)
  double* history_of(size_t i) {
    return history_offset[i] == kNoHistory ? nullptr : history.data() + history_offset[i];
  }
  static constexpr size_t kNoHistory = ~size_t(0);
  size_t size() const { return x.size(); }
};

}  // namespace lrigid
