// The output folder is the user's (docs/outputs.md, "The output folder"): a run writes, moves
// and removes only the names it writes itself, and records them in a manifest kept in the
// folder; the finish is a journalled commit that a kill or a power loss at any instant leaves
// either undone (the earlier results intact) or decided, and then completed by the next lrigid
// that opens the folder.
//   lrigid-manifest.json   what the last finished run wrote there (files, folders and the
//                          files in them)
//   lrigid-finish.json     the journal of a finish under way: the renames it makes, the
//                          earlier results it replaces and the manifest that follows
// Errors: lrigid::Error(ExitCode::Output) naming the path.
#pragma once
#include <csignal>
#include <string>
#include <vector>

namespace lrigid {

constexpr const char* kManifestName = "lrigid-manifest.json";
constexpr const char* kJournalName = "lrigid-finish.json";

// A result under its final name (relative to the output folder: "trajectories.csv", "bodies")
// and, at the commit, the complete temporary that becomes it (a name in the same folder).
struct ResultItem {
  std::string name;
  bool is_dir = false;
  std::string tmp;
};

// Before the run: refuses (exit 4, naming the path) when a name the run will write is taken by
// something lrigid did not write there (not in the manifest; for a folder of an earlier result,
// a file in it the manifest does not name). With `force`, a file (or an empty folder) that
// lrigid did not write is replaced; a folder holding such files never is.
void check_may_write(const std::string& dir, const std::vector<ResultItem>& items, bool force);

// The finish: checks again as check_may_write, makes every temporary durable (fsync of each
// file, each folder's files and the folders), writes the journal, then renames: every earlier
// result aside (summary.json first), every new one into place (summary.json last), writes the
// manifest, removes the earlier results (only the files the old manifest names) and, when
// `checkpoint_dir` is given (a folder name in `dir`), the run's checkpoint files. A rename that
// fails is undone (the temporaries go back under their names, the earlier results too) and the
// journal removed, so the run stays resumable; the Error names the path.
void commit_results(const std::string& dir, const std::vector<ResultItem>& items, bool force,
                    const std::string& checkpoint_dir = "");

// Non-zero while commit_results runs: the signal handlers (app/signals.cpp) then leave the
// temporaries alone, since the journal may name them.
extern volatile std::sig_atomic_t g_results_commit_under_way;

// A finish interrupted after its journal was written (a kill, a power loss): completes it.
// Returns true when there was one. Every lrigid command that opens an output folder calls it
// first (lrigid run, --resume, render, export-gltf).
bool complete_interrupted_finish(const std::string& dir);

// Removes a checkpoint folder's own files (latest.json, rank<R>.step<N>.bin and their
// temporaries), then the folder if that left it empty: never anything else in it.
void remove_checkpoint_files(const std::string& checkpoint_dir);

}  // namespace lrigid
