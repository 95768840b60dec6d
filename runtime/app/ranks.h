// The processes of `mpirun -np R lrigid run ...` (docs/scaling.md). Bodies are independent and
// each body's random numbers depend only on the seed and the body's index (util/rng.h), so every
// rank builds the same initial state, advances its own contiguous block of bodies, and rank 0
// gathers all bodies before each output and writes the one result, identical to a single process.
// Without mpirun (or without MPI at build time) there is one rank and nothing is exchanged.
#pragma once
#include <cstddef>
#include <cstdint>

#include "model/state.h"

namespace lrigid::app {

class Ranks {
 public:
  // Initializes MPI when started by mpirun; throws lrigid::Error when started by mpirun with
  // more than one process but built without MPI (the ranks would all write the same result).
  Ranks();
  ~Ranks();
  Ranks(const Ranks&) = delete;
  Ranks& operator=(const Ranks&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }

  // this rank's bodies [*begin, *end) of n: contiguous blocks, sizes differing by at most 1
  void share(size_t n, size_t* begin, size_t* end) const;
  // copies every rank's bodies (pose, velocities, seen velocity, status, stop time; with
  // `reasons` also why they stopped) into rank 0's state; collective
  void gather(State* state, bool reasons) const;
  uint64_t sum(uint64_t v) const;  // over ranks, on every rank
  double max(double v) const;      // over ranks, on every rank
  // after an error on any rank: ends all ranks with this exit code (no-op with one rank)
  void abort(int code) const;

 private:
  int rank_ = 0;
  int size_ = 1;
  bool mpi_ = false;
};

}  // namespace lrigid::app
