#include "io/run_recorder.h"

#include <cmath>
#include <filesystem>
#include <mutex>
#include <set>

#include "util/error.h"

namespace lrigid {

namespace {

namespace fs = std::filesystem;

// the folders recorders of this process write into (absolute)
std::mutex g_recording_folders_mutex;
std::set<std::string> g_recording_folders;

std::string recording_folder_key(const std::string& dir) {
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(fs::absolute(dir, ec), ec);
  return (ec ? fs::path(dir) : p).lexically_normal().string();
}

}  // namespace

RunRecorder::RunRecorder(const Scene& scene, const Model& model, RunFacts facts,
                         const std::string& resume_tag, bool force)
    : model_(model), key_(recording_folder_key(scene.output.dir)),
      stride_(output_stride(model, scene.output.every)),
      last_step_(static_cast<uint64_t>(std::llround(scene.duration / model.dt))) {
  {
    std::lock_guard<std::mutex> lock(g_recording_folders_mutex);
    if (!g_recording_folders.insert(key_).second)
      throw Error(ExitCode::Output,
                  where(scene.output.dir, "",
                        "another run of this process is recording into this folder; finish or "
                        "close it first, or choose another folder"));
  }
  try {
    writer_ = std::make_unique<ResultWriter>(scene.output.dir, model, scene.output, resume_tag,
                                             force);
  } catch (...) {
    std::lock_guard<std::mutex> lock(g_recording_folders_mutex);
    g_recording_folders.erase(key_);
    throw;
  }
  extra_["threads"] = facts.threads;
  extra_["warnings"] = findings_json(facts.findings);
  extra_["fluid_density"] = scene.fluid_density;  // kg/m^3; lrigid render draws water as a tank
  if (facts.ranks > 1) extra_["ranks"] = facts.ranks;
  if (!scene.uniform_field) {
    extra_["field"] = scene.field_path;  // for render and ParaView
    extra_["field_load_seconds"] = facts.field_load_seconds;
  }
}

RunRecorder::~RunRecorder() {
  writer_.reset();  // its temporaries go (unless finished) before another may take the folder
  std::lock_guard<std::mutex> lock(g_recording_folders_mutex);
  g_recording_folders.erase(key_);
}

void RunRecorder::frame(const State& state) {
  if (state.step > last_step_ || state.step == written_) return;
  if (state.step % stride_ != 0 && state.step != last_step_) return;
  writer_->write_frame(state);
  written_ = state.step;
}

void RunRecorder::finish(const State& state, const RunStats& stats) {
  nlohmann::json extra = extra_;
  if (model_.field.is_streamed()) {
    const StreamStats ss = model_.field.stream_stats();
    extra["field_stream"] = {{"frames_read", ss.loads},
                             {"max_resident_frames", ss.max_resident},
                             {"read_seconds", ss.load_seconds}};
  }
  writer_->finish(state, stats, extra);
}

}  // namespace lrigid
