// What the batched step's loops (integrate/rigid_batch_step.h, for each kind of M) share: the
// compile switches of their loops across bodies, the field sample and the Ornstein-Uhlenbeck half
// step in structure-of-arrays form, the per-lane normals, and the driver that runs a block of
// bodies through a stretch of steps and stops them as the scalar loop of integrate/simulation.cpp
// does. Internal to the files that instantiate the loops: everything here has internal linkage
// (each file compiles its own versions of the loops, see LRIGID_MULTIVERSION).
#pragma once
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>

#include "contact/events.h"
#include "contact/pass.h"
#include "contact/sleep.h"
#include "effects/basset.h"
#include "effects/drag.h"
#include "effects/magnus.h"
#include "effects/plan.h"
#include "effects/registry.h"
#include "effects/turbulence.h"
#include "fluid/trilinear.h"
#include "integrate/dynamics.h"
#include "integrate/impacts.h"
#include "integrate/integrators.h"
#include "integrate/rigid_batch.h"
#include "integrate/step_end.h"
#include "integrate/sweep.h"
#include "model/model.h"
#include "model/state.h"
#include "util/fast_math.h"
#include "util/lane.h"
#include "util/rng.h"

namespace lrigid {
namespace {  // NOLINT(build/namespaces): internal to the two batched-step files

// The loops across bodies are compiled for AVX-512, AVX2 and the baseline, and the best the CPU
// has is chosen when the program loads (GCC's function multiversioning; docs/performance.md
// gives the speed of each). A loop vectorizes only if every operation in it has a vector form in
// that instruction set: AVX2 has none for conversions between double and 64-bit integers or for
// 64-bit arithmetic shifts, so the loops' helpers (util/fast_math.h) do without them, and
// clones_vectorized_test checks the AVX2 and AVX-512 versions in the machine code. Rounding can
// differ between the versions (fused multiply-adds), never between threads. Clang 14 does not
// multiversion templates: its builds (the fuzz targets) run the baseline.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define LRIGID_MULTIVERSION \
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define LRIGID_MULTIVERSION
#endif

// The loops across bodies carry LRIGID_IVDEP (GCC's `ivdep`: their iterations are independent),
// not `#pragma omp simd`: OpenMP sizes the per-lane copies of a loop's local arrays before GCC
// makes the versions above, and the AVX-512 and AVX2 versions then stay scalar (measured: 4.9
// against 13 M body-steps/s per core). The per-body helpers are inlined into each version (a call
// would run the baseline one).
#if defined(__GNUC__) && !defined(__clang__)
#define LRIGID_IVDEP _Pragma("GCC ivdep")
#else
// Clang: no hint. Its 'vectorize(assume_safety)' is an order that fails the build (-Werror) where
// it cannot vectorize, as in the sanitizer builds of the fuzz targets, which are not for speed.
#define LRIGID_IVDEP
#endif

// A lambda holding one lane's update, written once for a vectorised loop over a whole block and a
// loop over a few chosen lanes: inlined into both (and so into each multiversioned copy).
#if defined(__GNUC__)
#define LRIGID_LANE_LAMBDA __attribute__((always_inline))
#else
#define LRIGID_LANE_LAMBDA
#endif

// What every batched step needs of the model and the body type: the field and the switches of
// the Langevin model.
struct FieldConsts {
  double h = 0;
  bool turb = false;    // seen turbulence
  bool sample = false;  // the field is sampled at all
  bool grid = false;
  // switches as factors 1 or 0, so the loops across bodies stay free of branches: mean flow,
  // Thomson's drift, grad U for the fluid acceleration (added mass in a mean flow)
  double mf = 0, wm = 0, gu = 0, tu = 0;  // (tu: the seen fluctuation in the fluid velocity)
  // crossing trajectories (effects/turbulence.h): the type's drift speed squared (m^2/s^2) and
  // direction (world, unit; zero without a drift)
  double vd2 = 0, cd[3] = {0, 0, 0};
  double mean_flow_scale = 1, turbulence_scale = 1;
  double F[3] = {0, 0, 0};  // gravity and buoyancy, world frame, N
  // the effects with memory or spin, as runtime factors (0 without them): the Basset
  // history's current interval as a mass on the left-hand side (BassetKernel::implicit_mass, kg;
  // 0 without) and its history force Samples::fb; the Magnus factor C_M rho V (0 without), kg
  bool basset = false;
  double basset_mass = 0, magnus = 0;
  // a centre of mass off the volume centroid (zero for a uniform body): r_cob, the centroid from the centre
  // of mass (body frame, m), where the fluid's forces and the buoyancy F_buoy (world, N) act
  double r_cob[3] = {0, 0, 0}, F_buoy[3] = {0, 0, 0};
  // grid
  double origin[3] = {0, 0, 0}, spacing[3] = {1, 1, 1}, upper_index[3] = {0, 0, 0};
  int points[3] = {0, 0, 0};  // grid points per axis
  int64_t sy = 0, sz = 0;
  const float* records = nullptr;
  FluidSample uniform;  // art scales applied
  bool ground = false;
  double ground_z = 0, half[3] = {0, 0, 0};
  bool round = false;  // a sphere or ellipsoid (contact/events.h ground_reach)
  uint64_t seed = 0;
  // contacts (contact/pass.h): the ground or the grid's solids collide; has_wall: the
  // samples carry the wall distance (Samples::wall); reach: the body type's bounding radius, m
  bool contacts = false, walls_collide = false, has_wall = false;
  bool floor_clamp = false;  // FluidField::floor_clamp
  bool ground_collide = false;  // Model::ground_collides
  double reach = 0;
};

inline void set_field_consts(const Model& model, const BodyType& type, FieldConsts* fc) {
  const EffectSet& e = type.effects;
  fc->h = model.dt;
  fc->turb = e.has(Effect::Turbulence);
  fc->tu = fc->turb ? 1.0 : 0.0;
  fc->sample = type.plan.sample_field;
  fc->mf = e.has(Effect::MeanFlow) ? 1.0 : 0.0;
  fc->wm = model.well_mixed_correction ? 1.0 : 0.0;
  fc->gu = type.plan.gradients ? 1.0 : 0.0;
  fc->vd2 = type.drift_speed * type.drift_speed;
  for (int a = 0; a < 3; ++a) fc->cd[a] = type.drift_dir[a];
  fc->grid = !model.field.is_uniform();
  fc->mean_flow_scale = model.mean_flow_scale;
  fc->turbulence_scale = model.turbulence_scale;
  // the buoyancy alone too: with an offset centre of mass it turns the body (explicit_torque)
  const Vec3 F_buoy = e.has(Effect::Buoyancy)
                          ? Vec3(-model.fluid_density * type.volume * model.gravity)
                          : Vec3::Zero();
  Vec3 F = Vec3::Zero();
  if (e.has(Effect::Gravity)) F += type.mass * model.gravity;
  if (e.has(Effect::Buoyancy)) F += F_buoy;
  for (int a = 0; a < 3; ++a) fc->F[a] = F[a];
  fc->basset = type.plan.basset;
  fc->basset_mass = fc->basset ? type.basset.implicit_mass : 0.0;
  fc->magnus = e.has(Effect::Magnus) ? type.plan.params->magnus : 0.0;
  for (int a = 0; a < 3; ++a) {
    fc->r_cob[a] = type.r_cob[a];
    fc->F_buoy[a] = F_buoy[a];
  }
  if (fc->grid) {
    const GridGeometry& g = model.field.geometry();
    for (int a = 0; a < 3; ++a) {
      fc->origin[a] = g.origin[a];
      fc->spacing[a] = g.spacing[a];
      fc->points[a] = g.n[a];
      fc->upper_index[a] = double(g.n[a] - 1);
    }
    fc->sy = g.n[0];
    fc->sz = int64_t(g.n[0]) * g.n[1];
    fc->records = model.field.frame_records(0);
  } else {
    model.field.sample(Vec3::Zero(), 0.0, false, &fc->uniform);
    apply_art_scales(model, &fc->uniform);
  }
  fc->ground = model.has_ground;
  fc->ground_z = model.ground_z;
  fc->contacts = model.contacts();
  fc->walls_collide = model.walls_collide();
  fc->ground_collide = model.ground_collides();
  fc->has_wall = fc->grid && model.field.has_wall_distance();
  fc->floor_clamp = fc->grid && model.field.floor_clamp();
  fc->reach = type.reach;
  for (int a = 0; a < 3; ++a) fc->half[a] = type.half_extents[a];
  fc->round = is_round(type);
  fc->seed = model.seed;
}

// What rules out the batched steps for every body type: the integrator (euler and rk4 only where
// explicit_schemes; the batched step runs them, rigid_batch_explicit.h, and passes true), the turbulence model, the noise, the field. Empty when none does.
inline std::string batch_exclusion(const Model& model, const BodyType& type,
                                   bool explicit_schemes) {
  if (!model.batched) return "the scene turns the batched step off";
  const bool split =
      model.integrator == Integrator::Splitting || model.integrator == Integrator::Strang;
  if (!split && !explicit_schemes) return "the integrator is not splitting or strang";
  if (type.effects.has(Effect::Turbulence) && model.turbulence_model != TurbulenceModel::Seen)
    return "the body turbulence model";
  if (model.noise_substeps > 1) return "noise substeps";
  // the registry (effects/registry.cpp) says which effects the loops implement
  if (const EffectInfo* e = first_unbatched(type.effects))
    return std::string("effect ") + e->name + " has no batched kernel";
  // the steps address grid records with 32-bit float offsets
  if (!model.field.is_uniform() && model.field.geometry().points() >= (size_t(1) << 28))
    return "a grid of 2^28 points or more";
  return "";
}

// The lanes of one 512-bit vector: the step's loops run over a whole number of them, so that
// every build's vector loop (2, 4 or 8 doubles; 4, 8 or 16 floats) covers them without a
// remainder and a lane's arithmetic does not depend on how many lanes the loop runs over.
template <typename T>
constexpr int kLaneGrain = 64 / int(sizeof(T));

// The fluid sample at a block's positions, structure of arrays, and the block's bookkeeping.
template <typename T>
struct Samples {
  alignas(64) T x[3][kBatch];  // positions, m (the state of every kind of lane starts with it)
  alignas(64) T U[3][kBatch];
  alignas(64) T alpha[kBatch];
  alignas(64) T beta[kBatch];
  alignas(64) T sigma2[kBatch];
  alignas(64) T gs[3][kBatch];   // grad sigma2
  alignas(64) T acc[3][kBatch];  // dU/dt + (grad U) U: the mean flow's acceleration, m/s^2
  alignas(64) T gU[9][kBatch];   // grad U, dU_p/dx_a at p * 3 + a, 1/s (0 without gradients)
  alignas(64) T inside[kBatch];  // 1 in the fluid, 0 outside
  // the wall distance at the sample where all 8 corners are valid (m), -1 where some is not (a
  // wall within a cell), +infinity outside the grid's box or without the array: the batched
  // steps' one comparison with the body's reach (contact/pass.h)
  alignas(64) T wall[kBatch];
  // the exact OU half step's coefficients at the sample (ou_exact): a steady field gives the
  // second half step of one step and the first of the next the same ones
  alignas(64) T decay[kBatch];  // exp(-alpha h/2)
  alignas(64) T noise[kBatch];  // beta sqrt((1 - exp(-alpha h)) / (2 alpha)), m/s
  // along the type's drift (crossing trajectories: alpha b and beta sqrt(b) in place of alpha
  // and beta); decay and noise above are then across it. Without a drift, the same values
  alignas(64) T decay_a[kBatch];
  alignas(64) T noise_a[kBatch];
  // Basset: the history force of the past intervals, world frame, N (basset_history_force), and
  // where each lane's history lives in the State
  alignas(64) T fb[3][kBatch];
  alignas(64) T gb[3][kBatch];  // u_f - V at the end of the step (end_step), m/s
  double* history[kBatch];
  // the field's frames at the time of the next sample (a time-dependent field: set by the driver
  // before each step, FluidField::frames_at; frames.a == nullptr: FieldConsts::records)
  FluidField::FrameBlend frames;
  uint32_t body[kBatch];
  bool live[kBatch];
  // a touchdown located inside the step (contact/events.h locate_touchdown): the lanes whose landing or
  // first ground contact is still to come (track), and the start of the step of those whose
  // step reached the ground (end_step keeps it)
  bool track[kBatch];
  BodyState start[kBatch];
  // contacts: the lanes whose body was flying at the start of the step (an impact on a surface
  // is located inside the step: contact_after_step's start), and, for the lanes whose step
  // succeeded, whether start[] holds the start of the step just taken
  bool flying[kBatch];
  bool started[kBatch];
  uint64_t newton = 0;  // steps of live lanes on which the loops ran Newton (BlockStats)
  // the lanes [0, width) a step computes: the live ones rounded up to whole vectors (kLaneGrain;
  // set by drive_block before each step). A block whose bodies have landed, fallen asleep or
  // never filled it steps only as many vectors as its last live lane needs: lanes past width
  // keep their state and are neither stepped nor committed.
  int width = kBatch;
};

// Whether lanes of type L keep the world velocity (L::kWorld), which a store and a load round
template <class L, class = void>
struct KeepsWorldVelocity : std::false_type {};
template <class L>
struct KeepsWorldVelocity<L, std::void_t<decltype(L::kWorld)>> : std::bool_constant<L::kWorld> {};

// The width (Samples::width) that covers lanes [0, hi)
template <typename T>
constexpr int lane_width(int hi) {
  return (hi + kLaneGrain<T> - 1) / kLaneGrain<T> * kLaneGrain<T>;
}

// Fills the sample arrays of lanes at positions x (may be lanes.x itself), lanes [lo, hi).
template <typename T>
LRIGID_MULTIVERSION void sample_lanes(const FieldConsts& fc, const T (*x)[kBatch],
                                      Samples<T>* lanes, int lo = 0, int hi = kBatch) {
  if (!fc.grid) {
    const FluidSample& u = fc.uniform;
LRIGID_IVDEP
    for (int j = lo; j < hi; ++j) {
#pragma GCC unroll 3
      for (int a = 0; a < 3; ++a) {
        lanes->U[a][j] = T(u.U[a]);
        lanes->gs[a][j] = T(0);
        lanes->acc[a][j] = T(0);
      }
#pragma GCC unroll 9
      for (int e = 0; e < 9; ++e) lanes->gU[e][j] = T(0);
      lanes->alpha[j] = T(u.alpha);
      lanes->beta[j] = T(u.beta);
      lanes->sigma2[j] = T(u.sigma2);
      const bool fin = std::isfinite(x[0][j]) && std::isfinite(x[1][j]) && std::isfinite(x[2][j]);
      lanes->inside[j] = fin ? T(1) : T(0);
      lanes->wall[j] = T(HUGE_VAL);
    }
    return;
  }
  // a time-dependent field: the blend of two frames at the sample's time, as FluidField::sample
  // (the frames share the valid points and the wall distance: the mesh does not move)
  const float* rec = lanes->frames.a ? lanes->frames.a : fc.records;
  const float* rec_b = lanes->frames.b;
  const T lam = T(lanes->frames.lam), rate = T(lanes->frames.inv_dt);
  // 32-bit float offsets of the 8 corners' records (batch_exclusion bounds the grid)
  const int sy = int(fc.sy), sz = int(fc.sz);
  const int off[8] = {
      0, 8, 8 * sy, 8 * (1 + sy), 8 * sz, 8 * (1 + sz), 8 * (sy + sz), 8 * (1 + sy + sz)};
  const T mfs = T(fc.mean_flow_scale), ts = T(fc.turbulence_scale), ts2 = ts * ts;
  // One lane at a time, the trilinear record kernel (fluid/trilinear.h, the scalar step's too):
  // the sums of the weights times the corners' records (slot 6: the valid weight W) and of the
  // weights' derivatives times them (the gradients).
  typedef typename Record8<T>::type V8;
  alignas(64) T val[8][kBatch], grad[3][8][kBatch], allv[kBatch], frac[3][kBatch];
  alignas(64) T dudt[3][kBatch];  // the weighted sums' rate of change in time (slots 0-2), 1/s
  alignas(64) int base[kBatch], inbox[kBatch];
  // the cells first (across lanes), so that their records can be fetched ahead
LRIGID_IVDEP
  for (int j = lo; j < hi; ++j) {
    int idx = 0, in = 1;
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      T s = (x[a][j] - T(fc.origin[a])) / T(fc.spacing[a]);
      // within a cell below the bottom face: the bottom layer (FluidField::set_floor_clamp)
      s = ((a == 2) & fc.floor_clamp & (s < T(0)) & (s >= T(-1))) ? T(0) : s;
      in &= int(s >= T(0)) & int(s <= T(fc.upper_index[a]));
      // clamped so that every lane reads inside the grid, also lanes outside it
      s = s > T(0) ? s : T(0);
      s = s < T(fc.upper_index[a]) ? s : T(fc.upper_index[a]);
      int i = static_cast<int>(s);
      i = i < fc.points[a] - 2 ? i : fc.points[a] - 2;
      frac[a][j] = s - T(i);
      idx += 8 * (a == 0 ? 1 : (a == 1 ? sy : sz)) * i;
    }
    base[j] = idx;
    inbox[j] = in;
  }
  // the grid is larger than the caches: the 4 pairs of corner records of a lane a few lanes
  // ahead are prefetched (each pair is 64 bytes, which may straddle two cache lines)
  constexpr int kAhead = 6;
  // the gather, once per kind of field (a branch on the series inside it doubled the loop's
  // instructions on a steady grid: GCC kept the records in memory across the two paths)
  auto gather = [&](auto blend) {
    constexpr bool kBlend = decltype(blend)::value;
    auto prefetch = [&](int j) {
#pragma GCC unroll 4
      for (int c = 0; c < 8; c += 2) {
        const float* r = rec + base[j] + off[c];
        __builtin_prefetch(r);
        __builtin_prefetch(r + 15);
        if constexpr (kBlend) {
          const float* rb = rec_b + base[j] + off[c];
          __builtin_prefetch(rb);
          __builtin_prefetch(rb + 15);
        }
      }
    };
    for (int j = lo; j < hi && j < lo + kAhead; ++j) prefetch(j);
    for (int j = lo; j < hi; ++j) {
      if (j + kAhead < hi) prefetch(j + kAhead);
      const T f[3] = {frac[0][j], frac[1][j], frac[2][j]};
      const int idx = base[j];
      bool in = inbox[j] != 0;
      V8 v, d0, d1, d2;
      int nvalid;
      if constexpr (kBlend) {
        V8 dv;
        nvalid = trilinear_record<T, true, true>(rec + idx, off, f, &v, &d0, &d1, &d2,
                                                 rec_b + idx, lam, &dv);
#pragma GCC unroll 3
        for (int p = 0; p < 3; ++p) dudt[p][j] = dv[p] * rate;
      } else {
        nvalid = trilinear_record<T, true>(rec + idx, off, f, &v, &d0, &d1, &d2);
#pragma GCC unroll 3
        for (int p = 0; p < 3; ++p) dudt[p][j] = T(0);
      }
      // slot 6 of v: the weight W of the valid corners
      // (colliding walls: any valid corner, as FluidField::sample_frame)
      in = in & (nvalid > 0) & ((v[6] >= T(0.5)) | fc.walls_collide);
      allv[j] = nvalid == 8 ? T(1) : T(0);
      lanes->inside[j] = in ? T(1) : T(0);
      // slot 7: the valid-weighted wall distance, the plain blend where all corners are valid
      lanes->wall[j] =
          (!fc.has_wall || inbox[j] == 0) ? T(HUGE_VAL) : (nvalid == 8 ? v[7] : T(-1));
#pragma GCC unroll 8
      for (int p = 0; p < 8; ++p) {
        val[p][j] = v[p];
        grad[0][p][j] = d0[p];
        grad[1][p][j] = d1[p];
        grad[2][p][j] = d2[p];
      }
    }
  };
  if (rec_b)
    gather(std::true_type{});
  else
    gather(std::false_type{});
LRIGID_IVDEP
  for (int j = lo; j < hi; ++j) {
    const T W = val[6][j];
    const T inv = T(1) / (W > T(0) ? W : T(1));
    // gradients only where all 8 corners are valid (as FluidField::sample)
    const T all = allv[j];
    T gu[3][3];
#pragma GCC unroll 3
    for (int p = 0; p < 3; ++p) {
      lanes->U[p][j] = mfs * val[p][j] * inv;
#pragma GCC unroll 3
      for (int a = 0; a < 3; ++a) {
        gu[p][a] = mfs * all * grad[a][p][j] / T(fc.spacing[a]);
        lanes->gU[p * 3 + a][j] = gu[p][a];
      }
    }
    lanes->alpha[j] = val[3][j] * inv;
    lanes->beta[j] = ts * val[4][j] * inv;
    lanes->sigma2[j] = ts2 * val[5][j] * inv;
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      lanes->gs[a][j] = ts2 * all * grad[a][5][j] / T(fc.spacing[a]);
      // DU/Dt = dU/dt + (grad U) U (effects/mean_flow.h)
      lanes->acc[a][j] = mfs * dudt[a][j] * inv + gu[a][0] * lanes->U[0][j] +
                         gu[a][1] * lanes->U[1][j] + gu[a][2] * lanes->U[2][j];
    }
  }
}

// The OU half step's decay and noise at the lanes' samples, across and along the type's drift
// (effects/turbulence.h ou_crossing_exact_kernel).
template <typename T>
LRIGID_MULTIVERSION void ou_coefficients(const FieldConsts& fc, Samples<T>* lanes, int lo = 0,
                                         int hi = kBatch) {
  const double hh = 0.5 * fc.h, vd2 = fc.vd2;
  if (vd2 > 0) {
LRIGID_IVDEP
    for (int j = lo; j < hi; ++j) {
      double decay, noise, decay_a, noise_a;
      ou_crossing_exact_kernel(double(lanes->alpha[j]), double(lanes->beta[j]),
                               double(lanes->sigma2[j]), vd2, hh, &decay, &noise, &decay_a,
                               &noise_a);
      lanes->decay[j] = T(decay);
      lanes->noise[j] = T(noise);
      lanes->decay_a[j] = T(decay_a);
      lanes->noise_a[j] = T(noise_a);
    }
    return;
  }
  // no drift (tracers, or the correction off): one pair for every axis, computed once
LRIGID_IVDEP
  for (int j = lo; j < hi; ++j) {
    double decay, noise;
    ou_exact_kernel(double(lanes->alpha[j]), double(lanes->beta[j]), hh, &decay, &noise);
    lanes->decay[j] = lanes->decay_a[j] = T(decay);
    lanes->noise[j] = lanes->noise_a[j] = T(noise);
  }
}

// Normals of step `step` for every lane: the Strang half-step increments of the linear noise,
// exactly as brownian_increments (integrators.cpp) draws them from NormalStream; Whole: the whole
// step's increment in z1 (euler, rk4), z2 unused.
template <typename T, bool Whole = false>
LRIGID_MULTIVERSION void lane_normals(const FieldConsts& fc, const Samples<T>& lanes, uint64_t step,
                                      T (*z1)[kBatch], T (*z2)[kBatch]) {
  const int nw = lanes.width;
  if (!fc.turb) {
    // no seen turbulence: no draw (the OU updates are the identity, lane_ou_half)
    for (int c = 0; c < 3; ++c)
      for (int j = 0; j < nw; ++j) z1[c][j] = z2[c][j] = T(0);
    return;
  }
  // words: block 0 (pairs 0, 1), block 1 words 2, 3 (pair 3), block 2 words 0, 1 (pair 4)
  alignas(64) uint32_t wd[8][kBatch];
  const uint32_t k0 = static_cast<uint32_t>(fc.seed), k1 = static_cast<uint32_t>(fc.seed >> 32);
  const uint32_t lo = static_cast<uint32_t>(step), hi = static_cast<uint32_t>(step >> 32);
LRIGID_IVDEP
  for (int j = 0; j < nw; ++j) {
    const uint32_t body = lanes.body[j];
    uint32_t b0[4] = {body, lo, hi, 0x6c720000u};
    uint32_t b1[4] = {body, lo, hi, 0x6c720001u};
    uint32_t b2[4] = {body, lo, hi, 0x6c720002u};
    philox4x32_10(b0[0], b0[1], b0[2], b0[3], k0, k1);
    philox4x32_10(b1[0], b1[1], b1[2], b1[3], k0, k1);
    philox4x32_10(b2[0], b2[1], b2[2], b2[3], k0, k1);
    wd[0][j] = b0[0], wd[1][j] = b0[1], wd[2][j] = b0[2], wd[3][j] = b0[3];
    wd[4][j] = b1[2], wd[5][j] = b1[3], wd[6][j] = b2[0], wd[7][j] = b2[1];
  }
LRIGID_IVDEP
  for (int j = 0; j < nw; ++j) {
    double c0, s0, c1, s1, c3, s3, c4, s4;
    sincos_of_turn(wd[1][j], &c0, &s0);
    sincos_of_turn(wd[3][j], &c1, &s1);
    sincos_of_turn(wd[5][j], &c3, &s3);
    sincos_of_turn(wd[7][j], &c4, &s4);
    const double r0 = NormalStream::box_muller_radius(wd[0][j]);
    const double r1 = NormalStream::box_muller_radius(wd[2][j]);
    const double r3 = NormalStream::box_muller_radius(wd[4][j]);
    const double r4 = NormalStream::box_muller_radius(wd[6][j]);
    const double a[3] = {r0 * c0, r0 * s0, r1 * c1};  // n[0..2]
    const double b[3] = {r3 * c3, r3 * s3, r4 * c4};  // n[6..8]
#pragma GCC unroll 3
    for (int c = 0; c < 3; ++c) {
      z1[c][j] = Whole ? T(a[c]) : T((a[c] + b[c]) * M_SQRT1_2);
      z2[c][j] = Whole ? T(0) : T((a[c] - b[c]) * M_SQRT1_2);
    }
  }
}

// A lane's outcome after one step. kScalar: the lane needs what the batched loops leave to the
// scalar step (e.g. a Newton iteration), which then redoes it; kNonFinite + i names the first
// non-finite part of the new state.
enum Outcome : uint8_t { kOk = 0, kOutside = 1, kScalar = 2, kNonFinite = 3 };
const char* const kNonFiniteName[5] = {"position", "orientation", "velocity", "angular velocity",
                                       "seen turbulent velocity"};

// Bits of what went right in a lane's step (bit i clear: part i of the new state is non-finite,
// in step_body's order; bit 5: inside the fluid; bit 6 set: take the scalar step), from the
// loop across lanes, where branches would stop it vectorizing.
template <typename T>
LRIGID_LANE int outcome_bits(const T* x, const T* q, const T* v, const T* w, const T* us,
                             bool inside, bool scalar) {
  // int & int: every condition evaluated, no branch (bool && would short-circuit)
  auto fin = [](T a) { return int(std::isfinite(a)); };
  const int fx = fin(x[0]) & fin(x[1]) & fin(x[2]);
  const int fq = fin(q[0]) & fin(q[1]) & fin(q[2]) & fin(q[3]);
  const int fv = fin(v[0]) & fin(v[1]) & fin(v[2]);
  const int fw = fin(w[0]) & fin(w[1]) & fin(w[2]);
  const int fu = fin(us[0]) & fin(us[1]) & fin(us[2]);
  return fx | fq << 1 | fv << 2 | fw << 3 | fu << 4 | int(inside) << 5 | int(scalar) << 6;
}

inline int decode_outcome(int bits) {
  if (bits >> 6 & 1) return kScalar;
  // a non-finite state fails before it is outside (a NaN position samples as outside the grid),
  // as step_body checks it
  int bad = 0;  // the first non-finite part, in the order step_body names them
  while (bad < 5 && (bits >> bad & 1)) ++bad;
  if (bad < 5) return int(kNonFinite) + bad;
  return !(bits >> 5 & 1) ? int(kOutside) : int(kOk);
}

// The body's lowest point is on or below the ground (contact/events.h touches_ground) for quaternion q
// (w, x, y, z) at height z.
template <typename T>
LRIGID_LANE int lane_landed(const FieldConsts& fc, const T* q, T z) {
  const T qw = q[0], qx = q[1], qy = q[2], qz = q[3];
  const T r[3] = {T(2) * (qx * qz - qw * qy), T(2) * (qy * qz + qw * qx),
                  T(1) - T(2) * (qx * qx + qy * qy)};
  const T h[3] = {T(fc.half[0]), T(fc.half[1]), T(fc.half[2])};
  const T c[3] = {T(fc.r_cob[0]), T(fc.r_cob[1]), T(fc.r_cob[2])};
  return int(fc.ground & (z - ground_reach(fc.round, r, h, c) <= T(fc.ground_z)));
}

// The exact OU half step (effects/turbulence.h ou_update, Thomson's drift along the world
// velocity V) of lane j's seen fluctuation us, with normals z (3 x kBatch) and the lanes'
// coefficients at their samples (lane_ou_update: with any decay and noise, as euler's and rk4's
// Euler-Maruyama update takes), across and along the drift direction cd (world, unit; zero
// without a drift: effects/turbulence.h ou_update_crossing). tu: the seen turbulence's factor,
// 1 or 0; with 0 the update is the identity (decay 1, no noise, no drift), exactly. (A factor,
// not a select on a flag: GCC does not vectorize a loop that selects on a bool.)
template <typename T>
LRIGID_LANE void lane_ou_update(T tu, T wm, T decay, T noise, T decay_a, T noise_a, const T* cd,
                                T h, const Samples<T>& lanes, const T (*z)[kBatch], int j,
                                const T* V, T* us) {
  const T gs[3] = {lanes.gs[0][j], lanes.gs[1][j], lanes.gs[2][j]};
  const T zj[3] = {z[0][j], z[1][j], z[2][j]};
  const T off = T(1) - tu;
  ou_update_crossing(wm * tu, decay * tu + off, noise * tu, decay_a * tu + off, noise_a * tu, cd,
                     lanes.sigma2[j], V, gs, zj, h, us);
}
template <typename T>
LRIGID_LANE void lane_ou_half(T tu, T wm, T hh, const T* cd, const Samples<T>& lanes,
                              const T (*z)[kBatch], int j, const T* V, T* us) {
  lane_ou_update(tu, wm, lanes.decay[j], lanes.noise[j], lanes.decay_a[j], lanes.noise_a[j], cd,
                 hh, lanes, z, j, V, us);
}

// A step's new state per lane, filled by a batched step before end_step: position,
// orientation, the velocity the lane keeps (Lanes::velocity: world V for spheres, body-frame v
// for plates), spin, and the seen fluctuation after the first OU half step; scalar: 1 for lanes
// that hand their step to the scalar step.
template <typename T>
struct NewState {
  alignas(64) T x[3][kBatch];
  alignas(64) T q[4][kBatch];
  alignas(64) T vel[3][kBatch];
  alignas(64) T w[3][kBatch];
  alignas(64) T us[3][kBatch];
  int scalar[kBatch];
};

// The end of every batched step: the field sampled at the new positions, the second OU half step
// (normals z2) along the world velocity V at the end of the step, each lane's outcome and
// landing, and the commit into `lanes` of the lanes whose step succeeded (the others keep the state
// at the start of the step). sampled_inside0: the step has already sampled the field at the new
// positions (strang), and this is each lane's inside flag at the start of the step. OUHalfStep
// false: no OU half step here (euler and rk4 update the seen fluctuation within the step). Inlined
// into each version of the step (as target_clones of its own it halved the step's speed on the
// beads scene: 9.5 against 14.5 M body-steps/s per core).
template <typename T, bool OUHalfStep = true, class Lanes>
LRIGID_LANE void end_step(const FieldConsts& fc, const T (*z2)[kBatch], const T (*V)[kBatch],
                          NewState<T>* next, Lanes* lanes, int* outcome, int* landed,
                          const T* sampled_inside0 = nullptr) {
  const int nw = lanes->width;
  const T hh = T(0.5 * fc.h), wm = T(fc.wm);
  const T cd[3] = {T(fc.cd[0]), T(fc.cd[1]), T(fc.cd[2])};
  alignas(64) T inside0[kBatch];
  if (sampled_inside0) {
    for (int j = 0; j < nw; ++j) inside0[j] = sampled_inside0[j];
  } else {
    for (int j = 0; j < nw; ++j) inside0[j] = fc.sample ? lanes->inside[j] : T(1);
    if (fc.sample) sample_lanes(fc, next->x, lanes, 0, nw);
  }
  const bool turb = fc.turb;
  const T tu = T(fc.tu);
  if (turb && OUHalfStep) ou_coefficients(fc, lanes, 0, nw);
  const bool sample = fc.sample;
LRIGID_IVDEP
  for (int j = 0; j < nw; ++j) {
    T us[3] = {next->us[0][j], next->us[1][j], next->us[2][j]};
    if constexpr (OUHalfStep) {
      const T Vj[3] = {V[0][j], V[1][j], V[2][j]};
      lane_ou_half(tu, wm, hh, cd, *lanes, z2, j, Vj, us);
    }
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) next->us[a][j] = us[a];
    // & rather than && on the lanes' conditions: no branches in the loop
    const bool in = (inside0[j] != T(0)) & (!sample | (lanes->inside[j] != T(0)));
    const T x[3] = {next->x[0][j], next->x[1][j], next->x[2][j]};
    const T v[3] = {next->vel[0][j], next->vel[1][j], next->vel[2][j]};
    const T w[3] = {next->w[0][j], next->w[1][j], next->w[2][j]};
    const T q[4] = {next->q[0][j], next->q[1][j], next->q[2][j], next->q[3][j]};
    outcome[j] = outcome_bits(x, q, v, w, us, in, next->scalar[j] != 0);
    landed[j] = lane_landed(fc, q, x[2]);
  }
  for (int j = 0; j < nw; ++j) outcome[j] = decode_outcome(outcome[j]);
  if (fc.basset) {
    // what the Basset history takes in: the relative velocity at the end of the step
    const T mf = T(fc.mf);
LRIGID_IVDEP
    for (int j = 0; j < nw; ++j)
#pragma GCC unroll 3
      for (int a = 0; a < 3; ++a)
        lanes->gb[a][j] = mf * lanes->U[a][j] + tu * next->us[a][j] - V[a][j];
  }
  T(*vel)[kBatch] = lanes->velocity();
  const bool contacts = fc.contacts;
  for (int j = 0; j < nw; ++j) {
    if (outcome[j] != kOk || !lanes->live[j]) continue;
    // the start of the step of a lane that may have met a surface in it: a landing or first
    // touchdown to locate, or a flying body near a colliding surface (an impact to locate)
    bool keep = landed[j] && lanes->track[j];
    if (contacts && lanes->flying[j])
      keep = keep || (landed[j] && fc.ground_collide) ||
             (fc.walls_collide && double(lanes->wall[j]) <= fc.reach);
    if (keep) lanes->store(j, &lanes->start[j]);
    lanes->started[j] = keep;
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      lanes->x[a][j] = next->x[a][j];
      vel[a][j] = next->vel[a][j];
      lanes->w[a][j] = next->w[a][j];
      lanes->us[a][j] = next->us[a][j];
    }
#pragma GCC unroll 4
    for (int a = 0; a < 4; ++a) lanes->q[a][j] = next->q[a][j];
  }
}

// Calls f with std::bool_constant<a> (inlined: a multiversioned loop keeps its version).
template <class F>
LRIGID_LANE void with_switch(bool a, F f) {
  if (a)
    f(std::true_type{});
  else
    f(std::false_type{});
}

// Runs a block of count bodies (indices body[0..count)) of one type through steps [first, last)
// with the scalar loop's statuses, stop times and reasons. Lanes (derived from Samples<T>) holds
// the block's state and provides load(j, BodyState), store(j, BodyState*), rest(j) (set at rest
// after landing) and velocity(); step(A, &lanes, step, outcome, landed), called with
// std::bool_constant<a> (the step's one template switch: the plates' kernels, or none for
// spheres), advances every lane by one step, keeping the start state of lanes that are
// not kOk, and leaves the samples at the new positions (end_step). The Basset history is the
// driver's: it sets each lane's history force before the step (Samples::fb) and appends the step
// to the history of the lanes that took it (as step_body does at its end).
// sweep: null, or the stretch's record of each body's motion (sweep.h; Lanes then also provides
// velocity(), w, the spin, and q, the orientation (w, x, y, z)): each lane's pose and speeds after
// each of its steps, where it falls asleep or stops, and its steps. With a sweep the block also
// takes, between two of its steps, what a store and a load do to a lane (for an isotropic M the
// world velocity turned into the body frame and back), so that its steps are those of stretches of
// one step each: the lockstep of contacts between bodies (simulation.cpp).
template <typename T, class Lanes, class Step>
BlockStats drive_block(const Model& model, const BodyType& type, const FieldConsts& fc, bool a,
                       State* state, const uint32_t* body, int count, uint64_t first, uint64_t last,
                       Step step, StretchSweep* sweep = nullptr) {
  BlockStats stats;
  State& st = *state;
  Lanes block{};  // zeroed: without a field to sample, the sample arrays stay the fluid at rest
  Lanes* lanes = &block;
  uint64_t dormant[kBatch];  // the step a sleeping lane wakes at (GustWatch::kNever: none)
  for (int j = 0; j < kBatch; ++j) {
    // lanes past count repeat the first body and stay idle
    const size_t i = body[j < count ? j : 0];
    lanes->load(j, load_body(st, i));
    lanes->body[j] = static_cast<uint32_t>(i);
    lanes->live[j] = j < count && st.status[i] == BodyStatus::Moving;
    // a sleeping body its gust watch wakes in this stretch: a dormant lane until then
    dormant[j] = j < count && wakes_before(st, i, last) ? st.watch[i].wake : GustWatch::kNever;
    lanes->history[j] = st.history_of(i);
    lanes->track[j] = fc.ground && (!fc.ground_collide || std::isnan(st.t_touch[i]));
    lanes->flying[j] = fc.contacts && st.contact[i] == ContactState::Flying;
    lanes->started[j] = false;
  }
  // with a sweep: each lane's steps, handed steps and whether it fell asleep, and over its step
  // ends its centre's least and greatest coordinates and its greatest squared speeds
  uint32_t lane_steps[kBatch] = {}, lane_handed[kBatch] = {};
  bool lane_slept[kBatch] = {};
  alignas(64) T sweep_lo[3][kBatch];
  alignas(64) T sweep_hi[3][kBatch];
  alignas(64) T sweep_v2[kBatch];
  alignas(64) T sweep_w2[kBatch];
  if (sweep) {
    for (int j = 0; j < kBatch; ++j) {
      for (int c = 0; c < 3; ++c) sweep_lo[c][j] = sweep_hi[c][j] = lanes->x[c][j];
      sweep_v2[j] = sweep_w2[j] = T(0);
    }
  }
  auto resample = [&](int lo, int hi) {
    if (fc.sample) sample_lanes(fc, lanes->x, lanes, lo, hi);
    if (fc.turb) ou_coefficients(fc, lanes, lo, hi);
  };
  // a time-dependent field: the frames of each sample's time (the samples at the end of a step
  // are at its end time)
  const bool unsteady = fc.grid && model.field.frame_count() > 1;
  if (unsteady) lanes->frames = model.field.frames_at(static_cast<double>(first) * model.dt);
  resample(0, kBatch);
  alignas(64) int outcome[kBatch];
  alignas(64) int landed[kBatch];
  // one comparison per surface: lane j may touch a colliding ground (its bounding box reaches
  // it: land) or a wall (the sample's wall distance within the body's reach)
  auto near_surface = [&](int j, bool land) {
    return (land & fc.ground_collide) | (fc.walls_collide & (double(lanes->wall[j]) <= fc.reach));
  };
  for (uint64_t s = first; s < last; ++s) {
    bool any = false, sleepers = false;
    int hi = 0;  // past the last live lane
    for (int j = 0; j < count; ++j) {
      if (dormant[j] == s) {
        // its watch wakes it: it takes this step with the u' the watch followed
        BodyState b;
        lanes->store(j, &b);
        b.u_seen = wake_sleeper(&st, lanes->body[j]);
        lanes->load(j, b);
        resample(j, j + 1);
        lanes->live[j] = true;
        dormant[j] = GustWatch::kNever;
      }
      any = any || lanes->live[j];
      hi = lanes->live[j] ? j + 1 : hi;
      sleepers = sleepers || dormant[j] != GustWatch::kNever;
    }
    lanes->width = lane_width<T>(hi);
    if (!any && !sleepers) break;
    const double t = static_cast<double>(s) * model.dt;
    // (the end time as the next stretch's start, first * dt: bitwise the same blend)
    if (unsteady) lanes->frames = model.field.frames_at(static_cast<double>(s + 1) * model.dt);
    if (!any) continue;  // only sleepers, waking later
    if (fc.basset) {
      for (int j = 0; j < lanes->width; ++j) {
        const Vec3 f =
            lanes->history[j] ? basset_history_force(type.basset, lanes->history[j]) : Vec3::Zero();
#pragma GCC unroll 3
        for (int c = 0; c < 3; ++c) lanes->fb[c][j] = T(f[c]);
      }
    }
    with_switch(a, [&](auto A) { step(A, lanes, s, outcome, landed); });
    if (fc.basset) {
      // the relative velocity g = u_f - V at the end of the step enters the history
      for (int j = 0; j < count; ++j) {
        if (!lanes->live[j] || outcome[j] != kOk || !lanes->history[j]) continue;
        const Vec3 g(double(lanes->gb[0][j]), double(lanes->gb[1][j]), double(lanes->gb[2][j]));
        basset_push(type.basset, g, model.dt, lanes->history[j]);
      }
    }
    for (int j = 0; j < count; ++j) {
      if (!lanes->live[j]) continue;
      const size_t i = lanes->body[j];
      bool land = landed[j] != 0;
      bool near = near_surface(j, land);
      if (outcome[j] == kOk && step_end_is_quiet(model, StepOutcome::Ok, near, land)) {
        // most lanes: a step in free flight, nothing to do at its end
        ++stats.body_steps;
        ++lane_steps[j];
        if (fc.contacts) {
          mark_flying(&st, i);
          lanes->flying[j] = true;
        }
        continue;
      }
      // the lane's state: after the step where it succeeded, at its start otherwise
      BodyState b;
      lanes->store(j, &b);
      b.history = lanes->history[j];
      StepOutcome out = StepOutcome::Ok;
      std::string reason;
      bool floor_impact = false, retaken = false;
      if (outcome[j] == kScalar) {
        // what the loops leave to the scalar step: the lane's whole step, taken again there
        lanes->start[j] = b;
        lanes->started[j] = true;
        out = step_body(model, type, lanes->body[j], s, t, &b, &reason);
        retaken = true;
      } else if (outcome[j] != kOk) {
        out = outcome[j] == kOutside ? StepOutcome::Exited : StepOutcome::Failed;
        if (out == StepOutcome::Failed)
          reason = std::string("non-finite ") + kNonFiniteName[outcome[j] - kNonFinite];
      }
      if (out == StepOutcome::Exited && fc.contacts) {
        // heading through the grid's floor into the ground: the impact located inside the
        // step, or the speculative contact and the scalar step
        bool again = false;
        lanes->start[j] = b;
        out = retry_into_ground(model, type, i, s, t, &b, &lanes->start[j], &reason, &st,
                                &floor_impact, &again);
        retaken = retaken || again;
        lanes->started[j] = again && !floor_impact;
      }
      if (retaken) {
        ++stats.scalar_steps;
        ++lane_handed[j];
        if (out == StepOutcome::Ok) {
          // the lane's sample is at its batched position: sample it where the step took it
          lanes->load(j, b);
          resample(j, j + 1);
          land = model.has_ground && touches_ground(model, type, b);
          near = near_surface(j, land);
        }
      }
      if (out == StepOutcome::Ok) {
        ++stats.body_steps;
        ++lane_steps[j];
      }
      const StepEnd end =
          finish_step(model, type, i, t, last, out, reason, near, &land,
                      lanes->started[j] && !floor_impact ? &lanes->start[j] : nullptr, nullptr,
                      &b, &st);
      lanes->track[j] = fc.ground && (!fc.ground_collide || std::isnan(st.t_touch[i]));
      lanes->flying[j] = fc.contacts && st.contact[i] == ContactState::Flying;
      // the contact's impulses and corrections, where a landing put the body, or the state a
      // step taken again stopped in (an exit or a failure of the lanes' own step leaves the lane
      // as it was at the start of the step)
      if (retaken || end.next != AfterStep::Stopped || st.status[i] == BodyStatus::Landed)
        lanes->load(j, b);
      if (end.next == AfterStep::Moving) {
        // the contact moved the body: its sample is taken again where it is now
        if (end.moved) resample(j, j + 1);
        continue;
      }
      lanes->live[j] = false;
      // asleep until its watch wakes it, in this stretch or a later one
      if (end.next == AfterStep::Asleep && end.wake < last) dormant[j] = end.wake;
      if (sweep && end.next == AfterStep::Asleep) {
        // where it sleeps until it wakes
        lane_slept[j] = true;
        sweep->hold(i, s, b);
      }
      if (sweep && end.next == AfterStep::Stopped) sweep->stop(i, s);
      if (st.status[i] == BodyStatus::Landed) lanes->rest(j);
    }
    if (sweep) {
      // the live lanes' squared speeds (the norms of any frame's) and extents, across the block
      const T(*vel)[kBatch] = lanes->velocity();
      alignas(64) T v2[kBatch];
      alignas(64) T w2[kBatch];
      for (int j = 0; j < kBatch; ++j) {
        v2[j] = vel[0][j] * vel[0][j] + vel[1][j] * vel[1][j] + vel[2][j] * vel[2][j];
        w2[j] = lanes->w[0][j] * lanes->w[0][j] + lanes->w[1][j] * lanes->w[1][j] +
                lanes->w[2][j] * lanes->w[2][j];
        const bool l = lanes->live[j];
        for (int c = 0; c < 3; ++c) {
          sweep_lo[c][j] = l ? std::min(sweep_lo[c][j], lanes->x[c][j]) : sweep_lo[c][j];
          sweep_hi[c][j] = l ? std::max(sweep_hi[c][j], lanes->x[c][j]) : sweep_hi[c][j];
        }
        sweep_v2[j] = l ? std::max(sweep_v2[j], v2[j]) : sweep_v2[j];
        sweep_w2[j] = l ? std::max(sweep_w2[j], w2[j]) : sweep_w2[j];
      }
      for (int j = 0; j < count; ++j) {
        if (!lanes->live[j]) continue;
        // the lane's pose as the state would hold it after the step
        StretchSweep::Slot& slot = sweep->at(lanes->body[j], s);
        slot.x = Vec3(double(lanes->x[0][j]), double(lanes->x[1][j]), double(lanes->x[2][j]));
        slot.q = Quat(double(lanes->q[0][j]), double(lanes->q[1][j]), double(lanes->q[2][j]),
                      double(lanes->q[3][j]));
        slot.v2 = double(v2[j]);
        slot.w2 = double(w2[j]);
        // (the store at a stretch's end and the load at the next one's start)
        if constexpr (KeepsWorldVelocity<Lanes>::value) {
          if (s + 1 < last) {
            BodyState b;
            lanes->store(j, &b);
            lanes->load(j, b);
          }
        }
      }
    }
  }
  for (int j = 0; j < count; ++j) {
    BodyState b;
    lanes->store(j, &b);
    store_body(b, body[j], &st);
    if (!sweep) continue;
    const size_t i = body[j];
    sweep->extend(i, Vec3(double(sweep_lo[0][j]), double(sweep_lo[1][j]), double(sweep_lo[2][j])),
                  Vec3(double(sweep_hi[0][j]), double(sweep_hi[1][j]), double(sweep_hi[2][j])),
                  double(sweep_v2[j]), double(sweep_w2[j]));
    sweep->steps[i] += lane_steps[j];
    sweep->handoffs[i] += lane_handed[j];
    sweep->slept[i] |= uint8_t(lane_slept[j]);
  }
  stats.newton_steps = lanes->newton;
  return stats;
}

}  // namespace
}  // namespace lrigid
