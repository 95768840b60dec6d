#include "fluid/field.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstddef>

#include "fluid/trilinear.h"

namespace lrigid {

namespace {
// ids of grid fields' contents (FluidField::id_)
std::atomic<uint64_t> next_field_id{1};

// The cell of grid g holding x: its first corner's indices i0 and x's fractions f (0..1) along
// each axis; false outside the grid's box (also for NaN). floor_clamp: within a cell below the
// bottom face, the bottom layer (FluidField::set_floor_clamp).
bool locate_cell(const GridGeometry& g, const Vec3& x, bool floor_clamp, int* i0, double* f) {
  for (int a = 0; a < 3; ++a) {
    double s = (x[a] - g.origin[a]) / g.spacing[a];
    if (a == 2 && floor_clamp && s < 0.0 && s >= -1.0) s = 0.0;
    if (!(s >= 0.0 && s <= double(g.n[a] - 1))) return false;
    int i = static_cast<int>(s);
    if (i > g.n[a] - 2) i = g.n[a] - 2;
    i0[a] = i;
    f[a] = s - i;
  }
  return true;
}

// A cell's 8 corner records (c = cx + 2 cy + 4 cz) as offsets in floats from its first record's
// (the records' kernels of fluid/trilinear.h), and the first record's offset in floats.
constexpr int kRecordFloats = sizeof(GridRecord) / sizeof(float);
void corner_offsets(const GridGeometry& g, int* off) {
  const int ry = kRecordFloats * g.n[0], rz = ry * g.n[1];
  for (int c = 0; c < 8; ++c)
    off[c] = ((c & 1) ? kRecordFloats : 0) + ((c & 2) ? ry : 0) + ((c & 4) ? rz : 0);
}
size_t first_record(const GridGeometry& g, const int* i0) {
  const size_t sy = size_t(g.n[0]), sz = size_t(g.n[0]) * size_t(g.n[1]);
  return kRecordFloats * (size_t(i0[0]) + size_t(i0[1]) * sy + size_t(i0[2]) * sz);
}
// the wall distance's slot in a record
constexpr int kWallSlot = offsetof(GridRecord, wall_distance) / sizeof(float);
}  // namespace

Vec3 GridGeometry::upper() const {
  return origin +
         Vec3(spacing.x() * (n[0] - 1), spacing.y() * (n[1] - 1), spacing.z() * (n[2] - 1));
}

FluidField FluidField::uniform(const Vec3& U, double k, double epsilon, double nu, Drift drift,
                               const TurbulenceLimits& limits) {
  FluidField f;
  const LangevinCoefficients c = langevin_coefficients(k, epsilon, nu, drift, limits);
  f.uniform_.U = U;
  f.uniform_.alpha = c.alpha;
  f.uniform_.beta = c.beta;
  f.uniform_.sigma2 = c.sigma2;
  return f;
}

std::vector<GridRecord> FluidField::records(const GridGeometry& geometry, const RawGridFrame& raw,
                                            double nu, Drift drift,
                                            const TurbulenceLimits& limits) {
  const size_t np = geometry.points();
  std::vector<GridRecord> recs(np);
  for (size_t p = 0; p < np; ++p) {
    GridRecord& r = recs[p];
    const bool valid = raw.valid.empty() || raw.valid[p] != 0;
    r.valid = valid ? 1.f : 0.f;
    r.wall_distance = raw.wall_distance.empty() ? 0.f : raw.wall_distance[p];
    for (int a = 0; a < 3; ++a) r.u[a] = valid && !raw.U.empty() ? raw.U[3 * p + a] : 0.f;
    if (valid && !raw.k.empty()) {
      const LangevinCoefficients c = langevin_coefficients(raw.k[p], raw.epsilon[p], nu, drift,
                                                           limits);
      r.alpha = float(c.alpha);
      r.beta = float(c.beta);
      r.sigma2 = float(c.sigma2);
    } else {
      r.alpha = r.beta = r.sigma2 = 0.f;
    }
  }
  return recs;
}

FluidField FluidField::grid(const GridGeometry& geometry, const std::vector<RawGridFrame>& frames,
                            double nu, Drift drift, TimeMode mode,
                            const TurbulenceLimits& limits) {
  FluidField f;
  f.id_ = next_field_id++;
  f.geometry_ = geometry;
  f.mode_ = mode;
  f.has_wall_distance_ = !frames.empty() && !frames.front().wall_distance.empty();
  for (const RawGridFrame& raw : frames) {
    f.frames_.push_back(records(geometry, raw, nu, drift, limits));
    f.times_.push_back(raw.time);
  }
  return f;
}

struct FluidField::Stream {
  FrameLoader load;
  double nu = 0;
  Drift drift = Drift::Stationary;
  TurbulenceLimits limits;
  StreamStats stats;
};

FluidField FluidField::streamed(const GridGeometry& geometry, const std::vector<double>& times,
                                FrameLoader load, double nu, Drift drift, TimeMode mode,
                                const TurbulenceLimits& limits, RawGridFrame* first) {
  FluidField f;
  f.geometry_ = geometry;
  f.mode_ = mode;
  f.times_ = times;
  f.frames_.resize(times.size());
  f.stream_ = std::make_shared<Stream>();
  f.stream_->load = std::move(load);
  f.stream_->nu = nu;
  f.stream_->drift = drift;
  f.stream_->limits = limits;
  // the first frame is what model compilation and the initial state sample; a frame the caller
  // already read is taken as it is (not counted as a read)
  if (first && !times.empty()) {
    f.frames_[0] = records(geometry, *first, nu, drift, limits);
    f.has_wall_distance_ = !first->wall_distance.empty();
  }
  if (!times.empty()) f.prepare(times.front(), times.front());
  return f;
}

void FluidField::bracket(double t, size_t* i, size_t* j, double* lam) const {
  *lam = 0;
  if (frames_.size() == 1 || !(t > times_.front())) {
    *i = *j = 0;
    return;
  }
  const double t0 = times_.front(), t1 = times_.back();
  double tt = t;
  if (mode_ == TimeMode::Loop && t1 > t0) tt = t0 + std::fmod(t - t0, t1 - t0);
  if (tt >= t1) {
    *i = *j = frames_.size() - 1;
    return;
  }
  *j = size_t(std::upper_bound(times_.begin(), times_.end(), tt) - times_.begin());
  *i = *j - 1;
  *lam = (tt - times_[*i]) / (times_[*j] - times_[*i]);
}

FluidField::FrameBlend FluidField::frames_at(double t) const {
  FrameBlend f;
  if (frames_.empty()) return f;
  size_t i, j;
  bracket(t, &i, &j, &f.lam);
  f.a = frame_records(i);
  if (i != j) {
    f.b = frame_records(j);
    f.inv_dt = 1.0 / (times_[j] - times_[i]);
  } else {
    f.lam = 0;
  }
  return f;
}

double FluidField::next_frame_time(double t) const {
  if (times_.size() < 2) return HUGE_VAL;
  const double t0 = times_.front(), t1 = times_.back();
  if (!(t >= t0)) return t0;
  if (mode_ == TimeMode::Loop && t1 > t0) {
    const double tt = t0 + std::fmod(t - t0, t1 - t0);
    const size_t j = size_t(std::upper_bound(times_.begin(), times_.end(), tt) - times_.begin());
    const double next = t + ((j < times_.size() ? times_[j] : t1) - tt);
    return next > t ? next : std::nextafter(t, HUGE_VAL);  // always ahead, even after rounding
  }
  if (t >= t1) return HUGE_VAL;
  return *std::upper_bound(times_.begin(), times_.end(), t);
}

void FluidField::prepare(double t_lo, double t_hi) const {
  if (!stream_) return;
  // the frames of every bracket met on [t_lo, t_hi]: brackets change only at frame times
  std::vector<char> need(frames_.size(), 0);
  auto add = [&](double t) {
    size_t i, j;
    double lam;
    bracket(t, &i, &j, &lam);
    need[i] = need[j] = 1;
  };
  add(t_lo);
  for (double t = next_frame_time(t_lo); t <= t_hi; t = next_frame_time(t)) add(t);
  add(t_hi);
  // drop first, then read: the peak is the frames needed, not old plus new
  for (size_t k = 0; k < frames_.size(); ++k)
    if (!need[k] && !frames_[k].empty()) std::vector<GridRecord>().swap(frames_[k]);
  size_t resident = 0;
  for (size_t k = 0; k < frames_.size(); ++k) {
    if (need[k] && frames_[k].empty()) {
      const auto start = std::chrono::steady_clock::now();
      const RawGridFrame raw = stream_->load(k);
      if (k == 0) has_wall_distance_ = !raw.wall_distance.empty();
      frames_[k] = records(geometry_, raw, stream_->nu, stream_->drift, stream_->limits);
      stream_->stats.load_seconds +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      ++stream_->stats.loads;
    }
    resident += need[k];
  }
  stream_->stats.max_resident = std::max(stream_->stats.max_resident, resident);
}

size_t FluidField::resident_frames() const {
  size_t r = 0;
  for (const auto& fr : frames_) r += !fr.empty();
  return r;
}

StreamStats FluidField::stream_stats() const { return stream_ ? stream_->stats : StreamStats{}; }

bool FluidField::in_box(const Vec3& x) const {
  if (frames_.empty()) return true;
  const Vec3 hi = geometry_.upper();
  for (int a = 0; a < 3; ++a)
    if (!(x[a] >= geometry_.origin[a] && x[a] <= hi[a])) return false;
  return true;
}

void FluidField::set_walls_collide(bool on) {
  if (on == walls_collide_) return;
  walls_collide_ = on;
  id_ = next_field_id++;
}

void FluidField::set_floor_clamp(bool on) {
  if (on == floor_clamp_) return;
  floor_clamp_ = on;
  id_ = next_field_id++;
}

const std::vector<GridRecord>* FluidField::wall_frame(double t) const {
  // the solids do not move: any resident frame holds the same distances. A streamed series keeps
  // only the frames about to be sampled (prepare), so t's own frame may be gone: a caller that
  // asked at another time (exit_reason asks at t = 0) read a released frame (SIGSEGV in
  // bench/perf/stream_bench.sh, the tank series with colliding walls)
  if (frames_.size() == 1) return frames_[0].empty() ? nullptr : &frames_[0];  // a steady field
  size_t i, j;
  double lam;
  bracket(t, &i, &j, &lam);
  if (!frames_[i].empty()) return &frames_[i];
  for (const std::vector<GridRecord>& f : frames_)
    if (!f.empty()) return &f;
  return nullptr;
}

bool FluidField::wall_distance(const Vec3& x, double t, double* d, Vec3* gradient) const {
  *d = HUGE_VAL;
  gradient->setZero();
  if (frames_.empty() || !has_wall_distance_) return false;
  const GridGeometry& g = geometry_;
  int i0[3];
  double f[3];
  if (!locate_cell(g, x, false, i0, f)) return false;
  const std::vector<GridRecord>* walls = wall_frame(t);
  if (!walls) return false;
  int off[8];
  corner_offsets(g, off);
  double grad[3];
  *d = trilinear_slot(reinterpret_cast<const float*>(walls->data()) + first_record(g, i0), off,
                      kWallSlot, f, grad);
  for (int a = 0; a < 3; ++a) (*gradient)[a] = grad[a] / g.spacing[a];
  return true;
}

bool FluidField::only_floor_near(const Vec3& x, double reach, double floor_z, double t) const {
  if (frames_.empty() || !has_wall_distance_) return false;
  const GridGeometry& g = geometry_;
  int lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    double s0 = (x[a] - reach - g.origin[a]) / g.spacing[a];
    const double s1 = (x[a] + reach - g.origin[a]) / g.spacing[a];
    // below the grid's bottom is the floor's side (a body lying on a floor at the bottom
    // reaches below it): the bottom layer
    if (a == 2 && s0 < 0.0 && s1 >= 0.0) s0 = 0.0;
    if (!(s0 >= 0.0 && s1 <= double(g.n[a] - 1))) return false;
    lo[a] = static_cast<int>(s0);
    hi[a] = std::min(static_cast<int>(std::ceil(s1)), g.n[a] - 1);
  }
  const std::vector<GridRecord>* walls = wall_frame(t);
  if (!walls) return false;
  const std::vector<GridRecord>& frame = *walls;
  const size_t sy = size_t(g.n[0]), sz = size_t(g.n[0]) * size_t(g.n[1]);
  for (int k = lo[2]; k <= hi[2]; ++k) {
    const double above = g.origin[2] + k * g.spacing[2] - floor_z;
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int i = lo[0]; i <= hi[0]; ++i) {
        const double d = double(frame[size_t(i) + size_t(j) * sy + size_t(k) * sz].wall_distance);
        if (!(std::abs(d - above) <= 1e-4)) return false;
      }
  }
  return true;
}

size_t FluidField::bytes() const {
  size_t b = 0;
  for (const auto& fr : frames_) b += fr.size() * sizeof(GridRecord);
  return b;
}

bool FluidField::sample_frame(const std::vector<GridRecord>& frame, const Vec3& x, bool gradients,
                              FluidSample* out) const {
  const GridGeometry& g = geometry_;
  int i0[3];
  double f[3];
  if (!locate_cell(g, x, floor_clamp_, i0, f)) {
    out->wall_distance = HUGE_VAL;
    return false;
  }
  // the 8 corners' records (fluid/trilinear.h, the batched step's kernel too)
  int off[8];
  corner_offsets(g, off);
  const float* r0 = reinterpret_cast<const float*>(frame.data()) + first_record(g, i0);
  Record8<double>::type v, dv[3];
  const int nvalid =
      gradients ? trilinear_record<double, true>(r0, off, f, &v, &dv[0], &dv[1], &dv[2])
                : trilinear_record<double, false>(r0, off, f, &v, &dv[0], &dv[1], &dv[2]);
  const double W = v[6];
  // the wall distance (slot 7) with the plain trilinear weights: invalid corners hold negative
  // distances, so the blend crosses 0 at the wall (trilinear_record weighs slots by validity)
  // (only when the grid has the array: grids without it answer +infinity)
  double wall = HUGE_VAL;
  if (has_wall_distance_) {
    double unused[3];
    wall = trilinear_slot(r0, off, kWallSlot, f, unused);
  }
  out->wall_distance = wall;
  // the wall lies between a valid and an invalid grid point: x is in the fluid when the valid
  // corners carry at least half of the trilinear weight (the wall at mid-spacing, error <= h/2)
  // (with colliding walls the contacts keep the bodies out of the solids: any valid corner
  // gives the flow, field.h set_walls_collide)
  if (nvalid == 0 || (W < 0.5 && !(walls_collide_ && has_wall_distance_))) return false;
  const double inv = 1.0 / W;
  out->U = Vec3(v[0], v[1], v[2]) * inv;
  out->alpha = v[3] * inv;
  out->beta = v[4] * inv;
  out->sigma2 = v[5] * inv;
  if (gradients) {
    // next to invalid points the renormalized blend has no reliable gradient: use none there
    if (nvalid == 8) {
      for (int i = 0; i < 3; ++i)
        for (int a = 0; a < 3; ++a) out->grad_U(i, a) = dv[a][i] / g.spacing[a];
      for (int a = 0; a < 3; ++a) out->grad_sigma2[a] = dv[a][5] / g.spacing[a];
    } else {
      out->grad_U.setZero();
      out->grad_sigma2.setZero();
    }
  }
  return true;
}

namespace {

// The last grid sample of this thread. A sample is a pure function of (field content, x, t) and
// a step asks for the same one more than once (splitting: the turbulence half step and the
// impulse step at the start of the step; the end of a step and the second half step in a steady
// field), so a repeat is answered from here. The field's id names its content (copies share it).
struct LastSample {
  uint64_t field = 0;
  Vec3 x = Vec3::Constant(std::nan(""));
  double t = 0;
  bool gradients = false, inside = false;
  FluidSample s;
};
thread_local LastSample last_sample;

}  // namespace

bool FluidField::sample(const Vec3& x, double t, bool gradients, FluidSample* out) const {
  if (frames_.empty()) {
    *out = uniform_;
    return std::isfinite(x.x()) && std::isfinite(x.y()) && std::isfinite(x.z());
  }
  LastSample& last = last_sample;
  const bool steady = frames_.size() == 1;
  if (last.field == id_ && last.x == x && (steady || last.t == t) &&
      (last.gradients || !gradients)) {
    *out = last.s;
    if (!gradients) {
      out->grad_U.setZero();
      out->grad_sigma2.setZero();
    }
    return last.inside;
  }
  last.inside = sample_uncached(x, t, gradients, out);
  last.field = id_;
  last.x = x;
  last.t = t;
  last.gradients = gradients;
  last.s = *out;
  return last.inside;
}

bool FluidField::sample_uncached(const Vec3& x, double t, bool gradients,
                                 FluidSample* out) const {
  out->dU_dt.setZero();
  size_t i, j;
  double lam;
  bracket(t, &i, &j, &lam);
  if (i == j) return sample_frame(frames_[i], x, gradients, out);
  FluidSample a, b;
  const bool in_a = sample_frame(frames_[i], x, gradients, &a);
  const bool in_b = sample_frame(frames_[j], x, gradients, &b);
  // the mesh does not move: the frames' distances agree (and are +infinity outside the box)
  out->wall_distance = std::isfinite(a.wall_distance) && std::isfinite(b.wall_distance)
                           ? (1 - lam) * a.wall_distance + lam * b.wall_distance
                           : std::min(a.wall_distance, b.wall_distance);
  if (!in_a || !in_b) return false;
  const double dt = times_[j] - times_[i];
  out->U = (1 - lam) * a.U + lam * b.U;
  out->alpha = (1 - lam) * a.alpha + lam * b.alpha;
  out->beta = (1 - lam) * a.beta + lam * b.beta;
  out->sigma2 = (1 - lam) * a.sigma2 + lam * b.sigma2;
  out->dU_dt = (b.U - a.U) / dt;
  if (gradients) {
    out->grad_U = (1 - lam) * a.grad_U + lam * b.grad_U;
    out->grad_sigma2 = (1 - lam) * a.grad_sigma2 + lam * b.grad_sigma2;
  }
  return true;
}

}  // namespace lrigid
