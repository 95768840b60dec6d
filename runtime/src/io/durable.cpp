#include "io/durable.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <algorithm>
#include <filesystem>
#include <vector>

#include "util/error.h"

namespace lrigid {

std::string Fnv64::hex() const {
  char buf[20];
  std::snprintf(buf, sizeof buf, "%016" PRIx64, h);
  return buf;
}

bool checksum_range(const std::string& path, uint64_t from, uint64_t to, Fnv64* f) {
  if (to < from) return false;
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  std::vector<char> buf(1 << 16);
  uint64_t at = from;
  while (at < to) {
    const ssize_t n = ::pread(fd, buf.data(), size_t(std::min<uint64_t>(buf.size(), to - at)),
                              off_t(at));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    f->add(buf.data(), size_t(n));
    at += uint64_t(n);
  }
  ::close(fd);
  return at == to;
}

void sync_path(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0)
    throw Error(ExitCode::Output, where(path, "", std::string("cannot open to sync: ") +
                                                      std::strerror(errno)));
  int rc;
  do rc = ::fsync(fd);
  while (rc != 0 && errno == EINTR);
  const int err = errno;
  ::close(fd);
  // some file systems cannot sync a folder (EINVAL): nothing more can be done there
  if (rc != 0 && err != EINVAL && err != EROFS)
    throw Error(ExitCode::Output,
                where(path, "", std::string("fsync failed (disk full or failing?): ") +
                                    std::strerror(err)));
}

void sync_parent(const std::string& path) {
  const std::filesystem::path p(path);
  sync_path(p.has_parent_path() ? p.parent_path().string() : ".");
}

}  // namespace lrigid
