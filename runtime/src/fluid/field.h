// The fluid as the runtime sees it: mean velocity U and the Langevin coefficients derived from
// k and epsilon, either uniform or on a regular grid (one frame, or a time series interpolated
// linearly in time). Constant during a run; sampling is thread-safe.
//
// Grid storage: one 32-byte record per grid point holding everything the step needs (U, alpha,
// beta, sigma2, valid), so the 8 corners of a trilinear sample touch 8 cache lines at most.
// Invalid points (inside solids or outside the CFD mesh) get weight 0: the value at x is the
// trilinear blend over the valid corners, renormalized. x is "outside" when it lies outside the
// grid box or when the valid corners carry less than half of the trilinear weight: the wall is
// taken halfway between a valid and an invalid grid point.
//
// Streamed series (FluidField::streamed): frames are read on demand through a loader and only
// those bracketing the times about to be sampled are resident. simulate() calls prepare() for
// each stretch of steps between parallel regions; the stretches end at frame times, so at most 2
// frames are resident, 3 during the one step that crosses a frame time (4 when it wraps a
// looping series; docs/scaling.md).
#pragma once
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "fluid/turbulence_coefficients.h"
#include "util/types.h"

namespace lrigid {

struct GridGeometry {
  int n[3] = {0, 0, 0};          // points per axis
  Vec3 origin = Vec3::Zero();    // position of point (0,0,0), m
  Vec3 spacing = Vec3::Ones();   // m
  size_t points() const { return size_t(n[0]) * n[1] * n[2]; }
  Vec3 upper() const;
};

// One time of a grid as read from a file (SI units). Arrays are x-fastest, size points().
struct RawGridFrame {
  double time = 0;                 // s
  std::vector<float> U;            // 3 per point, m/s
  std::vector<float> k;            // m^2/s^2
  std::vector<float> epsilon;      // m^2/s^3
  std::vector<uint8_t> valid;      // 1 in the fluid
  // signed distance to the nearest wall, m (positive in the fluid, negative in solids;
  // docs/grid-format.md); empty: the file has none (a grid of an older foam2grid)
  std::vector<float> wall_distance;
};

struct GridRecord {
  float u[3];    // m/s
  float alpha;   // 1/s
  float beta;    // m/s^1.5
  float sigma2;  // m^2/s^2
  float valid;   // 1 or 0
  float wall_distance;  // m, signed (RawGridFrame::wall_distance); 0 when the grid has none
};
static_assert(sizeof(GridRecord) == 32, "one grid point is half a cache line");

struct FluidSample {
  Vec3 U = Vec3::Zero();              // mean velocity, world frame, m/s
  double alpha = 0;                   // 1/s
  double beta = 0;                    // m/s^1.5
  double sigma2 = 0;                  // m^2/s^2
  Mat3 grad_U = Mat3::Zero();         // dU_i/dx_j, 1/s (only when gradients are asked for)
  Vec3 grad_sigma2 = Vec3::Zero();    // m/s^2
  Vec3 dU_dt = Vec3::Zero();          // partial time derivative of U, m/s^2
  // signed distance to the nearest wall, m: the plain trilinear blend of the 8 corners (invalid
  // ones too, whose distance is negative), so it crosses 0 at the wall, exactly for a planar
  // wall. Set whenever x lies in the grid's box, also when sample() returns false; +infinity
  // outside the box, on a uniform field and on a grid without the array (older foam2grid).
  double wall_distance = HUGE_VAL;
};

enum class TimeMode { Clamp, Loop };

// Reads frame `index` (0-based, in time order) of a streamed series; throws lrigid::Error on bad
// input. Called from one thread at a time.
using FrameLoader = std::function<RawGridFrame(size_t index)>;

// What streaming did so far (all zero for a field held in memory).
struct StreamStats {
  size_t loads = 0;            // frames read
  size_t max_resident = 0;     // most frames resident at once
  double load_seconds = 0;     // wall time spent reading and converting frames, s
};

class FluidField {
 public:
  static FluidField uniform(const Vec3& U, double k, double epsilon, double nu, Drift drift,
                            const TurbulenceLimits& limits = {});
  static FluidField grid(const GridGeometry& geometry, const std::vector<RawGridFrame>& frames,
                         double nu, Drift drift, TimeMode mode,
                         const TurbulenceLimits& limits = {});
  // A series read on demand: `times` (s, increasing) of the frames `load` returns. The first
  // frame is resident from the start (for the initial state); pass it as `first` when the
  // caller has already read it (opening the series does), so it is not read again.
  static FluidField streamed(const GridGeometry& geometry, const std::vector<double>& times,
                             FrameLoader load, double nu, Drift drift, TimeMode mode,
                             const TurbulenceLimits& limits = {}, RawGridFrame* first = nullptr);

  // Streamed fields: makes resident exactly the frames sample() uses for times in
  // [t_lo, t_hi] (s), reading missing ones and dropping the rest. Not thread-safe: call it
  // between parallel regions, never while another thread samples. No-op when not streamed.
  void prepare(double t_lo, double t_hi) const;
  // The first time after t (s) at which sample() switches to another pair of frames
  // (+infinity when it never does): a stretch of steps that stays below it needs 2 frames.
  double next_frame_time(double t) const;
  bool is_streamed() const { return stream_ != nullptr; }
  size_t resident_frames() const;
  StreamStats stream_stats() const;

  // false when x is outside the fluid (outside the grid box or no valid corner). A repeat of
  // the calling thread's previous grid sample (same field, x, t) is answered from a cache.
  bool sample(const Vec3& x, double t, bool gradients, FluidSample* out) const;

  bool is_uniform() const { return frames_.empty(); }
  // the grid holds a wall distance (the first frame's file has the array wall_distance)
  bool has_wall_distance() const { return has_wall_distance_; }
  // x lies in the grid's box (always true for a uniform field)
  bool in_box(const Vec3& x) const;
  // The wall distance at x (m, the plain trilinear blend of FluidSample::wall_distance) and its
  // gradient (1, world frame; the wall's normal where it is not zero), at time t's frame. false
  // (and d = +infinity) outside the grid's box, on a uniform field or a grid without the array.
  bool wall_distance(const Vec3& x, double t, double* d, Vec3* gradient) const;
  // Is the nearest wall of every grid point of the cells that the cube of half-side `reach`
  // about x overlaps the plane z = floor_z below it (its wall distance z - floor_z, to 1e-4 m)?
  // Then the interpolated wall distance in that cube is exactly z - floor_z (trilinear
  // interpolation reproduces a linear function): no point of a body within it can reach a wall
  // but that floor. One comparison per grid point, no interpolation (contact/touching.cpp
  // skips the wall queries of a body lying on a ground that is the grid's floor; a cube reaching
  // below the grid's bottom takes its bottom layer). false outside the grid's box, on a uniform
  // field or a grid without the array.
  bool only_floor_near(const Vec3& x, double reach, double floor_z, double t) const;
  // Bodies collide with the grid's solids (scene key walls.contact = "collide", on a grid with
  // the wall distance): a point counts as in the fluid wherever some corner is valid, also where
  // the valid corners carry less than half of the weight (the contacts keep the bodies' points
  // at wall distance >= 0; the half-weight rule would stop a body lying on a roof or the ground
  // whose real surface is below the mid-point between a valid and an invalid grid point).
  void set_walls_collide(bool on);  // (a new content id: the sample cache forgets)
  bool walls_collide() const { return walls_collide_ && has_wall_distance_; }
  // A colliding ground at the grid's bottom (scene key ground.contact = "collide"): a point at
  // most one grid cell below the grid's bottom face samples the bottom layer instead of being
  // outside. A step may end a little below the ground (turbulence pushing a body lying on it),
  // and the contact after the step moves it back up; without this the ground, which usually
  // is the grid's bottom, would stop such a body.
  void set_floor_clamp(bool on);
  bool floor_clamp() const { return floor_clamp_; }
  const GridGeometry& geometry() const { return geometry_; }
  size_t frame_count() const { return frames_.size(); }
  const std::vector<double>& times() const { return times_; }
  size_t bytes() const;  // of the resident frames
  // frame i's records as floats, 8 per grid point in GridRecord's order (the batched step
  // gathers from it); the frame must be resident
  const float* frame_records(size_t i) const {
    return reinterpret_cast<const float*>(frames_[i].data());
  }
  // The frames a sample at time t blends, as sample() does: the records of frames a and b (b is
  // nullptr when one frame serves), the weight lam of b, and 1 / (t_b - t_a) (1/s) for dU/dt.
  // The frames must be resident (prepare).
  struct FrameBlend {
    const float* a = nullptr;
    const float* b = nullptr;
    double lam = 0, inv_dt = 0;
  };
  FrameBlend frames_at(double t) const;

 private:
  struct Stream;
  // the frames sample() blends at time t: i and j (equal when one frame serves), lam in [0, 1]
  void bracket(double t, size_t* i, size_t* j, double* lam) const;
  // the frame the wall-distance queries read at time t: t's own when resident, else any resident
  // one (the solids do not move); null when none is
  const std::vector<GridRecord>* wall_frame(double t) const;
  static std::vector<GridRecord> records(const GridGeometry& geometry, const RawGridFrame& raw,
                                         double nu, Drift drift, const TurbulenceLimits& limits);

  bool sample_frame(const std::vector<GridRecord>& frame, const Vec3& x, bool gradients,
                    FluidSample* out) const;
  bool sample_uncached(const Vec3& x, double t, bool gradients, FluidSample* out) const;

  FluidSample uniform_;
  uint64_t id_ = 0;  // names the content for the per-thread last-sample cache (field.cpp)
  GridGeometry geometry_;
  // one entry per time; a streamed field keeps non-resident frames empty (prepare() fills them)
  mutable std::vector<std::vector<GridRecord>> frames_;
  std::vector<double> times_;
  TimeMode mode_ = TimeMode::Clamp;
  std::shared_ptr<Stream> stream_;  // null unless streamed
  // the first frame has a wall distance (set when it is read, by prepare() for a stream)
  mutable bool has_wall_distance_ = false;
  bool walls_collide_ = false;
  bool floor_clamp_ = false;
};

}  // namespace lrigid
