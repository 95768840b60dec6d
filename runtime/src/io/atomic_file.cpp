#include "io/atomic_file.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "util/error.h"

namespace lrigid {

namespace fs = std::filesystem;

void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write) {
  const std::string tmp = path + ".tmp" + std::to_string(::getpid());
  try {
    {
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      if (!out) throw Error(ExitCode::Output, where(path, "", "cannot open for writing"));
      write(out);
      out.flush();
      if (!out) throw Error(ExitCode::Output, where(path, "", "write failed (disk full?)"));
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec)
      throw Error(ExitCode::Output, where(path, "", "cannot move into place: " + ec.message()));
  } catch (...) {
    std::error_code ignore;
    fs::remove(tmp, ignore);
    throw;
  }
}

void commit_staged(const std::vector<StagedPath>& items) {
  std::error_code ec;
  for (const StagedPath& p : items) {
    const fs::file_status st = fs::symlink_status(p.final_path, ec);
    if (!fs::exists(st)) continue;
    if (p.is_dir != fs::is_directory(st))
      throw Error(ExitCode::Output,
                  where(p.final_path, "",
                        std::string("path taken by a ") + (p.is_dir ? "file" : "folder") +
                            "; the results were not moved into place"));
  }
  const std::string old_tag = ".old" + std::to_string(::getpid());
  std::vector<std::pair<std::string, std::string>> moved_aside;  // (final, backup)
  std::vector<std::string> placed;
  auto undo = [&] {
    std::error_code ignore;
    for (auto it = placed.rbegin(); it != placed.rend(); ++it) fs::remove_all(*it, ignore);
    for (auto it = moved_aside.rbegin(); it != moved_aside.rend(); ++it)
      fs::rename(it->second, it->first, ignore);
  };
  for (const StagedPath& p : items) {
    if (fs::exists(fs::symlink_status(p.final_path, ec))) {
      const std::string backup = p.final_path + old_tag;
      fs::rename(p.final_path, backup, ec);
      if (ec) {
        undo();
        throw Error(ExitCode::Output, where(p.final_path, "", "cannot replace: " + ec.message()));
      }
      moved_aside.emplace_back(p.final_path, backup);
    }
    fs::rename(p.tmp, p.final_path, ec);
    if (ec) {
      undo();
      throw Error(ExitCode::Output,
                  where(p.final_path, "", "cannot move into place: " + ec.message()));
    }
    placed.push_back(p.final_path);
  }
  for (const auto& m : moved_aside) fs::remove_all(m.second, ec);
}

void ensure_writable_directory(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw Error(ExitCode::Output, where(dir, "", "cannot create directory: " + ec.message()));
  if (::access(dir.c_str(), W_OK) != 0)
    throw Error(ExitCode::Output, where(dir, "", "directory is not writable"));
}

}  // namespace lrigid
