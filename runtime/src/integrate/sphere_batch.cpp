#include "integrate/sphere_batch.h"

#include <algorithm>
#include <cmath>

#include "effects/drag.h"
#include "integrate/dynamics.h"
#include "integrate/stops.h"
#include "util/fast_math.h"
#include "util/rng.h"

namespace lrigid {

bool sphere_batch_eligible(const Model& model, const BodyType& type, std::string* why) {
  auto no = [why](const std::string& reason) {
    if (why) *why = reason;
    return false;
  };
  if (!model.batched) return no("the scene turns the batched step off");
  if (model.integrator != Integrator::Splitting) return no("the integrator is not splitting");
  if (type.shape.type != ShapeType::Sphere) return no("not a sphere");
  if (!type.M_isotropic || !type.r_cob.isZero(0.0))
    return no("the centre of mass is off the centroid");
  for (const EffectInfo& info : all_effects()) {
    const Effect e = info.effect;
    if (!type.effects.has(e)) continue;
    if (e != Effect::Gravity && e != Effect::Buoyancy && e != Effect::Drag &&
        e != Effect::AddedMass && e != Effect::MeanFlow && e != Effect::Turbulence)
      return no(std::string("effect ") + info.name);
  }
  if (type.effects.has(Effect::Turbulence) && model.turbulence_model != TurbulenceModel::Seen)
    return no("the body turbulence model");
  if (model.noise_substeps > 1) return no("noise substeps");
  if (model.field.is_streamed() || model.field.frame_count() > 1)
    return no("a time-dependent field");
  // the step addresses grid records with 32-bit float offsets
  if (!model.field.is_uniform() && model.field.geometry().points() >= (size_t(1) << 28))
    return no("a grid of 2^28 points or more");
  return true;
}

namespace {

// The loops across bodies are compiled for AVX-512, AVX2 and the baseline, and the best the CPU
// has is chosen when the program loads (GCC's function multiversioning; 3.6 against 14.8 M
// body-steps/s per core for the baseline and AVX-512 on this machine). Rounding can differ
// between the versions (fused multiply-adds), never between threads. Clang 14 does not multiversion
// templates: its builds (the fuzz targets) run the baseline.
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
#define LRIGID_LANE inline __attribute__((always_inline))
#if defined(__GNUC__) && !defined(__clang__)
#define LRIGID_IVDEP _Pragma("GCC ivdep")
#else
// Clang: no hint. Its 'vectorize(assume_safety)' is an order that fails the build (-Werror) where
// it cannot vectorize, as in the sanitizer builds of the fuzz targets, which are not for speed.
#define LRIGID_IVDEP
#endif

// What the step needs of the model and the body type, in the world frame.
struct Consts {
  double h = 0;
  bool turb = false, drag = false;  // the step's two template switches
  // switches as factors 1 or 0, so the loops across bodies stay free of branches: mean flow,
  // Thomson's drift, grad U for the fluid acceleration (added mass in a mean flow)
  double mf = 0, wm = 0, gu = 0;
  bool sample = false;  // the field is sampled at all
  bool grid = false;
  double m = 0, ma = 0, J = 0;  // M's linear and angular diagonal; K's linear diagonal (0 without)
  double F[3] = {0, 0, 0};      // gravity and buoyancy, world frame, N
  // sphere drag (effects/drag.cpp drag_wrench with r_cob = 0)
  double rho = 0, nu = 0, a_perp = 0, d_perp = 0, edge = 0, c_ang0 = 0, rot[3] = {0, 0, 0};
  double rot_max = 0;
  double mean_flow_scale = 1, turbulence_scale = 1;
  // grid
  double origin[3] = {0, 0, 0}, spacing[3] = {1, 1, 1}, upper_index[3] = {0, 0, 0};
  int n[3] = {0, 0, 0};
  int64_t sy = 0, sz = 0;
  const float* records = nullptr;
  FluidSample uniform;  // art scales applied
  bool ground = false;
  double ground_z = 0, half[3] = {0, 0, 0};
  uint64_t seed = 0;
};

Consts make_consts(const Model& model, const BodyType& type) {
  Consts k;
  const EffectSet& e = type.effects;
  k.h = model.dt;
  k.turb = e.has(Effect::Turbulence);
  k.drag = e.has(Effect::Drag);
  k.sample = type.plan.sample_field;
  k.mf = e.has(Effect::MeanFlow) ? 1.0 : 0.0;
  k.wm = model.well_mixed_correction ? 1.0 : 0.0;
  k.gu = type.plan.gradients ? 1.0 : 0.0;
  k.grid = !model.field.is_uniform();
  k.m = type.M(0, 0);
  k.ma = e.has(Effect::AddedMass) ? type.K_fluid(0, 0) : 0.0;
  k.J = type.M(3, 3);
  Vec3 F = Vec3::Zero();
  if (e.has(Effect::Gravity)) F += type.mass * model.gravity;
  if (e.has(Effect::Buoyancy)) F -= model.fluid_density * type.volume * model.gravity;
  for (int a = 0; a < 3; ++a) k.F[a] = F[a];
  k.rho = model.fluid_density;
  k.nu = model.nu;
  const double r = type.ell.x();
  k.a_perp = M_PI * r * r;
  k.d_perp = 2.0 * std::sqrt(k.a_perp / M_PI);
  k.edge = kDragEdgewise * (type.area_max - k.a_perp);
  const double r_m = type.ell.mean();
  k.c_ang0 = 8.0 * M_PI * k.rho * k.nu * r_m * r_m * r_m;
  for (int a = 0; a < 3; ++a) k.rot[a] = 0.5 * k.rho * kDragRotation * type.rot_drag_len5[a];
  k.rot_max = k.rho * kDragRotation * type.rot_drag_len5.maxCoeff();
  k.mean_flow_scale = model.mean_flow_scale;
  k.turbulence_scale = model.turbulence_scale;
  if (k.grid) {
    const GridGeometry& g = model.field.geometry();
    for (int a = 0; a < 3; ++a) {
      k.origin[a] = g.origin[a];
      k.spacing[a] = g.spacing[a];
      k.n[a] = g.n[a];
      k.upper_index[a] = double(g.n[a] - 1);
    }
    k.sy = g.n[0];
    k.sz = int64_t(g.n[0]) * g.n[1];
    k.records = model.field.frame_records(0);
  } else {
    model.field.sample(Vec3::Zero(), 0.0, false, &k.uniform);
    apply_art_scales(model, &k.uniform);
  }
  k.ground = model.has_ground;
  k.ground_z = model.ground_z;
  for (int a = 0; a < 3; ++a) k.half[a] = type.half_extents[a];
  k.seed = model.seed;
  return k;
}

// The state of a block of bodies and the fluid sample at their positions, structure of arrays.
// The velocity V is the world-frame one (q v).
template <typename T>
struct Lanes {
  alignas(64) T x[3][kBatch];
  alignas(64) T V[3][kBatch];
  alignas(64) T w[3][kBatch];
  alignas(64) T q[4][kBatch];  // (w, x, y, z)
  alignas(64) T us[3][kBatch];
  alignas(64) T U[3][kBatch];
  alignas(64) T alpha[kBatch];
  alignas(64) T beta[kBatch];
  alignas(64) T sigma2[kBatch];
  alignas(64) T gs[3][kBatch];   // grad sigma2
  alignas(64) T acc[3][kBatch];  // (grad U) U: the mean flow's acceleration (steady field)
  alignas(64) T inside[kBatch];  // 1 in the fluid, 0 outside
  // the exact OU half step's coefficients at the sample (ou_exact): a steady field gives the
  // second half step of one step and the first of the next the same ones
  alignas(64) T decay[kBatch];   // exp(-alpha h/2)
  alignas(64) T noise[kBatch];   // beta sqrt((1 - exp(-alpha h)) / (2 alpha)), m/s
  uint32_t body[kBatch];
  bool live[kBatch];
};

// Fills the sample arrays of L at positions x (may be L.x itself).
template <typename T>
LRIGID_MULTIVERSION void sample_lanes(const Consts& k, const T (*x)[kBatch], Lanes<T>* L) {
  if (!k.grid) {
    const FluidSample& u = k.uniform;
LRIGID_IVDEP
    for (int j = 0; j < kBatch; ++j) {
#pragma GCC unroll 3
      for (int a = 0; a < 3; ++a) {
        L->U[a][j] = T(u.U[a]);
        L->gs[a][j] = T(0);
        L->acc[a][j] = T(0);
      }
      L->alpha[j] = T(u.alpha);
      L->beta[j] = T(u.beta);
      L->sigma2[j] = T(u.sigma2);
      const bool fin = std::isfinite(x[0][j]) && std::isfinite(x[1][j]) && std::isfinite(x[2][j]);
      L->inside[j] = fin ? T(1) : T(0);
    }
    return;
  }
  const float* rec = k.records;
  // 32-bit float offsets of the 8 corners' records (sphere_batch_eligible bounds the grid)
  const int sy = int(k.sy), sz = int(k.sz);
  const int off[8] = {0, 8, 8 * sy, 8 * (1 + sy), 8 * sz, 8 * (1 + sz), 8 * (sy + sz),
                      8 * (1 + sy + sz)};
  const T mfs = T(k.mean_flow_scale), ts = T(k.turbulence_scale), ts2 = ts * ts;
LRIGID_IVDEP
  for (int j = 0; j < kBatch; ++j) {
    T f[3];
    int idx = 0;
    bool in = true;
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      T s = (x[a][j] - T(k.origin[a])) / T(k.spacing[a]);
      in = in & (s >= T(0)) & (s <= T(k.upper_index[a]));
      // clamped so that every lane reads inside the grid, also lanes outside it
      s = s > T(0) ? s : T(0);
      s = s < T(k.upper_index[a]) ? s : T(k.upper_index[a]);
      int i = static_cast<int>(s);
      i = i < k.n[a] - 2 ? i : k.n[a] - 2;
      f[a] = s - T(i);
      idx += 8 * (a == 0 ? 1 : (a == 1 ? sy : sz)) * i;
    }
    const T gx[2] = {T(1) - f[0], f[0]}, gy[2] = {T(1) - f[1], f[1]}, gz[2] = {T(1) - f[2], f[2]};
    T W = 0, v[6] = {0, 0, 0, 0, 0, 0}, dv[4][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    int nvalid = 0;
#pragma GCC unroll 8
    for (int c = 0; c < 8; ++c) {
      const int cx = c & 1, cy = (c >> 1) & 1, cz = c >> 2;
      const int r = idx + off[c];
      const T valid = T(rec[r + 6]);
      nvalid += valid != T(0);
      const T wc = valid * (gx[cx] * gy[cy] * gz[cz]);
      const T dw[3] = {(cx ? T(1) : T(-1)) * gy[cy] * gz[cz], gx[cx] * (cy ? T(1) : T(-1)) * gz[cz],
                       gx[cx] * gy[cy] * (cz ? T(1) : T(-1))};
      W += wc;
      const T g[6] = {T(rec[r]),     T(rec[r + 1]), T(rec[r + 2]),
                      T(rec[r + 3]), T(rec[r + 4]), T(rec[r + 5])};
#pragma GCC unroll 6
      for (int p = 0; p < 6; ++p) v[p] += wc * g[p];
      const T gv[4] = {g[0], g[1], g[2], g[5]};
#pragma GCC unroll 4
      for (int p = 0; p < 4; ++p)
#pragma GCC unroll 3
        for (int a = 0; a < 3; ++a) dv[p][a] += dw[a] * gv[p];
    }
    in = in & (nvalid > 0) & (W >= T(0.5));
    const T inv = T(1) / (W > T(0) ? W : T(1));
    // gradients only where all 8 corners are valid (as FluidField::sample)
    const T all = nvalid == 8 ? T(1) : T(0);
    T gu[3][3];
#pragma GCC unroll 3
    for (int p = 0; p < 3; ++p) {
      L->U[p][j] = mfs * v[p] * inv;
#pragma GCC unroll 3
      for (int a = 0; a < 3; ++a) gu[p][a] = mfs * all * dv[p][a] / T(k.spacing[a]);
    }
    L->alpha[j] = v[3] * inv;
    L->beta[j] = ts * v[4] * inv;
    L->sigma2[j] = ts2 * v[5] * inv;
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      L->gs[a][j] = ts2 * all * dv[3][a] / T(k.spacing[a]);
      L->acc[a][j] = gu[a][0] * L->U[0][j] + gu[a][1] * L->U[1][j] + gu[a][2] * L->U[2][j];
    }
    L->inside[j] = in ? T(1) : T(0);
  }
}

// The OU half step's decay and noise at the lanes' samples (effects/turbulence.h ou_exact).
template <typename T>
LRIGID_MULTIVERSION void ou_coefficients(const Consts& k, Lanes<T>* L) {
  const double hh = 0.5 * k.h;
LRIGID_IVDEP
  for (int j = 0; j < kBatch; ++j) {
    const double alpha = double(L->alpha[j]), ah = alpha * hh;
    const double a_safe = alpha > 0 ? alpha : 1.0;
    L->decay[j] = T(exp_fast(-ah));
    L->noise[j] = T(double(L->beta[j]) * (ah > 1e-12 ? std::sqrt(one_minus_exp_neg(2.0 * ah) /
                                                                 (2.0 * a_safe))
                                                     : std::sqrt(hh)));
  }
}

// One exact Ornstein-Uhlenbeck half step of the seen fluctuation us (effects/turbulence.h) with
// Thomson's drift along the body's path (world velocity V), for one lane; wm: 1 with the drift,
// 0 without (Consts::wm, passed in: a load under a lane's condition would not vectorize).
template <typename T>
LRIGID_LANE void ou_half(T wm, T decay, T noise, T sigma2, const T* V, const T* gs, const T* z,
                         T hh, T* us) {
  const T s_safe = sigma2 > T(0) ? sigma2 : T(1);
  const T proj = (V[0] * gs[0] + V[1] * gs[1] + V[2] * gs[2]) / (T(2) * s_safe);
  const T on = sigma2 > T(0) ? wm : T(0);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a)
    us[a] = decay * us[a] + hh * (on * (T(0.5) * gs[a] + us[a] * proj)) + noise * z[a];
}

// Sphere drag (effects/drag.cpp drag_wrench, centre of buoyancy at the centre of mass): force
// and torque on relative velocity u and spin w, and the stiffness the implicit step needs.
template <typename T>
struct Drag {
  T f[3], tq[3];
  T c_lin, p, c_ang;
  T u_hat[3];
};

template <typename T>
LRIGID_LANE Drag<T> sphere_drag(const Consts& k, const T* u, const T* w) {
  Drag<T> d;
  const T speed = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  const bool moving = speed > T(0);
  const T inv = T(1) / (moving ? speed : T(1));
  const T re = speed * T(k.d_perp / k.nu);
  const T re_safe = moving ? re : T(1);
  // C_D Re = 24 (1 + 0.15 Re^0.687) below Re = 1000, 0.44 above
  const T s = T(0.15 * exp_fast(0.687 * log_fast(double(re_safe))));
  const bool newton_regime = re >= T(1000);
  const T cd = newton_regime ? T(0.44) : T(24) / re_safe * (T(1) + s);
  const T p = newton_regime ? T(1) : T(0.687) * s / (T(1) + s);
  const T c_moving = T(0.5 * k.rho) * speed * (cd * T(k.a_perp) + T(k.edge));
  const T c_lin = moving ? c_moving : T(0);
  d.c_lin = c_lin;
  d.p = moving ? p : T(0);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) {
    d.u_hat[a] = moving ? u[a] * inv : T(0);
    d.f[a] = -c_lin * u[a];
  }
  const T w_norm = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) d.tq[a] = -(T(k.c_ang0) + T(k.rot[a]) * w_norm) * w[a];
  d.c_ang = T(k.c_ang0) + T(k.rot_max) * w_norm;
  return d;
}

// y = (m I + h c_lin (I + p u u^T))^-1 b (Sherman-Morrison), times m: the impulse change
template <typename T>
LRIGID_LANE void implicit_linear(const Consts& k, const Drag<T>& d, const T* b, T* dP) {
  const T a = T(k.m) + T(k.h) * d.c_lin, c = T(k.h) * d.c_lin * d.p;
  const T ub = d.u_hat[0] * b[0] + d.u_hat[1] * b[1] + d.u_hat[2] * b[2];
  const T g = c / (a + c);
  for (int i = 0; i < 3; ++i) dP[i] = T(k.m) * (b[i] - g * d.u_hat[i] * ub) / a;
}

constexpr double kStiffChange = 0.1;  // as integrators.cpp
constexpr int kDragMaxNewton = 12;
constexpr double kDragTol = 1e-10;

// a step's outcome per lane; kNonFinite + i names the first non-finite part of the new state
enum Outcome : uint8_t { kOk = 0, kOutside = 1, kNonFinite = 2 };
const char* const kNonFiniteName[5] = {"position", "orientation", "velocity", "angular velocity",
                                       "seen turbulent velocity"};

// Normals of step `step` for every lane: the Strang half-step increments of the linear noise,
// exactly as brownian_increments (integrators.cpp) draws them from NormalStream.
template <typename T>
LRIGID_MULTIVERSION void lane_normals(const Consts& k, const Lanes<T>& L, uint64_t step,
                                      T (*z1)[kBatch], T (*z2)[kBatch]) {
  // words: block 0 (pairs 0, 1), block 1 words 2, 3 (pair 3), block 2 words 0, 1 (pair 4)
  alignas(64) uint32_t wd[8][kBatch];
  const uint32_t k0 = static_cast<uint32_t>(k.seed), k1 = static_cast<uint32_t>(k.seed >> 32);
  const uint32_t lo = static_cast<uint32_t>(step), hi = static_cast<uint32_t>(step >> 32);
LRIGID_IVDEP
  for (int j = 0; j < kBatch; ++j) {
    const uint32_t body = L.body[j];
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
  for (int j = 0; j < kBatch; ++j) {
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
      z1[c][j] = T((a[c] + b[c]) * M_SQRT1_2);
      z2[c][j] = T((a[c] - b[c]) * M_SQRT1_2);
    }
  }
}

// Advances every lane of L by one step; lanes that are not kOk keep their state at the start of
// the step. landed: the lane is on or below the ground after the step.
template <typename T, bool Turb, bool WithDrag>
LRIGID_MULTIVERSION void step_lanes(const Consts& k, Lanes<T>* L, uint64_t step, int* outcome,
                                    int* landed) {
  const T h = T(k.h), hh = T(0.5 * k.h), wm = T(k.wm);
  const bool sample = k.sample, ground = k.ground;
  const T ground_z = T(k.ground_z), half0 = T(k.half[0]), half1 = T(k.half[1]);
  const T half2 = T(k.half[2]);
  alignas(64) T z1[3][kBatch], z2[3][kBatch];
  if constexpr (Turb) lane_normals(k, *L, step, z1, z2);
  // new state, committed at the end for the lanes whose step succeeded
  alignas(64) T xn[3][kBatch], Vn[3][kBatch], wn[3][kBatch], qn[4][kBatch], usn[3][kBatch];
  // what the Newton iteration of stiff drag needs
  alignas(64) T uf[3][kBatch], Pi[3][kBatch], dP[3][kBatch], dL[3][kBatch], V0[3][kBatch];
  alignas(64) T norm_r[kBatch];
  int stiff[kBatch];
  int any_stiff = 0;
LRIGID_IVDEP
  for (int j = 0; j < kBatch; ++j) {
    T us[3] = {L->us[0][j], L->us[1][j], L->us[2][j]};
    const T U[3] = {L->U[0][j], L->U[1][j], L->U[2][j]};
    const T gs[3] = {L->gs[0][j], L->gs[1][j], L->gs[2][j]};
    // 1. first OU half step
    if constexpr (Turb) {
      const T z[3] = {z1[0][j], z1[1][j], z1[2][j]};
      const T V[3] = {L->V[0][j], L->V[1][j], L->V[2][j]};
      ou_half(wm, L->decay[j], L->noise[j], L->sigma2[j], V, gs, z, hh, us);
    }
    // 2. the free Kirchhoff flow: for isotropic M the world velocity is unchanged and
    //    q <- q cay(h w) (integrate/dynamics.cpp kirchhoff_flow)
    T u_f[3], V[3], w[3];
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      u_f[a] = T(k.mf) * U[a] + (Turb ? us[a] : T(0));
      V[a] = L->V[a][j];
      w[a] = L->w[a][j];
    }
    {
      const T qw = L->q[0][j], qx = L->q[1][j], qy = L->q[2][j], qz = L->q[3][j];
      const T ax = hh * w[0], ay = hh * w[1], az = hh * w[2];
      T nw = qw - (qx * ax + qy * ay + qz * az);
      T nx = qw * ax + qx + (qy * az - qz * ay);
      T ny = qw * ay + qy + (qz * ax - qx * az);
      T nz = qw * az + qz + (qx * ay - qy * ax);
      const T inv = T(1) / std::sqrt(nw * nw + nx * nx + ny * ny + nz * nz);
      qn[0][j] = nw * inv, qn[1][j] = nx * inv, qn[2][j] = ny * inv, qn[3][j] = nz * inv;
    }
    // 3. the forces, drag implicit: (M + h J) M^-1 dPi = h G
    T vr[3];
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) vr[a] = V[a] - u_f[a];
    Drag<T> d = {};
    if constexpr (WithDrag) d = sphere_drag(k, vr, w);
    T b[3], P[3], dPj[3], dLj[3], Vnew[3], wnew[3], u_end[3];
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      b[a] = h * (T(k.F[a]) + d.f[a]);
      P[a] = T(k.m) * V[a] - T(k.ma) * u_f[a];
      // the fluid velocity at the end of the step enters through the added mass
      u_end[a] = u_f[a] + h * T(k.gu) * L->acc[a][j];
    }
    implicit_linear(k, d, b, dPj);
    const T ja = T(k.J) + h * d.c_ang;
    T e_new = 0, e_r = 0;
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      dLj[a] = T(k.J) * (h * d.tq[a]) / ja;
      Vnew[a] = (P[a] + dPj[a] + T(k.ma) * u_end[a]) / T(k.m);
      wnew[a] = (T(k.J) * w[a] + dLj[a]) / T(k.J);
      e_new += dPj[a] * dPj[a] / T(k.m) + dLj[a] * dLj[a] / T(k.J);
      e_r += T(k.m) * vr[a] * vr[a] + T(k.J) * w[a] * w[a];
    }
    const int s = WithDrag ? int(e_new > T(kStiffChange * kStiffChange) * e_r) : 0;
    stiff[j] = s;
    any_stiff |= s;
    norm_r[j] = e_r;
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      uf[a][j] = u_f[a];
      Pi[a][j] = P[a];
      dP[a][j] = dPj[a];
      dL[a][j] = dLj[a];
      V0[a][j] = V[a];
      Vn[a][j] = Vnew[a];
      wn[a][j] = wnew[a];
      usn[a][j] = us[a];
    }
  }
  // stiff drag: Newton on R(dPi) = dPi - h (G_other + F_drag(xi(dPi))), lanes drop out as they
  // converge
  if (WithDrag && any_stiff) {
    for (int it = 0; it < kDragMaxNewton; ++it) {
      int any = 0;
LRIGID_IVDEP
      for (int j = 0; j < kBatch; ++j) {
        // every lane computes, the lanes still iterating keep the result
        const bool act = stiff[j] != 0;
        T vr[3], w[3];
#pragma GCC unroll 3
        for (int a = 0; a < 3; ++a) {
          vr[a] = Vn[a][j] - uf[a][j];
          w[a] = wn[a][j];
        }
        const Drag<T> d = sphere_drag(k, vr, w);
        T res[3], dd[3];
#pragma GCC unroll 3
        for (int a = 0; a < 3; ++a) res[a] = dP[a][j] - h * (T(k.F[a]) + d.f[a]);
        implicit_linear(k, d, res, dd);
        const T ja = T(k.J) + h * d.c_ang;
        T conv = 0;
#pragma GCC unroll 3
        for (int a = 0; a < 3; ++a) {
          const T dl = -T(k.J) * (dL[a][j] - h * d.tq[a]) / ja;
          const T dPa = dP[a][j] - dd[a], dLa = dL[a][j] + dl;
          const T acc = T(k.gu) * L->acc[a][j];
          const T Va = (Pi[a][j] + dPa + T(k.ma) * (uf[a][j] + h * acc)) / T(k.m);
          const T wa = (T(k.J) * L->w[a][j] + dLa) / T(k.J);
          dP[a][j] = act ? dPa : dP[a][j];
          dL[a][j] = act ? dLa : dL[a][j];
          Vn[a][j] = act ? Va : Vn[a][j];
          wn[a][j] = act ? wa : wn[a][j];
          conv += dd[a] * dd[a] / T(k.m) + dl * dl / T(k.J);
        }
        const int more = int(act & (conv > T(kDragTol * kDragTol) * norm_r[j]));
        stiff[j] = more;
        any |= more;
      }
      if (!any) break;
    }
  }
  // 4. x by the trapezoidal rule; 5. the second OU half step at the new position
LRIGID_IVDEP
  for (int j = 0; j < kBatch; ++j)
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) xn[a][j] = L->x[a][j] + hh * (V0[a][j] + Vn[a][j]);
  alignas(64) T inside0[kBatch];
  for (int j = 0; j < kBatch; ++j) inside0[j] = k.sample ? L->inside[j] : T(1);
  if (k.sample) sample_lanes(k, xn, L);
  if (Turb) ou_coefficients(k, L);
LRIGID_IVDEP
  for (int j = 0; j < kBatch; ++j) {
    T us[3] = {usn[0][j], usn[1][j], usn[2][j]};
    if constexpr (Turb) {
      const T V[3] = {Vn[0][j], Vn[1][j], Vn[2][j]};
      const T gs[3] = {L->gs[0][j], L->gs[1][j], L->gs[2][j]};
      const T z[3] = {z2[0][j], z2[1][j], z2[2][j]};
      ou_half(wm, L->decay[j], L->noise[j], L->sigma2[j], V, gs, z, hh, us);
    }
    usn[0][j] = us[0];
    usn[1][j] = us[1];
    usn[2][j] = us[2];
    // & rather than && on the lanes' conditions: no branches in the loop
    const bool in = (inside0[j] != T(0)) & (!sample | (L->inside[j] != T(0)));
    // int & int: every condition evaluated, no branch (bool && would short-circuit)
    auto fin = [](T v) { return int(std::isfinite(v)); };
    const bool fx = fin(xn[0][j]) & fin(xn[1][j]) & fin(xn[2][j]);
    const bool fq = fin(qn[0][j]) & fin(qn[1][j]) & fin(qn[2][j]) & fin(qn[3][j]);
    const bool fv = fin(Vn[0][j]) & fin(Vn[1][j]) & fin(Vn[2][j]);
    const bool fw = fin(wn[0][j]) & fin(wn[1][j]) & fin(wn[2][j]);
    const bool fu = fin(us[0]) & fin(us[1]) & fin(us[2]);
    // bits of what is right, decoded into the outcome below (bit i clear: part i non-finite)
    outcome[j] = int(fx) | int(fq) << 1 | int(fv) << 2 | int(fw) << 3 | int(fu) << 4 |
                 int(in) << 5;
    // the lowest point of the body's bounding box (simulation.cpp touches_ground)
    const T qw = qn[0][j], qx = qn[1][j], qy = qn[2][j], qz = qn[3][j];
    const T r20 = T(2) * (qx * qz - qw * qy), r21 = T(2) * (qy * qz + qw * qx);
    const T r22 = T(1) - T(2) * (qx * qx + qy * qy);
    const T reach = std::abs(r20) * half0 + std::abs(r21) * half1 + std::abs(r22) * half2;
    landed[j] = int(ground & (xn[2][j] - reach <= ground_z));
  }
  for (int j = 0; j < kBatch; ++j) {
    const int bits = outcome[j];
    int bad = 0;  // the first non-finite part, in the order step_body names them
    while (bad < 5 && (bits >> bad & 1)) ++bad;
    outcome[j] = !(bits >> 5 & 1) ? int(kOutside) : (bad < 5 ? int(kNonFinite) + bad : int(kOk));
  }
  // commit the lanes whose step succeeded
  for (int j = 0; j < kBatch; ++j) {
    if (outcome[j] != kOk || !L->live[j]) continue;
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      L->x[a][j] = xn[a][j];
      L->V[a][j] = Vn[a][j];
      L->w[a][j] = wn[a][j];
      L->us[a][j] = usn[a][j];
    }
#pragma GCC unroll 4
    for (int a = 0; a < 4; ++a) L->q[a][j] = qn[a][j];
  }
}

template <typename T>
void lane_to_body(const Lanes<T>& L, int j, BodyState* b) {
  b->x = Vec3(double(L.x[0][j]), double(L.x[1][j]), double(L.x[2][j]));
  b->q = Quat(double(L.q[0][j]), double(L.q[1][j]), double(L.q[2][j]), double(L.q[3][j]));
  const Vec3 V(double(L.V[0][j]), double(L.V[1][j]), double(L.V[2][j]));
  b->v = b->q.toRotationMatrix().transpose() * V;
  b->w = Vec3(double(L.w[0][j]), double(L.w[1][j]), double(L.w[2][j]));
  b->u_seen = Vec3(double(L.us[0][j]), double(L.us[1][j]), double(L.us[2][j]));
}

template <typename T>
BlockStats advance(const Model& model, const BodyType& type, State* state, const uint32_t* body,
                   int count, uint64_t first, uint64_t last) {
  BlockStats stats;
  State& st = *state;
  const Consts k = make_consts(model, type);
  Lanes<T> L{};  // zeroed: without a field to sample, the sample arrays stay the fluid at rest
  for (int j = 0; j < kBatch; ++j) {
    // lanes past count repeat the first body and stay idle
    const size_t i = body[j < count ? j : 0];
    const Vec3 V = st.q[i] * st.v[i];
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      L.x[a][j] = T(st.x[i][a]);
      L.V[a][j] = T(V[a]);
      L.w[a][j] = T(st.w[i][a]);
      L.us[a][j] = T(st.u_seen[i][a]);
    }
    L.q[0][j] = T(st.q[i].w()), L.q[1][j] = T(st.q[i].x());
    L.q[2][j] = T(st.q[i].y()), L.q[3][j] = T(st.q[i].z());
    L.body[j] = static_cast<uint32_t>(i);
    L.live[j] = j < count && st.status[i] == BodyStatus::Moving;
  }
  if (k.sample) sample_lanes(k, L.x, &L);
  if (k.turb) ou_coefficients(k, &L);
  alignas(64) int outcome[kBatch];
  alignas(64) int landed[kBatch];
  for (uint64_t s = first; s < last; ++s) {
    bool any = false;
    for (int j = 0; j < count; ++j) any = any || L.live[j];
    if (!any) break;
    const double t = static_cast<double>(s) * model.dt;
    if (k.turb && k.drag) step_lanes<T, true, true>(k, &L, s, outcome, landed);
    else if (k.turb) step_lanes<T, true, false>(k, &L, s, outcome, landed);
    else if (k.drag) step_lanes<T, false, true>(k, &L, s, outcome, landed);
    else step_lanes<T, false, false>(k, &L, s, outcome, landed);
    for (int j = 0; j < count; ++j) {
      if (!L.live[j]) continue;
      const size_t i = L.body[j];
      if (outcome[j] == kOk) {
        ++stats.body_steps;
        if (!landed[j]) continue;
        st.status[i] = BodyStatus::Landed;
        st.t_stop[i] = t + model.dt;
      } else {
        // the lane kept its state at the start of the step (as step_body restores it)
        BodyState b;
        lane_to_body(L, j, &b);
        const bool outside = outcome[j] == kOutside;
        const std::string failure =
            outside ? "" : std::string("non-finite ") + kNonFiniteName[outcome[j] - kNonFinite];
        stop_body(model, type, i, t, outside ? StepOutcome::Exited : StepOutcome::Failed, failure,
                  b, &st);
      }
      L.live[j] = false;
      if (st.status[i] == BodyStatus::Landed) {
#pragma GCC unroll 3
        for (int a = 0; a < 3; ++a) L.V[a][j] = L.w[a][j] = T(0);
      }
    }
  }
  for (int j = 0; j < count; ++j) {
    const size_t i = body[j];
    BodyState b;
    lane_to_body(L, j, &b);
    store_body(b, i, &st);
  }
  return stats;
}

}  // namespace

const char* sphere_batch_isa() {
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
  // the same tests the loader's choice among the target_clones versions makes
  if (__builtin_cpu_supports("x86-64-v4")) return "AVX-512";
  if (__builtin_cpu_supports("x86-64-v3")) return "AVX2";
  return "baseline x86-64";
#else
  return "baseline";
#endif
}

BlockStats advance_sphere_block(const Model& model, const BodyType& type, State* state,
                                const uint32_t* body, int count, uint64_t first, uint64_t last) {
  if (model.precision == Precision::Float)
    return advance<float>(model, type, state, body, count, first, last);
  return advance<double>(model, type, state, body, count, first, last);
}

}  // namespace lrigid
