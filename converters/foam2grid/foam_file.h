// Reading OpenFOAM files: the FoamFile header, dictionaries and lists, ascii or binary
// (raw list data), optionally gzip-compressed (name.gz). Only what foam2grid needs: polyMesh
// lists, field files (internalField and each patch's value) and transportProperties.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace foam2grid {

/// Storage format of one file, from its FoamFile header.
struct FoamFormat {
  bool binary = false;   ///< "format binary": list data are raw bytes
  int label_bytes = 4;   ///< bytes per label in raw lists (arch "label=32|64")
  int scalar_bytes = 8;  ///< bytes per scalar in raw lists (arch "scalar=32|64")
};

/// One OpenFOAM file held in memory.
class FoamFile {
 public:
  /// Reads path (mapped into memory), or path.gz when only that exists (decompressed);
  /// throws Error(kBadInput) if neither can be read.
  explicit FoamFile(const std::string& path);
  ~FoamFile();
  FoamFile(const FoamFile&) = delete;
  FoamFile& operator=(const FoamFile&) = delete;

  /// True when path or path.gz exists.
  static bool exists(const std::string& path);

  const std::string& path() const { return path_; }
  std::string_view text() const { return text_; }
  const FoamFormat& format() const { return format_; }
  const std::string& class_name() const { return class_name_; }
  /// Offset of the first character after the FoamFile header.
  std::size_t body() const { return body_; }

 private:
  std::string path_;
  std::string owned_;    // decompressed text of a .gz file
  void* map_ = nullptr;  // mapped plain file
  std::size_t map_size_ = 0;
  std::string_view text_;
  FoamFormat format_;
  std::string class_name_;
  std::size_t body_ = 0;
};

/// A dictionary entry: either a sub-dictionary or a value, kept as the text range [begin, end)
/// (end is the position of the closing ';').
struct DictEntry {
  std::string key;
  bool is_dict = false;
  std::size_t begin = 0;
  std::size_t end = 0;
  std::vector<DictEntry> sub;
};

/// Finds the entry with this exact key (nullptr if absent).
const DictEntry* find_entry(const std::vector<DictEntry>& entries, const std::string& key);

/// A reading position in a FoamFile. Errors name the file and the line.
class Cursor {
 public:
  Cursor(const FoamFile& file, std::size_t pos);

  /// Skips white space and // and /* */ comments.
  void skip_space();
  /// Next character after white space (0 at the end of the text).
  char peek();
  bool at_end();
  /// Consumes c (after white space) or fails naming what was expected.
  void expect(char c, const std::string& what);
  /// Consumes c if it is next.
  bool accept(char c);
  /// A word, number or quoted string (quotes removed).
  std::string token();
  double scalar();
  std::int64_t label();

  /// A list of scalars with ncomp components per element: "N (...)", "(...)", "N{v}" or
  /// binary "N (raw)". Elements with ncomp > 1 are "(x y z)" in ascii.
  void scalar_list(int ncomp, std::vector<double>* out);
  /// A list of labels (as scalar_list with one component).
  void label_list(std::vector<std::int64_t>* out);
  /// A list of faces: faceList "N (4(a b c d) ...)" or faceCompactList (offsets, then labels).
  void face_list(std::vector<std::int64_t>* offsets, std::vector<std::int64_t>* labels);
  /// A field value: "uniform v" or "nonuniform List<T> ...", ncomp components; n is the
  /// expected number of elements (a uniform value is repeated n times).
  void field_value(int ncomp, std::size_t n, std::vector<double>* out);

  /// Entries up to the closing '}' (or the end of the text when top_level).
  std::vector<DictEntry> dict(bool top_level);
  /// Skips one value up to and including ';' (binary lists are skipped by their size).
  void skip_value();

  [[noreturn]] void fail(const std::string& what) const;
  std::size_t pos() const { return pos_; }
  const FoamFile& file() const { return file_; }

 private:
  std::size_t raw_bytes_per_element(const std::string& list_type) const;
  const FoamFile& file_;
  std::string_view s_;
  std::size_t pos_;
};

}  // namespace foam2grid
