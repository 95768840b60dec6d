// Write a file so that it either appears complete or not at all: the content goes to a
// temporary name in the same directory and is renamed into place only when fully written.
#pragma once
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace lrigid {

// Calls `write` with a stream to a temporary file, then renames it to `path`. On any failure
// (the writer throws, the stream fails, the rename fails) the temporary file is removed and an
// lrigid::Error with ExitCode::Output is thrown naming the path.
void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write);

// A complete file or directory under a temporary name, and the name it should have.
struct StagedPath {
  std::string tmp;
  std::string final_path;
  bool is_dir = false;
};

// Renames every staged path into place, in order (put the completion marker, summary.json,
// last), so that either all of them appear or none does. First checks that no final path is
// taken by something of the other kind (a folder where a file goes, or the reverse): such a
// path is never removed, the commit fails before renaming anything. What already is at a
// final path (an earlier run's results) is moved aside and removed only once everything is in
// place; if a rename fails, the new ones are removed and the old ones put back. Throws an
// lrigid::Error with ExitCode::Output naming the path; the temporaries are then left for the
// caller to remove.
void commit_staged(const std::vector<StagedPath>& items);

// Creates `dir` (and parents) and checks it is writable; throws ExitCode::Output otherwise.
void ensure_writable_directory(const std::string& dir);

}  // namespace lrigid
