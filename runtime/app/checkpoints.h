// Checkpoints of lrigid run and --resume (docs/cli.md). In the output directory:
//   checkpoint/rank<R>.step<N>.bin   each rank's state at output step N (io/checkpoint.h);
//                                    rank 0's also holds what the result writer wrote so far
//   checkpoint/latest.json           the step every rank completed, written last (atomically),
//                                    with the fingerprints of the build and the scene
// The run's temporaries (<name>.tmp<pid>) stay next to them; a resumed run takes them over.
#pragma once
#include <chrono>
#include <string>

#include "io/checkpoint.h"
#include "io/result_writer.h"
#include "ranks.h"

namespace lrigid::app {

class Checkpoints {
 public:
  // every: s of wall time between checkpoints (0: none)
  Checkpoints(std::string out_dir, CheckpointId id, const Ranks& ranks, double every);

  // --resume: the interrupted run's temporaries' tag. Throws lrigid::Error saying clearly when
  // the directory holds a finished run, no checkpoint, or one of another build, scene or number
  // of ranks.
  std::string resume_tag() const;
  // a fresh run: refuses a directory holding an interrupted run's checkpoint (ExitCode::Output)
  void refuse_to_overwrite() const;
  // reads this rank's checkpoint into state and stats (and the writer's part, on rank 0)
  void load(State* state, RunStats* stats, ResultWriter* writer) const;
  // at an output, on every rank: saves when `every` s of wall time have passed since the last
  // checkpoint (or the start). Collective. Throws ExitCode::Output (the last one stays intact).
  void maybe_save(const State& state, const RunStats& stats, ResultWriter* writer);
  // after the finish: the checkpoints are no longer needed (rank 0); removes only the
  // checkpoint's own files (the finish's commit has normally done it already)
  void remove() const;
  bool exists() const;  // latest.json is there

 private:
  std::string dir_;  // <out>/checkpoint
  CheckpointId id_;
  const Ranks& ranks_;
  double every_;
  std::chrono::steady_clock::time_point last_;
  std::string out_dir_;
};

}  // namespace lrigid::app
