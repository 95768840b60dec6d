// Checksums and durability for what a run writes (docs/outputs.md, "What survives a crash"):
// an FNV-1a 64 checksum that can be fed piece by piece, and fsync of files and folders.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace lrigid {

// FNV-1a 64, fed in pieces: the same value as over the concatenated bytes
struct Fnv64 {
  uint64_t h = 0xcbf29ce484222325ull;  // the offset basis, 14695981039346656037
  void add(const void* data, size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) {
      h ^= p[i];
      h *= 1099511628211ull;
    }
  }
  std::string hex() const;  // 16 hex digits
};

// Goes on with a checksum `f` over a file's bytes [from, to): returns false when the file
// cannot be opened or ends before `to`.
bool checksum_range(const std::string& path, uint64_t from, uint64_t to, Fnv64* f);

// fsync of a file (opened read-only) or a folder; throws lrigid::Error(ExitCode::Output) naming
// the path when it fails. A folder's fsync makes the names created, renamed or removed in it
// durable; a file's, its content.
void sync_path(const std::string& path);
// fsync of the folder holding `path`
void sync_parent(const std::string& path);

}  // namespace lrigid
