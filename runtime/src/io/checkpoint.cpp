#include "io/checkpoint.h"

#include <elf.h>
#include <link.h>

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <type_traits>

#include "io/atomic_file.h"
#include "io/durable.h"
#include "util/error.h"

namespace lrigid {

namespace {

// format 3 ends in a checksum of everything before it; format 2 (an older lrigid's) has none;
// format 7 holds the contact impulses between bodies (State::pair_impulses); format 8's run
// counts hold the stretches taken in lockstep (RunStats::lockstep_stretches)
constexpr char kMagic[8] = {'L', 'R', 'I', 'G', 'C', 'K', 'P', '8'};
constexpr char kMagicUnchecked[8] = {'L', 'R', 'I', 'G', 'C', 'K', 'P', '2'};

using Fnv = Fnv64;

// (arrays are written as their bytes: no padding, nothing but values)
static_assert(sizeof(PairImpulse) == 64 && std::is_trivially_copyable_v<PairImpulse>);
// (the run's counts too: a change of RunStats's fields is a new format, kMagic)
static_assert(sizeof(RunStats) == 96 && std::is_trivially_copyable_v<RunStats>);

}  // namespace

BinaryIn::BinaryIn(std::istream& in, std::string file) : in_(in), file_(std::move(file)) {
  const std::streampos here = in_.tellg();
  if (here < 0) return;
  in_.seekg(0, std::ios::end);
  end_ = in_.tellg();
  in_.seekg(here);
  if (!in_) {  // not seekable after all: read without the bound
    in_.clear();
    in_.seekg(here);
    end_ = -1;
  }
}

uint64_t BinaryIn::length(size_t item) {
  uint64_t n = 0;
  pod(&n);
  // an array cannot be longer than what is left of the file (a length written wrong would
  // otherwise allocate up to the bound below, or more than the machine has)
  const std::streamoff at = end_ >= 0 ? std::streamoff(in_.tellg()) : -1;
  const uint64_t left = at >= 0 && end_ >= at ? uint64_t(end_ - at) : uint64_t(1) << 40;
  if (n > (uint64_t(1) << 40) / (item ? item : 1) || n > left / (item ? item : 1))
    fail_input(file_, "", "corrupt checkpoint (an array of " + std::to_string(n) + " items)");
  return n;
}

void BinaryIn::read(char* p, size_t n) {
  in_.read(p, std::streamsize(n));
  if (size_t(in_.gcount()) != n) fail_input(file_, "", "truncated checkpoint");
}

std::string text_fingerprint(const std::string& text) {
  Fnv f;
  f.add(text.data(), text.size());
  return f.hex();
}

std::string file_fingerprint(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  Fnv f;
  std::vector<char> buf(1 << 16);
  while (in) {
    in.read(buf.data(), std::streamsize(buf.size()));
    f.add(buf.data(), size_t(in.gcount()));
  }
  return f.hex();
}

namespace {

// The GNU build-id note of the running program (dl_iterate_phdr visits it first), as hex; ""
// when it has none
int program_build_id(dl_phdr_info* info, size_t, void* out) {
  for (int k = 0; k < info->dlpi_phnum; ++k) {
    const ElfW(Phdr)& ph = info->dlpi_phdr[k];
    if (ph.p_type != PT_NOTE) continue;
    const size_t align = ph.p_align == 8 ? 8 : 4;
    auto padded = [align](size_t n) { return (n + align - 1) / align * align; };
    const char* p = reinterpret_cast<const char*>(info->dlpi_addr + ph.p_vaddr);
    const char* end = p + ph.p_memsz;
    while (p + sizeof(ElfW(Nhdr)) <= end) {
      ElfW(Nhdr) nh;
      std::memcpy(&nh, p, sizeof nh);
      const char* name = p + sizeof nh;
      const char* desc = name + padded(nh.n_namesz);
      const char* next = desc + padded(nh.n_descsz);
      if (next > end) break;
      if (nh.n_type == NT_GNU_BUILD_ID && nh.n_namesz == 4 && std::memcmp(name, "GNU", 4) == 0) {
        std::string& hex = *static_cast<std::string*>(out);
        char two[3];
        for (size_t b = 0; b < nh.n_descsz; ++b) {
          std::snprintf(two, sizeof two, "%02x", static_cast<unsigned char>(desc[b]));
          hex += two;
        }
        return 1;
      }
      p = next;
    }
  }
  return 1;  // the program only, not its libraries
}

}  // namespace

std::string build_fingerprint() {
  // the build-id the linker wrote (a hash of the linked binary), read from memory at once; the
  // whole file's FNV where there is none (35 MB read at each run: 0.05 s)
  std::string id;
  dl_iterate_phdr(program_build_id, &id);
  return id.empty() ? file_fingerprint("/proc/self/exe") : "gnu-build-id:" + id;
}

void write_checkpoint(const std::string& path, const CheckpointId& id, int rank,
                      const State& st, const RunStats& stats,
                      const std::function<void(BinaryOut&)>& extra) {
  // built in memory, then written with its checksum (FNV-1a 64 of every byte before it)
  std::ostringstream o(std::ios::binary);
  {
    BinaryOut b(o);
    o.write(kMagic, sizeof kMagic);
    b.str(id.build);
    b.str(id.scene);
    b.pod(int32_t(id.ranks));
    b.pod(int32_t(rank));
    b.pod(st.t);
    b.pod(st.step);
    b.vec(st.x);
    b.vec(st.q);
    b.vec(st.v);
    b.vec(st.w);
    b.vec(st.u_seen);
    b.vec(st.type);
    b.vec(st.status);
    b.vec(st.t_stop);
    b.pod(uint64_t(st.reason.size()));
    for (const std::string& r : st.reason) b.str(r);
    b.vec(st.history);
    b.vec(st.history_offset);
    // contacts (contact/sleep.h)
    b.vec(st.contact);
    b.vec(st.rest_steps);
    b.vec(st.impacts);
    b.vec(st.t_touch);
    b.vec(st.x_touch);
    b.vec(st.hidden);
    b.vec(st.watch);
    b.vec(st.pair_impulses);
    b.pod(stats);
    extra(b);
  }
  const std::string bytes = std::move(o).str();
  Fnv sum;
  sum.add(bytes.data(), bytes.size());
  write_file_atomically(path, [&](std::ostream& out) {
    out.write(bytes.data(), std::streamsize(bytes.size()));
    out.write(reinterpret_cast<const char*>(&sum.h), sizeof sum.h);
  });
}

void read_checkpoint(const std::string& path, const CheckpointId& id, int rank, State* st,
                     RunStats* stats, const std::function<void(BinaryIn&)>& extra) {
  std::string bytes;
  {
    std::ifstream f(path, std::ios::binary);
    if (!f) {
      std::error_code ec;
      fail_input(path, "",
                 std::filesystem::exists(path, ec)
                     ? "checkpoint cannot be read"
                     : "checkpoint missing (the step that checkpoint/latest.json names has no "
                       "file for this rank)");
    }
    std::stringstream ss;
    ss << f.rdbuf();
    bytes = std::move(ss).str();
  }
  if (bytes.size() >= sizeof kMagic &&
      std::memcmp(bytes.data(), kMagicUnchecked, sizeof kMagicUnchecked) == 0)
    fail_input(path, "",
               "a checkpoint of format 2 (an older lrigid's), which has no checksum, so it "
               "cannot be verified; it is refused rather than trusted: resume it with the lrigid "
               "that wrote it, or start the run afresh");
  if (bytes.size() < sizeof kMagic + sizeof(uint64_t) ||
      std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
    fail_input(path, "", "not an lrigid checkpoint (or one of another format version)");
  {
    uint64_t want = 0;
    const size_t body = bytes.size() - sizeof want;
    std::memcpy(&want, bytes.data() + body, sizeof want);
    Fnv sum;
    sum.add(bytes.data(), body);
    if (sum.h != want)
      fail_input(path, "",
                 "checksum mismatch (" + sum.hex() + ", written " + Fnv{want}.hex() +
                     "): the checkpoint is corrupt or cut short; nothing was changed");
    bytes.resize(body);
  }
  std::istringstream in(std::move(bytes), std::ios::binary);
  BinaryIn b(in, path);
  char magic[sizeof kMagic];
  b.pod(&magic);
  std::string build, scene;
  int32_t ranks = 0, r = 0;
  b.str(&build);
  b.str(&scene);
  b.pod(&ranks);
  b.pod(&r);
  if (build != id.build)
    fail_input(path, "",
               "written by another build of lrigid (fingerprint " + build + ", this one " +
                   id.build + "): resume with the binary that started the run");
  if (scene != id.scene)
    fail_input(path, "",
               "written by a run of another scene (or another seed, integrator or dt): the "
               "scene given differs from the one the run started with");
  if (ranks != id.ranks)
    fail_input(path, "",
               "written by a run of " + std::to_string(ranks) + " MPI rank(s); resume with " +
                   (ranks > 1 ? "mpirun -np " + std::to_string(ranks) : "one process"));
  if (r != rank) fail_input(path, "", "holds rank " + std::to_string(r));
  const size_t n = st->size();
  b.pod(&st->t);
  b.pod(&st->step);
  b.vec(&st->x);
  b.vec(&st->q);
  b.vec(&st->v);
  b.vec(&st->w);
  b.vec(&st->u_seen);
  b.vec(&st->type);
  b.vec(&st->status);
  b.vec(&st->t_stop);
  uint64_t nr = 0;
  b.pod(&nr);
  if (nr != n) fail_input(path, "", "holds another number of bodies");
  st->reason.resize(n);
  for (std::string& s : st->reason) b.str(&s);
  b.vec(&st->history);
  b.vec(&st->history_offset);
  b.vec(&st->contact);
  b.vec(&st->rest_steps);
  b.vec(&st->impacts);
  b.vec(&st->t_touch);
  b.vec(&st->x_touch);
  b.vec(&st->hidden);
  b.vec(&st->watch);
  b.vec(&st->pair_impulses);
  for (size_t k : {st->x.size(), st->q.size(), st->v.size(), st->w.size(), st->u_seen.size(),
                   st->type.size(), st->status.size(), st->t_stop.size(),
                   st->history_offset.size(), st->contact.size(), st->rest_steps.size(),
                   st->impacts.size(), st->t_touch.size(), st->x_touch.size(),
                   st->hidden.size()})
    if (k != n) fail_input(path, "", "holds another number of bodies");
  // the gust watches: one per body where contacts are on, none otherwise
  if (!st->watch.empty() && st->watch.size() != n)
    fail_input(path, "", "holds another number of bodies");
  // the contact impulses: of bodies it has, sorted by their pair, each pushing
  for (size_t k = 0; k < st->pair_impulses.size(); ++k) {
    const PairImpulse& p = st->pair_impulses[k];
    const bool pair = p.a < n && (p.b == PairImpulse::kSurface || (p.a < p.b && p.b < n));
    const bool sorted = k == 0 || st->pair_impulses[k - 1].a < p.a ||
                        (st->pair_impulses[k - 1].a == p.a && st->pair_impulses[k - 1].b <= p.b);
    bool finite = std::isfinite(p.jn) && p.jn > 0;
    for (int e = 0; e < 3; ++e) finite = finite && std::isfinite(p.r[e]) && std::isfinite(p.jt[e]);
    if (!pair || !sorted || !finite)
      fail_input(path, "", "corrupt checkpoint (contact impulse " + std::to_string(k) + ")");
  }
  b.pod(stats);
  extra(b);
  if (in.peek() != std::char_traits<char>::eof())
    fail_input(path, "", "corrupt checkpoint (bytes left after its end)");
}

}  // namespace lrigid
