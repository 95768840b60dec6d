#include "ranks.h"

#include <cstdlib>
#include <string>
#include <vector>

#include "util/error.h"

#ifdef LRIGID_HAVE_MPI
#include <mpi.h>
#endif

namespace lrigid::app {

namespace {

// processes mpirun started (0 when not started by mpirun)
int launched_processes() {
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"})
    if (const char* v = std::getenv(var)) return std::atoi(v);
  return 0;
}

// bodies [*begin, *end) of n for rank r of p
void block(size_t n, size_t r, size_t p, size_t* begin, size_t* end) {
  const size_t base = n / p, extra = n % p;
  *begin = r * base + (r < extra ? r : extra);
  *end = *begin + base + (r < extra ? 1 : 0);
}

// doubles: x 3, q 4, v 3, w 3, u_seen 3, t_stop, status, contact, impacts, t_touch, x_touch 3,
// hidden
constexpr int kPerBody = 25;

}  // namespace

Ranks::Ranks() {
  const int launched = launched_processes();
#ifdef LRIGID_HAVE_MPI
  if (launched > 0) {
    MPI_Init(nullptr, nullptr);
    mpi_ = true;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
  }
#else
  if (launched > 1)
    throw Error(ExitCode::Usage, "started by mpirun with " + std::to_string(launched) +
                                     " processes, but this lrigid was built without MPI "
                                     "(install libopenmpi-dev and rebuild)");
#endif
}

Ranks::~Ranks() {
#ifdef LRIGID_HAVE_MPI
  if (mpi_) MPI_Finalize();
#endif
}

void Ranks::share(size_t n, size_t* begin, size_t* end) const {
  block(n, size_t(rank_), size_t(size_), begin, end);
}

void Ranks::gather(State* state, bool reasons) const {
#ifdef LRIGID_HAVE_MPI
  if (size_ == 1) return;
  State& s = *state;
  size_t b, e;
  share(s.size(), &b, &e);
  std::vector<double> mine;
  mine.reserve((e - b) * kPerBody);
  for (size_t i = b; i < e; ++i) {
    const double rec[kPerBody] = {s.x[i].x(),      s.x[i].y(),      s.x[i].z(),
                                  s.q[i].w(),      s.q[i].x(),      s.q[i].y(),
                                  s.q[i].z(),      s.v[i].x(),      s.v[i].y(),
                                  s.v[i].z(),      s.w[i].x(),      s.w[i].y(),
                                  s.w[i].z(),      s.u_seen[i].x(), s.u_seen[i].y(),
                                  s.u_seen[i].z(), s.t_stop[i],     double(s.status[i]),
                                  double(s.contact[i]), double(s.impacts[i]),
                                  s.t_touch[i],    s.x_touch[i].x(), s.x_touch[i].y(),
                                  s.x_touch[i].z(), double(s.hidden[i])};
    mine.insert(mine.end(), rec, rec + kPerBody);
  }
  const size_t nr = static_cast<size_t>(size_);
  std::vector<int> counts(nr, 0), displs(nr, 0);
  for (int r = 0; r < size_; ++r) {
    size_t rb, re;
    block(s.size(), size_t(r), size_t(size_), &rb, &re);
    counts[size_t(r)] = int((re - rb) * kPerBody);
    displs[size_t(r)] = int(rb * kPerBody);
  }
  std::vector<double> all(root() ? s.size() * kPerBody : 0);
  MPI_Gatherv(mine.data(), int(mine.size()), MPI_DOUBLE, all.data(), counts.data(),
              displs.data(), MPI_DOUBLE, 0, MPI_COMM_WORLD);
  if (root()) {
    for (size_t i = 0; i < s.size(); ++i) {
      if (i >= b && i < e) continue;
      const double* p = &all[i * kPerBody];
      s.x[i] = Vec3(p[0], p[1], p[2]);
      s.q[i] = Quat(p[3], p[4], p[5], p[6]);
      s.v[i] = Vec3(p[7], p[8], p[9]);
      s.w[i] = Vec3(p[10], p[11], p[12]);
      s.u_seen[i] = Vec3(p[13], p[14], p[15]);
      s.t_stop[i] = p[16];
      s.status[i] = static_cast<BodyStatus>(static_cast<int>(p[17]));
      // contacts (contact/pass.h): the state, events and first touchdown the outputs show
      s.contact[i] = static_cast<ContactState>(static_cast<int>(p[18]));
      s.impacts[i] = static_cast<uint32_t>(p[19]);
      s.t_touch[i] = p[20];
      s.x_touch[i] = Vec3(p[21], p[22], p[23]);
      s.hidden[i] = static_cast<uint8_t>(p[24]);
    }
  }
  if (!reasons) return;
  // why bodies stopped: "index\0reason\0" for each of this rank's bodies with a reason
  std::string text;
  for (size_t i = b; i < e; ++i)
    if (!s.reason[i].empty()) text += std::to_string(i) + '\0' + s.reason[i] + '\0';
  int len = int(text.size());
  std::vector<int> lens(static_cast<size_t>(size_), 0);
  MPI_Gather(&len, 1, MPI_INT, lens.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  std::vector<int> offs(lens.size(), 0);
  int total = 0;
  for (int r = 0; r < size_; ++r) {
    offs[size_t(r)] = total;
    total += lens[size_t(r)];
  }
  std::vector<char> buf(root() ? size_t(total) : 0);
  MPI_Gatherv(text.data(), len, MPI_CHAR, buf.data(), lens.data(), offs.data(), MPI_CHAR, 0,
              MPI_COMM_WORLD);
  if (!root()) return;
  for (size_t p = 0; p < buf.size();) {
    const std::string index(&buf[p]);
    p += index.size() + 1;
    const std::string why(&buf[p]);
    p += why.size() + 1;
    s.reason[std::stoul(index)] = why;
  }
#else
  (void)state;
  (void)reasons;
#endif
}

uint64_t Ranks::sum(uint64_t v) const {
#ifdef LRIGID_HAVE_MPI
  if (size_ > 1) {
    unsigned long long in = v, out = 0;
    MPI_Allreduce(&in, &out, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
    return out;
  }
#endif
  return v;
}

double Ranks::max(double v) const {
#ifdef LRIGID_HAVE_MPI
  if (size_ > 1) {
    double out = v;
    MPI_Allreduce(&v, &out, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    return out;
  }
#endif
  return v;
}

void Ranks::abort(int code) const {
#ifdef LRIGID_HAVE_MPI
  if (mpi_ && size_ > 1) MPI_Abort(MPI_COMM_WORLD, code);
#else
  (void)code;
#endif
}

}  // namespace lrigid::app
