#include "foam_file.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "error.h"

namespace foam2grid {
namespace {

bool is_file(const std::string& path) {
  struct stat st;
  return stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

inline bool is_space(char c) {
  return c == ' ' || c == '\n' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

bool is_delimiter(char c) {
  return is_space(c) || c == '(' || c == ')' || c == '{' || c == '}' || c == ';' || c == '"' ||
         c == '[' || c == ']';
}

std::string read_gzip(const std::string& path) {
  gzFile gz = gzopen(path.c_str(), "rb");
  if (gz == nullptr) fail_input(path + ": cannot open the file");
  std::string out;
  char buf[1 << 16];
  int n;
  while ((n = gzread(gz, buf, sizeof(buf))) > 0) out.append(buf, static_cast<std::size_t>(n));
  const bool bad = n < 0;
  gzclose(gz);
  if (bad) fail_input(path + ": corrupt gzip data");
  return out;
}

}  // namespace

FoamFile::~FoamFile() {
  if (map_ != nullptr) munmap(map_, map_size_);
}

bool FoamFile::exists(const std::string& path) { return is_file(path) || is_file(path + ".gz"); }

FoamFile::FoamFile(const std::string& path) : path_(path) {
  if (is_file(path)) {
    // mapped read-only: no copy of large mesh files
    const int fd = open(path.c_str(), O_RDONLY);
    if (fd < 0) fail_input(path + ": cannot open the file");
    struct stat st;
    if (fstat(fd, &st) != 0) {
      close(fd);
      fail_input(path + ": cannot read the file");
    }
    map_size_ = static_cast<std::size_t>(st.st_size);
    if (map_size_ > 0) {
      map_ = mmap(nullptr, map_size_, PROT_READ, MAP_PRIVATE, fd, 0);
      if (map_ == MAP_FAILED) {
        map_ = nullptr;
        close(fd);
        fail_input(path + ": cannot map the file into memory");
      }
      madvise(map_, map_size_, MADV_SEQUENTIAL);
      text_ = std::string_view(static_cast<const char*>(map_), map_size_);
    }
    close(fd);
  } else if (is_file(path + ".gz")) {
    path_ = path + ".gz";
    owned_ = read_gzip(path_);
    text_ = owned_;
  } else {
    fail_input(path + ": file not found");
  }
  // header: FoamFile { ... }
  Cursor c(*this, 0);
  const std::string key = c.token();
  if (key != "FoamFile") c.fail("expected the FoamFile header, found '" + key + "'");
  c.expect('{', "'{' after FoamFile");
  const std::vector<DictEntry> header = c.dict(false);
  if (const DictEntry* e = find_entry(header, "format")) {
    Cursor v(*this, e->begin);
    const std::string fmt = v.token();
    if (fmt == "binary") {
      format_.binary = true;
    } else if (fmt != "ascii") {
      v.fail("format must be ascii or binary, found '" + fmt + "'");
    }
  }
  if (const DictEntry* e = find_entry(header, "class"))
    class_name_ = Cursor(*this, e->begin).token();
  if (const DictEntry* e = find_entry(header, "arch")) {
    const std::string arch = Cursor(*this, e->begin).token();
    if (arch.find("label=64") != std::string::npos) format_.label_bytes = 8;
    if (arch.find("scalar=32") != std::string::npos) format_.scalar_bytes = 4;
  }
  body_ = c.pos();
}

const DictEntry* find_entry(const std::vector<DictEntry>& entries, const std::string& key) {
  for (const DictEntry& e : entries) {
    if (e.key == key) return &e;
  }
  return nullptr;
}

Cursor::Cursor(const FoamFile& file, std::size_t pos) : file_(file), s_(file.text()), pos_(pos) {}

void Cursor::fail(const std::string& what) const {
  const std::size_t end = std::min(pos_, s_.size());
  const long line = 1 + std::count(s_.begin(), s_.begin() + static_cast<long>(end), '\n');
  fail_input(file_.path() + ": line " + std::to_string(line) + ": " + what);
}

void Cursor::skip_space() {
  const std::size_t n = s_.size();
  while (pos_ < n) {
    const char c = s_[pos_];
    if (is_space(c)) {
      ++pos_;
    } else if (c == '/' && pos_ + 1 < n && s_[pos_ + 1] == '/') {
      while (pos_ < n && s_[pos_] != '\n') ++pos_;
    } else if (c == '/' && pos_ + 1 < n && s_[pos_ + 1] == '*') {
      const std::size_t e = s_.find("*/", pos_ + 2);
      pos_ = e == std::string::npos ? n : e + 2;
    } else {
      break;
    }
  }
}

char Cursor::peek() {
  skip_space();
  return pos_ < s_.size() ? s_[pos_] : '\0';
}

bool Cursor::at_end() { return peek() == '\0'; }

void Cursor::expect(char c, const std::string& what) {
  if (peek() != c) {
    fail("expected " + what + ", found " +
         (at_end() ? std::string("the end of the file") : "'" + std::string(1, s_[pos_]) + "'"));
  }
  ++pos_;
}

bool Cursor::accept(char c) {
  if (peek() != c) return false;
  ++pos_;
  return true;
}

std::string Cursor::token() {
  const char c = peek();
  if (c == '\0') fail("unexpected end of the file");
  if (c == '"') {
    const std::size_t e = s_.find('"', pos_ + 1);
    if (e == std::string::npos) fail("unterminated string");
    std::string out(s_.substr(pos_ + 1, e - pos_ - 1));
    pos_ = e + 1;
    return out;
  }
  if (is_delimiter(c)) fail(std::string("expected a word or number, found '") + c + "'");
  const std::size_t b = pos_;
  while (pos_ < s_.size() && !is_delimiter(s_[pos_])) ++pos_;
  return std::string(s_.substr(b, pos_ - b));
}

double Cursor::scalar() {
  skip_space();
  const char* b = s_.data() + pos_;
  const char* e = s_.data() + s_.size();
  double v = 0;
  auto r = std::from_chars(b, e, v);
  if (r.ec != std::errc() || (r.ptr < e && !is_delimiter(*r.ptr))) {
    // nan and inf as OpenFOAM writes them ("nan", "-nan", "inf")
    const std::string t = token();
    if (t == "nan" || t == "-nan" || t == "NaN") return std::nan("");
    if (t == "inf" || t == "Inf") return HUGE_VAL;
    if (t == "-inf" || t == "-Inf") return -HUGE_VAL;
    fail("expected a number, found '" + t + "'");
  }
  pos_ += static_cast<std::size_t>(r.ptr - b);
  return v;
}

std::int64_t Cursor::label() {
  skip_space();
  const char* b = s_.data() + pos_;
  const char* e = s_.data() + s_.size();
  std::int64_t v = 0;
  auto r = std::from_chars(b, e, v);
  if (r.ec != std::errc() || (r.ptr < e && !is_delimiter(*r.ptr))) {
    fail("expected an integer, found '" + token() + "'");
  }
  pos_ += static_cast<std::size_t>(r.ptr - b);
  return v;
}

std::size_t Cursor::raw_bytes_per_element(const std::string& list_type) const {
  const std::size_t sb = static_cast<std::size_t>(file_.format().scalar_bytes);
  if (list_type == "List<scalar>") return sb;
  if (list_type == "List<vector>") return 3 * sb;
  if (list_type == "List<sphericalTensor>") return sb;
  if (list_type == "List<symmTensor>") return 6 * sb;
  if (list_type == "List<tensor>") return 9 * sb;
  if (list_type == "List<label>") return static_cast<std::size_t>(file_.format().label_bytes);
  if (list_type == "List<bool>") return 1;
  fail("cannot skip binary data of '" + list_type + "'");
}

void Cursor::scalar_list(int ncomp, std::vector<double>* out) {
  out->clear();
  const std::size_t nc = static_cast<std::size_t>(ncomp);
  char c = peek();
  std::int64_t n = -1;
  if (std::isdigit(static_cast<unsigned char>(c))) {
    n = label();
    if (n < 0) fail("negative list size");
    c = peek();
  }
  if (c == '{') {  // N{value}: n copies of one value
    ++pos_;
    std::vector<double> v(nc);
    if (nc > 1) expect('(', "'(' of a vector");
    for (std::size_t k = 0; k < nc; ++k) v[k] = scalar();
    if (nc > 1) expect(')', "')' of a vector");
    expect('}', "'}' closing N{value}");
    out->reserve(static_cast<std::size_t>(n) * nc);
    for (std::int64_t i = 0; i < n; ++i) out->insert(out->end(), v.begin(), v.end());
    return;
  }
  expect('(', "'(' opening a list");
  if (file_.format().binary && n >= 0) {
    const std::size_t sb = static_cast<std::size_t>(file_.format().scalar_bytes);
    const std::size_t count = static_cast<std::size_t>(n) * nc;
    if (pos_ + count * sb > s_.size()) fail("binary list of " + std::to_string(n) + " truncated");
    out->resize(count);
    const char* p = s_.data() + pos_;
    if (sb == 8) {
      std::memcpy(out->data(), p, count * 8);
    } else {
      for (std::size_t i = 0; i < count; ++i) {
        float f;
        std::memcpy(&f, p + 4 * i, 4);
        (*out)[i] = f;
      }
    }
    pos_ += count * sb;
    expect(')', "')' closing a binary list");
    return;
  }
  if (n >= 0) out->reserve(static_cast<std::size_t>(n) * nc);
  while (peek() != ')') {
    if (at_end()) fail("list not closed");
    if (nc > 1) expect('(', "'(' of a vector");
    for (std::size_t k = 0; k < nc; ++k) out->push_back(scalar());
    if (nc > 1) expect(')', "')' of a vector");
  }
  ++pos_;
  if (n >= 0 && out->size() != static_cast<std::size_t>(n) * nc) {
    fail("list says " + std::to_string(n) + " elements but holds " +
         std::to_string(out->size() / nc));
  }
}

void Cursor::label_list(std::vector<std::int64_t>* out) {
  out->clear();
  char c = peek();
  std::int64_t n = -1;
  if (std::isdigit(static_cast<unsigned char>(c))) {
    n = label();
    c = peek();
  }
  if (c == '{') {
    ++pos_;
    const std::int64_t v = label();
    expect('}', "'}' closing N{value}");
    out->assign(static_cast<std::size_t>(n), v);
    return;
  }
  expect('(', "'(' opening a list");
  if (file_.format().binary && n >= 0) {
    const std::size_t lb = static_cast<std::size_t>(file_.format().label_bytes);
    const std::size_t count = static_cast<std::size_t>(n);
    if (pos_ + count * lb > s_.size()) fail("binary list of " + std::to_string(n) + " truncated");
    out->resize(count);
    const char* p = s_.data() + pos_;
    for (std::size_t i = 0; i < count; ++i) {
      if (lb == 4) {
        std::int32_t v;
        std::memcpy(&v, p + 4 * i, 4);
        (*out)[i] = v;
      } else {
        std::memcpy(&(*out)[i], p + 8 * i, 8);
      }
    }
    pos_ += count * lb;
    expect(')', "')' closing a binary list");
    return;
  }
  if (n >= 0) out->reserve(static_cast<std::size_t>(n));
  while (peek() != ')') {
    if (at_end()) fail("list not closed");
    out->push_back(label());
  }
  ++pos_;
  if (n >= 0 && out->size() != static_cast<std::size_t>(n)) {
    fail("list says " + std::to_string(n) + " elements but holds " + std::to_string(out->size()));
  }
}

void Cursor::face_list(std::vector<std::int64_t>* offsets, std::vector<std::int64_t>* labels) {
  offsets->clear();
  labels->clear();
  if (file_.class_name() == "faceCompactList") {
    label_list(offsets);
    label_list(labels);
    if (offsets->empty() || offsets->front() != 0 ||
        offsets->back() != static_cast<std::int64_t>(labels->size())) {
      fail("inconsistent faceCompactList offsets");
    }
    return;
  }
  const std::int64_t n = label();
  expect('(', "'(' opening the face list");
  offsets->reserve(static_cast<std::size_t>(n) + 1);
  labels->reserve(static_cast<std::size_t>(n) * 4);
  offsets->push_back(0);
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int64_t m = label();
    expect('(', "'(' of a face");
    for (std::int64_t k = 0; k < m; ++k) labels->push_back(label());
    expect(')', "')' of a face");
    offsets->push_back(static_cast<std::int64_t>(labels->size()));
  }
  expect(')', "')' closing the face list");
}

void Cursor::field_value(int ncomp, std::size_t n, std::vector<double>* out) {
  const std::size_t nc = static_cast<std::size_t>(ncomp);
  const std::string kind = token();
  if (kind == "uniform") {
    std::vector<double> v(nc);
    if (nc > 1) expect('(', "'(' of a uniform vector");
    for (std::size_t k = 0; k < nc; ++k) v[k] = scalar();
    if (nc > 1) expect(')', "')' of a uniform vector");
    out->clear();
    out->reserve(n * nc);
    for (std::size_t i = 0; i < n; ++i) out->insert(out->end(), v.begin(), v.end());
  } else if (kind == "nonuniform") {
    // "nonuniform List<T> N (...)", or an empty list written as "nonuniform 0()"
    const char c = peek();
    if (!std::isdigit(static_cast<unsigned char>(c)) && c != '(') {
      const std::string type = token();
      const std::string want = nc == 1 ? "List<scalar>" : "List<vector>";
      if (type != want) fail("expected " + want + ", found '" + type + "'");
    }
    scalar_list(ncomp, out);
    if (out->size() != n * nc) {
      fail("expected " + std::to_string(n) + " values, found " + std::to_string(out->size() / nc));
    }
  } else {
    fail("expected 'uniform' or 'nonuniform', found '" + kind + "'");
  }
}

std::vector<DictEntry> Cursor::dict(bool top_level) {
  std::vector<DictEntry> entries;
  while (true) {
    const char c = peek();
    if (c == '\0') {
      if (!top_level) fail("dictionary not closed with '}'");
      return entries;
    }
    if (c == '}') {
      if (top_level) fail("unexpected '}'");
      ++pos_;
      return entries;
    }
    if (c == ';') {  // stray semicolon
      ++pos_;
      continue;
    }
    DictEntry e;
    e.key = token();
    if (!e.key.empty() && e.key[0] == '#') {  // directive: #include "file" and the like
      if (peek() == '"') token();
      continue;
    }
    if (peek() == '{') {
      ++pos_;
      e.is_dict = true;
      e.begin = pos_;
      e.sub = dict(false);
      e.end = pos_;
    } else {
      skip_space();
      e.begin = pos_;
      skip_value();
      e.end = pos_ - 1;
    }
    entries.push_back(std::move(e));
  }
}

void Cursor::skip_value() {
  int depth = 0;
  std::string last_word;
  while (true) {
    const char c = peek();
    if (c == '\0') fail("value not terminated by ';'");
    if (c == ';' && depth == 0) {
      ++pos_;
      return;
    }
    if (c == '(' || c == '[' || c == '{') {
      ++depth;
      ++pos_;
    } else if (c == ')' || c == ']' || c == '}') {
      if (--depth < 0) fail(std::string("unbalanced '") + c + "'");
      ++pos_;
    } else if (c == ';') {
      ++pos_;
    } else {
      const std::string t = token();
      if (!file_.format().binary && !t.empty() && std::isdigit(static_cast<unsigned char>(t[0])) &&
          last_word.rfind("List<", 0) == 0 && peek() == '(') {
        // an ascii list (numbers and parentheses only): skip to its matching ')'
        int list_depth = 0;
        const std::size_t n = s_.size();
        for (; pos_ < n; ++pos_) {
          const char ch = s_[pos_];
          if (ch == '(') {
            ++list_depth;
          } else if (ch == ')' && --list_depth == 0) {
            ++pos_;
            break;
          }
        }
        if (list_depth != 0) fail("list not closed");
        last_word.clear();
        continue;
      }
      if (file_.format().binary && !t.empty() && std::isdigit(static_cast<unsigned char>(t[0])) &&
          last_word.rfind("List<", 0) == 0 && peek() == '(') {
        std::int64_t n = 0;
        std::from_chars(t.data(), t.data() + t.size(), n);
        ++pos_;
        pos_ += static_cast<std::size_t>(n) * raw_bytes_per_element(last_word);
        if (pos_ > s_.size()) fail("binary list truncated");
        expect(')', "')' closing a binary list");
        last_word.clear();
        continue;
      }
      last_word = t;
    }
  }
}

}  // namespace foam2grid
