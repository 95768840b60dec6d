// lrigid run SCENE.json [-o DIR] [--seed S] [--threads T] [--stream-field M] [--quiet]
//            [--resume DIR] [--checkpoint-every S]
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <iostream>
#include <memory>

#include "checkpoints.h"
#include "checks.h"
#include "commands.h"
#include "compile/compile_model.h"
#include "ranks.h"
#include "integrate/simulation.h"
#include "io/added_mass_cache.h"
#include "io/field_loader.h"
#include "io/grid_reader.h"
#include "io/progress.h"
#include "io/result_writer.h"
#include "io/results_dir.h"
#include "io/run_recorder.h"
#include "io/sanity.h"
#include "io/scene_json.h"
#include "io/tolerance_table.h"
#include "model/state.h"
#include "model/tolerance.h"
#include "util/error.h"

namespace lrigid::app {

namespace {

struct RunArgs {
  std::string scene;
  std::string out;
  long long seed = -1;
  int threads = 0;
  bool quiet = false;
  bool strict = false;             // --strict: sanity warnings (io/sanity.h) are errors
  double tolerance = 0;            // relative error; > 0: choose scheme and dt (docs/accuracy.md)
  std::string tolerance_table;     // empty: default_tolerance_table_path()
  std::string stream = "auto";     // --stream-field: auto, on, off
  std::string resume;              // --resume DIR: continue the interrupted run in DIR
  double checkpoint_every = -1;    // --checkpoint-every S (< 0: the scene's)
  bool force = false;              // --force: replace files at the results' names that lrigid
                                   // did not write (io/results_dir.h)
};

// what a checkpoint must match: the scene file's bytes and what overrides them
std::string scene_fingerprint(const std::string& scene_file, const Scene& s) {
  std::ifstream in(scene_file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  char buf[160];
  std::snprintf(buf, sizeof buf, "\nseed=%llu integrator=%s dt=%.17g", (unsigned long long)s.seed,
                integrator_name(s.integrator),
                s.dt);
  return text_fingerprint(text.str() + buf);
}

// --tolerance E: the cheapest measured integrator and dt reaching E for this kind of scene
void apply_tolerance(const RunArgs& a, Scene* scene) {
  const std::string path =
      a.tolerance_table.empty() ? default_tolerance_table_path() : a.tolerance_table;
  const ToleranceChoice c =
      choose_for_tolerance(read_tolerance_table(path), scene_kind(*scene), a.tolerance);
  if (!integrator_from_name(c.entry.integrator, &scene->integrator))
    scene->integrator = kDefaultIntegrator;  // read_tolerance_table checked the names
  scene->dt = c.entry.dt;
  if (!a.quiet) std::fprintf(stderr, "lrigid: %s; from %s\n", c.explanation.c_str(), path.c_str());
}

void run(const RunArgs& a, const Ranks& ranks) {
  Scene scene = read_scene(a.scene);
  if (a.tolerance > 0) apply_tolerance(a, &scene);
  if (a.seed >= 0) scene.seed = static_cast<uint64_t>(a.seed);
  if (!a.out.empty()) scene.output.dir = a.out;
  if (!a.resume.empty()) {
    if (!a.out.empty() && a.out != a.resume)
      throw Error(ExitCode::Usage, "--resume " + a.resume + " and -o " + a.out +
                                       " name different directories");
    scene.output.dir = a.resume;
  }
  if (a.checkpoint_every >= 0) scene.output.checkpoint_every = a.checkpoint_every;
  check_memory(scene);
  const auto load0 = std::chrono::steady_clock::now();
  FluidField field = load_field(scene, stream_mode_from(a.stream), a.quiet);
  // s: reading the grid (all frames, or the header and first frame when streamed)
  const double load_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - load0).count();
  const Model model = compile_model(scene, std::move(field), cached_added_mass);
  // what is valid but most likely a mistake (units above all): before the run, on stderr and
  // in summary.json
  const std::vector<SanityFinding> findings = check_scene(scene, model);
  report_findings(findings, scene.file, a.strict, a.quiet || !ranks.root());
  State state = initial_state(model, scene);
  // checkpoints (app/checkpoints.h): the build's fingerprint is only needed with them
  const bool checkpoints = scene.output.checkpoint_every > 0 || !a.resume.empty();
  CheckpointId id;
  if (checkpoints) id = {build_fingerprint(), scene_fingerprint(a.scene, scene), ranks.size(), a.scene};
  Checkpoints cps(scene.output.dir, id, ranks, scene.output.checkpoint_every);
  // a finish that a kill or a power loss interrupted after it was decided: completed first
  // (io/results_dir.h), then --resume finds the run finished
  if (ranks.root()) complete_interrupted_finish(scene.output.dir);
  std::string resume_tag;
  if (!a.resume.empty()) resume_tag = cps.resume_tag();
  else if (checkpoints) cps.refuse_to_overwrite();
  // with several MPI ranks, rank 0 alone writes, after gathering every rank's bodies
  std::unique_ptr<RunRecorder> recorder;
  if (ranks.root())
    recorder = std::make_unique<RunRecorder>(
        scene, model, RunFacts{a.threads, findings, load_seconds, ranks.size()}, resume_tag,
        a.force);
  ResultWriter* const writer = recorder ? recorder->writer() : nullptr;
  if (writer && checkpoints) writer->set_checkpoint_dir("checkpoint");
  // what a failure from here on leaves, said after the error (lrigid::Error only: exit codes 3-5)
  auto say_what_is_left = [&] {
    if (!ranks.root()) return;  // part of the error: printed with --quiet too
    if (cps.exists())
      std::fprintf(stderr,
                   "lrigid: the run is resumable from its last checkpoint: lrigid run %s "
                   "--resume %s\n",
                   a.scene.c_str(), scene.output.dir.c_str());
    else
      std::fprintf(stderr,
                   "lrigid: no result was written and there is no checkpoint to resume from; "
                   "earlier results in %s, if any, are unchanged\n",
                   scene.output.dir.c_str());
  };
  try {
    RunStats live;
    if (!a.resume.empty()) {
      cps.load(&state, &live, writer);
      if (!a.quiet && ranks.root())
        std::fprintf(stderr, "lrigid: resuming %s at t = %.6g s (step %llu)\n",
                     scene.output.dir.c_str(), state.t, (unsigned long long)state.step);
    }

    RunOptions opt;
    opt.every = scene.output.every;
    opt.live_stats = &live;
    opt.output_at_start = a.resume.empty();
    opt.threads = a.threads;
    ranks.share(state.size(), &opt.body_begin, &opt.body_end);
    if (ranks.size() > 1) opt.on_sync = [&](State& s, bool last) { ranks.gather(&s, last); };
    opt.on_output = [&](const State& s) {
      if (recorder) recorder->frame(s);
      cps.maybe_save(s, live, writer);  // collective: every rank calls it
    };
    const bool quiet = a.quiet || !ranks.root();
    Progress progress("lrigid", quiet ? Progress::Mode::Quiet : Progress::Mode::Auto);
    if (!quiet)
      opt.on_progress = [&](const State& s, double f) {
        size_t moving = 0, landed = 0, exited = 0, resting = 0, waiting = 0;
        for (size_t i = 0; i < s.size(); ++i) {
          const BodyStatus b = s.status[i];
          // each body counted once: moving (flying or sliding), resting on a surface or asleep
          // there (contact/sleep.h), landed, or stopped (exited or failed)
          const bool rests = b == BodyStatus::Sleeping ||
                             (b == BodyStatus::Moving && i < s.contact.size() &&
                              s.contact[i] == ContactState::Resting);
          resting += rests;
          moving += b == BodyStatus::Moving && !rests;
          landed += b == BodyStatus::Landed;
          exited += b == BodyStatus::Exited || b == BodyStatus::Failed;
          waiting += b == BodyStatus::Unreleased;
        }
        char buf[240];
        const int len = std::snprintf(
            buf, sizeof buf, "t = %.3f / %.3f s, moving %zu, resting %zu, landed %zu, stopped %zu",
            s.t, model.duration, moving, resting, landed, exited);
        // bodies not released yet (bodies[i].release)
        if (waiting > 0 && len > 0 && size_t(len) < sizeof buf)
          std::snprintf(buf + len, sizeof buf - size_t(len), ", waiting %zu", waiting);
        progress.update(f, buf);
      };
    RunStats stats = simulate(model, &state, opt);
    progress.finish();
    // (with contacts between bodies every rank steps every body: rank 0's count is the run's)
    if (!model.body_contact) stats.body_steps = ranks.sum(stats.body_steps);
    stats.wall_seconds = ranks.max(stats.wall_seconds);
    if (!recorder) return;
    recorder->finish(state, stats);
    cps.remove();
    if (!a.quiet) {
      std::fprintf(stderr,
                   "lrigid: %zu bodies, %llu body-steps in %.3f s (%.3g body-steps/s); landed %zu, "
                   "exited %zu, failed %zu; resting or asleep on a surface %zu\n"
                   "lrigid: results in %s\n",
                   state.size(), static_cast<unsigned long long>(stats.body_steps),
                   stats.wall_seconds,
                   stats.wall_seconds > 0 ? stats.body_steps / stats.wall_seconds : 0.0, stats.landed,
                   stats.exited, stats.failed, stats.resting, writer->dir().c_str());
    }
  } catch (const Error& e) {
    // a --resume refused by its checks changed nothing: the message says so itself
    if (a.resume.empty() || e.code() != ExitCode::BadInput) say_what_is_left();
    throw;
  }
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
  auto* cmd = app.add_subcommand("run", "Integrate the bodies of a scene (docs/scene-format.md)");
  cmd->add_option("scene", args->scene, "Scene file (JSON, schema v1)")->required();
  cmd->add_option("-o,--output", args->out, "Output directory (overrides output.dir)")
      ->check([](const std::string& v) {
        return v.empty() ? std::string("an empty name; give a directory (\".\" for here)")
                         : std::string();
      });
  cmd->add_option("--seed", args->seed, "Random seed (overrides the scene's seed), 0 or more")
      ->check(non_negative("a whole number, 0 or more (the random seed)"));
  cmd->add_option("--threads", args->threads, "Threads (default: all cores); results do not "
                                              "depend on it")
      ->check(CLI::Range(1, 1024));
  cmd->add_flag("--quiet", args->quiet, "Print nothing but errors");
  cmd->add_flag("--strict", args->strict,
                "Make the sanity warnings errors (a body size, mass or density implausible for "
                "the fluid and grid, a spawn box outside the grid, a time step beyond the "
                "scheme's measured limit, a grid too coarse for the bodies: docs/scene-format.md)");
  cmd->add_option("--tolerance", args->tolerance,
                  "Relative error to reach: picks the cheapest integrator and dt of the measured "
                  "table for this kind of scene (docs/accuracy.md) and says what it chose")
      ->check(positive("a relative error > 0, e.g. 0.01"));
  cmd->add_option("--tolerance-table", args->tolerance_table,
                  "Measured table for --tolerance (default: next to the binary, else "
                  "docs/accuracy/tolerance_table.json)");
  cmd->add_option("--stream-field", args->stream,
                  "Read a .pvd series frame by frame, keeping only the frames around the current "
                  "time in memory: on, off, or auto (when all frames would take more than half "
                  "the memory)")
      ->check(CLI::IsMember({"auto", "on", "off"}));
  cmd->add_option("--resume", args->resume,
                  "Continue the interrupted run whose output directory is DIR from its last "
                  "checkpoint (same scene, options and build); results are identical to an "
                  "uninterrupted run");
  cmd->add_flag("--force", args->force,
                "Replace files at the results' names (trajectories.csv, summary.json, ...) that "
                "lrigid did not write; without it such a file stops the run before it starts "
                "(exit 4). A folder holding files lrigid did not write is never replaced "
                "(docs/outputs.md)");
  cmd->add_option("--checkpoint-every", args->checkpoint_every,
                  "Seconds of wall time between checkpoints (overrides "
                  "output.checkpoint_every; 0: none)")
      ->check(non_negative("seconds, 0 or more (0: no checkpoints)"));
  cmd->callback([args] {
    const Ranks ranks;
    try {
      run(*args, ranks);
    } catch (const std::exception& e) {
      // one failing rank ends all of them (the others would wait for it forever)
      if (ranks.size() > 1) {
        const auto* err = dynamic_cast<const Error*>(&e);
        std::cerr << "lrigid: error (rank " << ranks.rank() << "): " << e.what() << "\n";
        ranks.abort(static_cast<int>(err ? err->code() : ExitCode::Runtime));
      }
      throw;
    }
  });
}

}  // namespace lrigid::app
