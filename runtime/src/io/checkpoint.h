// Checkpoints of a run (docs/cli.md, "Checkpoints and --resume"): the whole State of the
// bodies (pose, velocities, seen turbulence, status, Basset histories), the run's counts and
// an opaque part the result writer adds (what it wrote so far). Binary, little-endian as the
// machine, for the same build only: the header holds fingerprints of the build and of the
// scene, and reading checks them first, saying which one differs.
#pragma once
#include <cstdint>
#include <functional>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "integrate/simulation.h"
#include "model/state.h"

namespace lrigid {

// Raw values and arrays of trivially copyable things, with lengths.
class BinaryOut {
 public:
  explicit BinaryOut(std::ostream& o) : o_(o) {}
  template <typename T>
  void pod(const T& v) {
    o_.write(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  template <typename T>
  void vec(const std::vector<T>& v) {
    pod(uint64_t(v.size()));
    if (!v.empty()) o_.write(reinterpret_cast<const char*>(v.data()), sizeof(T) * v.size());
  }
  void str(const std::string& s) {
    pod(uint64_t(s.size()));
    o_.write(s.data(), std::streamsize(s.size()));
  }

 private:
  std::ostream& o_;
};

// Reads what BinaryOut wrote; a short or implausible file is ExitCode::BadInput naming it. A
// length longer than the bytes left in a seekable stream is refused before anything is
// allocated for it.
class BinaryIn {
 public:
  BinaryIn(std::istream& in, std::string file);
  template <typename T>
  void pod(T* v) {
    read(reinterpret_cast<char*>(v), sizeof(T));
  }
  template <typename T>
  void vec(std::vector<T>* v) {
    v->resize(length(sizeof(T)));
    if (!v->empty()) read(reinterpret_cast<char*>(v->data()), sizeof(T) * v->size());
  }
  void str(std::string* s) {
    s->resize(length(1));
    if (!s->empty()) read(s->data(), s->size());
  }
  const std::string& file() const { return file_; }

 private:
  uint64_t length(size_t item);
  void read(char* p, size_t n);
  std::istream& in_;
  std::string file_;
  std::streamoff end_ = -1;  // the stream's length where it can be told
};

// What a checkpoint belongs to: checked before anything else is read.
struct CheckpointId {
  std::string build;  // fingerprint of the lrigid binary (build_fingerprint())
  std::string scene;  // fingerprint of the scene and what overrides it (seed, integrator, dt)
  int ranks = 1;      // MPI ranks of the run
  std::string scene_file;  // for messages
};

// FNV-1a 64 of a file's bytes as 16 hex digits ("" when it cannot be read).
std::string file_fingerprint(const std::string& path);
std::string text_fingerprint(const std::string& text);
// the running binary: its GNU build-id ("gnu-build-id:" and hex digits, as `readelf -n` shows
// it), or the FNV of /proc/self/exe where it has none
std::string build_fingerprint();

// Writes one rank's checkpoint atomically (io/atomic_file.h): throws ExitCode::Output.
void write_checkpoint(const std::string& path, const CheckpointId& id, int rank,
                      const State& state, const RunStats& stats,
                      const std::function<void(BinaryOut&)>& extra);

// Reads it back into `state` (which must hold the run's bodies already: sizes are checked) and
// `stats`; `extra` reads what write_checkpoint's `extra` wrote. Throws ExitCode::BadInput
// naming the file and what differs (another build, scene or number of ranks).
void read_checkpoint(const std::string& path, const CheckpointId& id, int rank, State* state,
                     RunStats* stats, const std::function<void(BinaryIn&)>& extra);

}  // namespace lrigid
