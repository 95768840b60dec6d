#include "io/atomic_file.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "io/durable.h"
#include "util/error.h"

namespace lrigid {

namespace fs = std::filesystem;

void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write, bool durable) {
  const std::string tmp = path + ".tmp" + std::to_string(::getpid());
  try {
    {
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      if (!out) throw Error(ExitCode::Output, where(path, "", "cannot open for writing"));
      write(out);
      out.flush();
      if (!out) throw Error(ExitCode::Output, where(path, "", "write failed (disk full?)"));
      out.close();
      if (!out) throw Error(ExitCode::Output, where(path, "", "write failed (disk full?)"));
    }
    // the content on disk before the name points at it, and the name on disk before returning
    if (durable) sync_path(tmp);
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec)
      throw Error(ExitCode::Output, where(path, "", "cannot move into place: " + ec.message()));
    if (durable) sync_parent(path);
  } catch (...) {
    std::error_code ignore;
    fs::remove(tmp, ignore);
    throw;
  }
}

void ensure_writable_directory(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw Error(ExitCode::Output, where(dir, "", "cannot create directory: " + ec.message()));
  if (::access(dir.c_str(), W_OK) != 0)
    throw Error(ExitCode::Output, where(dir, "", "directory is not writable"));
}

}  // namespace lrigid
