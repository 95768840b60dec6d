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
// lrigid::Error with ExitCode::Output is thrown naming the path. `durable`: the file is
// fsync'ed before the rename and its folder after it, so that once this returns, a power loss
// leaves either the old file or the complete new one (not for files that are only a view, such
// as the partial .pvd collections).
void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write,
                           bool durable = true);

// Creates `dir` (and parents) and checks it is writable; throws ExitCode::Output otherwise.
void ensure_writable_directory(const std::string& dir);

}  // namespace lrigid
