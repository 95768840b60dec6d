// Writes a run's results into a directory (docs/outputs.md):
//   trajectories.csv   body,type,t,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz (SI, world frame)
//   bodies.pvd + bodies/bodies_NNNNNN.vtp   ParaView time series of body points with arrays
//   shapes.pvd + shapes/shapes_NNNNNN.vtp   the same frames as surfaces: each body's shape
//                      (tessellated, coarser for many bodies) placed at (x, q); with "pvd"
//   animation.glb      glTF 2.0 baked animation for DCC tools (io/gltf_writer.h); with "glb"
//   animation_instanced.glb, houdini_points.csv, bodies.usda   the other caches for DCC tools
//                      (io/dcc_cache.h kDccFormats); with "glb_instanced", "houdini", "usd"
//   landings.csv       body,type,t,x,y,z of bodies that reached the ground (scenes with ground)
//   summary.json       counts, timing, effects, stopped bodies and why
// Nothing appears under its final name until the run completed: files are written under
// temporary names, and finish() commits them (io/results_dir.h: fsync, a journal, the earlier
// results aside with summary.json first, the new ones into place with summary.json last, the
// manifest), so either all results appear or none, and only names lrigid wrote are replaced
// (the constructor refuses, before the run, a name taken by something else unless `force`).
// A writer destroyed before finish() removes its temporaries, unless a checkpoint refers to
// them (and always when it resumes an interrupted run: a failed resume deletes nothing).
#pragma once
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "integrate/simulation.h"
#include "io/atomic_file.h"
#include "io/durable.h"
#include "io/gltf_writer.h"
#include "io/results_dir.h"
#include "io/vtp_frames.h"
#include "model/state.h"
#include "nlohmann/json.hpp"

namespace lrigid {

// The surface of a body type in its body frame (origin at the centre of mass, shape axes):
// tessellate(shape, target_faces) shifted by -com. m
TriangleMesh body_surface(const BodyType& type, int target_faces);

// World-frame velocity of body i's centre of mass as the outputs write it, R = q[i]'s matrix:
// with the "body" turbulence model the turbulent velocity u' moves the body directly and is
// part of its velocity. m/s
Vec3 body_velocity(const Model& m, const State& st, size_t i, const Mat3& R);

// Faces per body used for the shapes series: fewer for many bodies (docs/outputs.md).
int shape_faces_for(size_t bodies);

// A results directory read back (for lrigid export-gltf and lrigid render): summary.json and
// trajectories.csv, with each body type's surface rebuilt from the shape recorded in the summary
// (`target_faces` as for tessellate()). Throws lrigid::Error(ExitCode::BadInput) naming the file,
// line or key when something is missing or malformed.
struct Results {
  nlohmann::json summary;
  GltfAnimation frames;  // types with surfaces, body types, times, x, q
};
Results read_results(const std::string& dir, int target_faces);

class BinaryIn;
class BinaryOut;

class ResultWriter {
 public:
  // With `resume_tag` (the temporaries' suffix of an interrupted run, from its checkpoint) the
  // writer goes on with that run's temporaries instead of starting new ones; restore() then
  // brings them back to the checkpoint.
  ResultWriter(const std::string& dir, const Model& model, const OutputSpec& spec,
               const std::string& resume_tag = "", bool force = false);
  ~ResultWriter();
  ResultWriter(const ResultWriter&) = delete;
  ResultWriter& operator=(const ResultWriter&) = delete;

  void write_frame(const State& state);
  // Moves everything into place; `extra` is merged into summary.json.
  void finish(const State& state, const RunStats& stats, const nlohmann::json& extra);

  const std::string& dir() const { return dir_; }
  // the suffix of this writer's temporary names (".tmp<pid>")
  const std::string& tag() const { return tag_; }

  // Checkpoints (io/checkpoint.h): what was written so far (the trajectories' length and
  // checksum, the frames with each file's size and checksum, the animation kept in memory).
  // save() first makes the output so far durable (fsync). restore() reads the writer's part
  // and checks the output so far against its checksums, changing nothing: a file cut short,
  // or changed, is lrigid::Error(ExitCode::BadInput) naming it. go_on(), once the whole
  // checkpoint has passed its checks, brings the output back to it: the trajectories cut to
  // their checkpointed length, the partial series rewritten, the interrupted finish's
  // leftovers removed.
  void save(BinaryOut& out);
  void restore(BinaryIn& in);
  void go_on();
  // the run's checkpoint folder (a name in dir()), removed as part of the finish's commit
  void set_checkpoint_dir(const std::string& name) { checkpoint_dir_ = name; }
  // once a checkpoint refers to them, the temporaries are kept when the run fails
  void keep_temporaries() { keep_ = true; }

 private:
  void cleanup();
  void write_partial_pvds() const;
  void remove_stale_temporaries() const;
  std::vector<ResultItem> planned() const;
  bool keeps_frames() const;      // a cache for DCC tools is written (io/dcc_cache.h)
  bool keeps_velocities() const;  // one of them needs the velocities

  std::string dir_;
  const Model& model_;
  OutputSpec spec_;
  std::string tag_;
  std::FILE* csv_ = nullptr;
  std::string csv_tmp_;
  std::string csv_line_;  // a frame of trajectories.csv, reused
  std::string vtp_tmp_dir_;
  std::string shapes_tmp_dir_;
  std::unique_ptr<FramesThread> vtp_;  // the two series' frames (io/vtp_frames.h)
  std::chrono::steady_clock::time_point partial_written_;  // the partial .pvd's last rewrite
  GltfAnimation gltf_;                  // frames kept for the caches for DCC tools
  std::vector<std::pair<double, std::string>> frames_;
  std::vector<ResultItem> staged_;      // complete temporaries waiting for commit_results
  // checkpoints: the trajectories checksummed (and fsync'ed) so far, and each frame's files
  Fnv64 csv_sum_;
  uint64_t csv_summed_ = 0;
  struct FrameSum {
    uint64_t bodies_bytes, bodies_sum, shapes_bytes, shapes_sum;
  };
  std::vector<FrameSum> frame_sums_;
  std::string checkpoint_dir_;
  bool force_ = false;
  bool finished_ = false;
  bool keep_ = false;
};

}  // namespace lrigid
