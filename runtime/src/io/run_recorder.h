// What a run records into its output folder (docs/outputs.md), for `lrigid run` and the Python
// module's Simulation(output_dir=...) alike, so that both write the same files: the
// ResultWriter's formats (the scene's "output.formats"), one frame at each of the scene's
// output times (t = 0, every output.every, and the duration), and at the end summary.json with
// what the run adds to it (threads, sanity warnings, fluid density, the grid, its load time and
// streaming). Nothing appears under its final name before finish() (io/result_writer.h): a
// recorder destroyed before it leaves no result, and earlier results in the folder unchanged.
// One recorder at a time records into a folder in a process: the temporaries' names carry the
// process id, so a second one into the same folder is refused (ExitCode::Output).
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "integrate/simulation.h"
#include "io/result_writer.h"
#include "io/sanity.h"
#include "model/scene.h"

namespace lrigid {

// What the run adds to summary.json besides its state and counts.
struct RunFacts {
  int threads = 0;                      // as asked (0: all cores)
  std::vector<SanityFinding> findings;  // check_scene (io/sanity.h)
  double field_load_seconds = 0;        // s: reading the grid
  int ranks = 1;                        // MPI ranks (app/ranks.h)
};

class RunRecorder {
 public:
  // Into scene.output.dir, at the output times of scene.output.every and scene.duration.
  // `model` must outlive the recorder, with the scene's duration at finish(). `resume_tag` and
  // `force` as for ResultWriter.
  RunRecorder(const Scene& scene, const Model& model, RunFacts facts,
              const std::string& resume_tag = "", bool force = false);
  ~RunRecorder();
  RunRecorder(const RunRecorder&) = delete;
  RunRecorder& operator=(const RunRecorder&) = delete;

  // Writes the frame of `state` when its step is an output step not written yet (a multiple of
  // the output stride, or the last step of the scene's duration); does nothing otherwise.
  void frame(const State& state);
  // The last step of the scene's duration, the one finish() is meant for.
  uint64_t last_step() const { return last_step_; }
  // Commits every result (ResultWriter::finish) with the run's facts in summary.json.
  void finish(const State& state, const RunStats& stats);

  ResultWriter* writer() { return writer_.get(); }
  const std::string& dir() const { return writer_->dir(); }

 private:
  const Model& model_;
  nlohmann::json extra_;  // the run's facts known from the start
  std::string key_;  // the folder, absolute: what no other recorder of the process may take
  uint64_t stride_ = 1, last_step_ = 0;
  uint64_t written_ = ~uint64_t(0);  // the step of the last frame written (none yet)
  std::unique_ptr<ResultWriter> writer_;
};

}  // namespace lrigid
