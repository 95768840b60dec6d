// Cleanup on SIGINT/SIGTERM/SIGHUP. An interrupted run never leaves a final-looking
// file, because results appear under their final names only at the end; this handler also
// removes the temporary ones ("<name>.tmp<pid>", files and directories) so nothing is left.
// The handler uses only async-signal-safe calls (open, getdents64, readlinkat, unlinkat,
// close, sigaction, raise): it lists /proc/self/fd, and for every open file whose path has a
// component ending in ".tmp<pid>" it cleans the directory holding that component. A run
// interrupted while no temporary file is open keeps its (never final-looking) temporaries.
#include "signals.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <initializer_list>

#include "io/results_dir.h"

namespace lrigid::app {

namespace {

char g_tag[32];       // ".tmp<pid>"
volatile sig_atomic_t g_keep = 0;  // a checkpoint refers to the temporaries
size_t g_tag_len = 0;

struct Dirent64 {
  uint64_t d_ino;
  int64_t d_off;
  unsigned short d_reclen;
  unsigned char d_type;
  char d_name[1];
};

size_t length(const char* s) {
  size_t n = 0;
  while (s[n]) ++n;
  return n;
}

// name ends in the tag
bool tagged(const char* name) {
  const size_t n = length(name);
  if (n < g_tag_len) return false;
  for (size_t i = 0; i < g_tag_len; ++i)
    if (name[n - g_tag_len + i] != g_tag[i]) return false;
  return true;
}

// calls f(name, type) for each entry of the directory fd (except . and ..)
template <typename F>
void for_each_entry(int fd, F f) {
  alignas(8) char buf[4096];
  for (;;) {
    const long n = syscall(SYS_getdents64, fd, buf, sizeof buf);
    if (n <= 0) return;
    for (long off = 0; off < n;) {
      const auto* d = reinterpret_cast<const Dirent64*>(buf + off);
      off += d->d_reclen;
      const char* name = d->d_name;
      if (name[0] == '.' && (name[1] == 0 || (name[1] == '.' && name[2] == 0))) continue;
      f(name, d->d_type);
    }
  }
}

// removes the tagged entries of directory `dir` (a tagged directory with its files)
void clean_directory(const char* dir) {
  const int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  for_each_entry(fd, [fd](const char* name, unsigned char type) {
    if (!tagged(name)) return;
    if (type == DT_DIR) {
      // the frames thread (io/vtp_frames.cpp) goes on writing while this handler runs: a frame
      // it creates after the listing makes the folder non-empty again, so empty it and try
      // again (a bounded number of times; the thread writes one frame file at a time)
      for (int attempt = 0; attempt < 1000; ++attempt) {
        const int sub = openat(fd, name, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
        if (sub >= 0) {
          for_each_entry(sub, [sub](const char* f, unsigned char) { unlinkat(sub, f, 0); });
          close(sub);
        }
        if (unlinkat(fd, name, AT_REMOVEDIR) == 0 || errno != ENOTEMPTY) break;
      }
    } else {
      unlinkat(fd, name, 0);
    }
  });
  close(fd);
}

void on_signal(int sig) {
  // (a finish's commit under way: its journal names the temporaries, io/results_dir.h)
  const int fds = g_keep || g_results_commit_under_way ? -1 : open("/proc/self/fd", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fds >= 0) {
    for_each_entry(fds, [fds](const char* name, unsigned char) {
      char path[4096];
      const ssize_t n = readlinkat(fds, name, path, sizeof path - 1);
      if (n <= 0 || path[0] != '/') return;
      path[n] = 0;
      // the first component ending in the tag; its parent is the output directory
      size_t start = 0;
      for (size_t i = 1; i <= size_t(n); ++i) {
        if (path[i] != '/' && path[i] != 0) continue;
        if (i - start > g_tag_len) {
          bool match = true;
          for (size_t j = 0; j < g_tag_len && match; ++j)
            match = path[i - g_tag_len + j] == g_tag[j];
          if (match) {
            path[start > 0 ? start : 1] = 0;
            clean_directory(path);
            return;
          }
        }
        start = i;
      }
    });
    close(fds);
  }
  struct sigaction dfl = {};
  dfl.sa_handler = SIG_DFL;
  sigaction(sig, &dfl, nullptr);
  raise(sig);
}

// ".tmp" followed by the decimal pid, without snprintf (used before any thread starts)
void make_tag() {
  char digits[24];
  int nd = 0;
  for (long p = getpid(); p > 0 || nd == 0; p /= 10) digits[nd++] = char('0' + p % 10);
  const char* prefix = ".tmp";
  size_t k = 0;
  for (; prefix[k]; ++k) g_tag[k] = prefix[k];
  while (nd > 0) g_tag[k++] = digits[--nd];
  g_tag[k] = 0;
  g_tag_len = k;
}

}  // namespace

void keep_temporaries_on_signal() { g_keep = 1; }

void install_signal_cleanup() {
  make_tag();
  struct sigaction sa = {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&sa.sa_mask, sig);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaction(sig, &sa, nullptr);
  // a file-size limit (ulimit -f) must end in a failed write, exit 4 and a clean directory,
  // not in a core dump that leaves the temporaries behind
  signal(SIGXFSZ, SIG_IGN);
}

}  // namespace lrigid::app
