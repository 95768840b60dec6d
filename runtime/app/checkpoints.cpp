#include "checkpoints.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "io/atomic_file.h"
#include "io/results_dir.h"
#include "signals.h"
#include "util/error.h"

namespace lrigid::app {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::string rank_file(const std::string& dir, int rank, uint64_t step) {
  return (fs::path(dir) / ("rank" + std::to_string(rank) + ".step" + std::to_string(step) +
                           ".bin"))
      .string();
}

json read_latest(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail_input(path, "", "cannot be read");
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    fail_input(path, "", std::string("not valid JSON: ") + e.what());
  }
}

}  // namespace

Checkpoints::Checkpoints(std::string out_dir, CheckpointId id, const Ranks& ranks, double every)
    : dir_((fs::path(out_dir) / "checkpoint").string()),
      id_(std::move(id)),
      ranks_(ranks),
      every_(every),
      last_(std::chrono::steady_clock::now()),
      out_dir_(std::move(out_dir)) {}

std::string Checkpoints::resume_tag() const {
  const std::string latest = (fs::path(dir_) / "latest.json").string();
  std::error_code ec;
  if (!fs::exists(latest, ec)) {
    if (fs::exists(fs::path(out_dir_) / "summary.json", ec))
      fail_input(out_dir_, "",
                 "this run has finished (summary.json is there): there is nothing to resume; "
                 "start a new run without --resume");
    fail_input(out_dir_, "",
               "no checkpoint to resume from (" + latest +
                   " not found; checkpoints are written every output.checkpoint_every s of "
                   "wall time)");
  }
  const json j = read_latest(latest);
  try {
    if (j.at("build").get<std::string>() != id_.build)
      fail_input(latest, "",
                 "the run was started by another build of lrigid: resume it with the binary "
                 "that started it");
    if (j.at("scene").get<std::string>() != id_.scene)
      fail_input(latest, "",
                 "the run was started with another scene (" +
                     j.at("scene_file").get<std::string>() +
                     ", or another seed, integrator or dt): resume it with the same scene and "
                     "options");
    const int ranks = j.at("ranks").get<int>();
    if (ranks != id_.ranks)
      fail_input(latest, "",
                 "the run was started with " + std::to_string(ranks) +
                     " MPI rank(s): resume it with " +
                     (ranks > 1 ? "mpirun -np " + std::to_string(ranks) : "one process"));
    // the suffix of the interrupted run's temporaries, ".tmp" and its process id: a resume
    // goes on with (and tidies) the files of that name only, so anything else is refused
    const std::string tag = j.at("tag").get<std::string>();
    if (tag.size() <= 4 || tag.compare(0, 4, ".tmp") != 0 ||
        tag.find_first_not_of("0123456789", 4) != std::string::npos)
      fail_input(latest, "tag",
                 "malformed: \"" + tag +
                     "\" is not the suffix of a run's temporaries (.tmp and a number); "
                     "nothing was changed");
    return tag;
  } catch (const json::exception& e) {
    fail_input(latest, "", std::string("malformed: ") + e.what());
  }
}

void Checkpoints::refuse_to_overwrite() const {
  std::error_code ec;
  if (fs::exists(fs::path(dir_) / "latest.json", ec))
    throw Error(ExitCode::Output,
                where(out_dir_, "",
                      "holds the checkpoint of an interrupted run: resume it with --resume " +
                          out_dir_ + ", or remove " + dir_ + " to start afresh"));
}

void Checkpoints::load(State* state, RunStats* stats, ResultWriter* writer) const {
  const std::string latest = (fs::path(dir_) / "latest.json").string();
  const json j = read_latest(latest);
  uint64_t step = 0;
  try {
    step = j.at("step").get<uint64_t>();
  } catch (const json::exception& e) {
    fail_input(latest, "step", std::string("malformed: ") + e.what());
  }
  std::error_code ec;
  if (!fs::exists(rank_file(dir_, ranks_.rank(), step), ec))
    fail_input(rank_file(dir_, ranks_.rank(), step), "",
               "missing: " + latest + " names step " + std::to_string(step) +
                   ", whose checkpoint file is not there; nothing was changed");
  read_checkpoint(rank_file(dir_, ranks_.rank(), step), id_, ranks_.rank(), state, stats,
                  [&](BinaryIn& in) {
                    if (writer) writer->restore(in);
                  });
  if (state->step != step)
    fail_input(rank_file(dir_, ranks_.rank(), step), "", "holds another step than latest.json");
  // everything checked: the resume changes the folder from here on
  if (writer) writer->go_on();
  if (writer) writer->keep_temporaries();
  keep_temporaries_on_signal();
}

void Checkpoints::maybe_save(const State& state, const RunStats& stats, ResultWriter* writer) {
  if (every_ <= 0) return;
  const double since =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - last_).count();
  if (ranks_.max(since) < every_) return;  // every rank decides alike
  if (ranks_.root()) ensure_writable_directory(dir_);
  ranks_.max(0.0);  // the directory exists for every rank
  write_checkpoint(rank_file(dir_, ranks_.rank(), state.step), id_, ranks_.rank(), state, stats,
                   [&](BinaryOut& out) {
                     if (writer) writer->save(out);
                   });
  ranks_.max(0.0);  // every rank has written its part
  if (ranks_.root()) {
    const json latest = {{"step", state.step},
                         {"t", state.t},
                         {"ranks", id_.ranks},
                         {"tag", writer ? writer->tag() : std::string()},
                         {"build", id_.build},
                         {"scene", id_.scene},
                         {"scene_file", id_.scene_file}};
    write_file_atomically((fs::path(dir_) / "latest.json").string(),
                          [&](std::ostream& o) { o << latest.dump(1) << '\n'; });
    // the older checkpoints are superseded
    const std::string keep = ".step" + std::to_string(state.step) + ".bin";
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir_, ec)) {
      const std::string n = e.path().filename().string();
      if (n.size() > keep.size() && n.compare(n.size() - keep.size(), keep.size(), keep) != 0 &&
          n.rfind("rank", 0) == 0)
        fs::remove(e.path(), ec);
    }
    if (writer) writer->keep_temporaries();
  }
  keep_temporaries_on_signal();
  last_ = std::chrono::steady_clock::now();
}

bool Checkpoints::exists() const {
  std::error_code ec;
  return fs::exists(fs::path(dir_) / "latest.json", ec);
}

void Checkpoints::remove() const { remove_checkpoint_files(dir_); }

}  // namespace lrigid::app
