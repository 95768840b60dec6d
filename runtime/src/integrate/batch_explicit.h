// What the euler and rk4 loops of the batched steps need beyond batch_lanes.h, written for any
// kind of lane (Lanes derived from Samples<T>, consts derived from FieldConsts): the field's
// frames at rk4's stage times, rk4's per-stage storage across a block, and the Euler-Maruyama
// update of the seen fluctuation. Internal to the batched step's explicit schemes
// (rigid_batch_explicit.h).
#pragma once
#include <type_traits>

#include "effects/turbulence.h"
#include "fluid/field.h"
#include "integrate/batch_lanes.h"

namespace lrigid {
namespace {  // NOLINT(build/namespaces): internal to the batched-step files

// The field's frames at rk4's stage times t + h/2 and t + h of step s (a time-dependent field;
// none: the driver's frames, FieldConsts::records)
struct Rk4Frames {
  bool unsteady = false;
  FluidField::FrameBlend mid, end;
};

inline Rk4Frames rk4_frames(const Model& model, bool unsteady, uint64_t s) {
  Rk4Frames f;
  f.unsteady = unsteady;
  if (unsteady) {
    const double t = static_cast<double>(s) * model.dt;
    f.mid = model.field.frames_at(t + 0.5 * model.dt);
    f.end = model.field.frames_at(t + model.dt);
  }
  return f;
}

// rk4's state within a step: each stage's state (position, rotation vector theta from the
// start's q, body-frame v, w), and the sums k1 + 2 k2 + 2 k3 + k4 of the rates of x (world),
// theta and xi = (v; w); ok: 0 where a stage's sample left the fluid; v0: the start's body-frame
// velocity (for lanes that keep the world one)
template <typename T>
struct Rk4Block {
  alignas(64) T v0[3][kBatch];
  alignas(64) T xs[3][kBatch];
  alignas(64) T th[3][kBatch];
  alignas(64) T vs[3][kBatch];
  alignas(64) T ws[3][kBatch];
  alignas(64) T Sx[3][kBatch];
  alignas(64) T Sth[3][kBatch];
  alignas(64) T Sxi[6][kBatch];
  alignas(64) T ok[kBatch];
};

// Stage I's rates at lane j (kx of x, world; kth of theta; kxi of xi = (v; w), body frame) into
// rk4's sums k1 + 2 k2 + 2 k3 + k4, and before the last stage the next stage's state from the
// start's x0, v0, w0: x0 + c h kx, theta = c h kth, v0 + c h kxi (c = 1/2, 1/2, 1); in: the stage's
// sample was inside the fluid (k->ok is 0 from the first stage that was not)
// (the last stage writes a next state too, which nothing reads: one loop serves stages 1 to 3;
// the sums are read whatever the stage, since a load under a condition keeps the loops scalar)
template <typename T>
LRIGID_LANE void rk4_sum_lane(int I, Rk4Block<T>* k, int j, bool in, T h, const T* x0, const T* v0,
                              const T* w0, const T* kx, const T* kth, const T* kxi) {
  const bool first = I == 0;
  const T ci = I <= 1 ? T(0.5) : T(1), wi = first || I == 3 ? T(1) : T(2);
  const bool was_ok = k->ok[j] != T(0);
  k->ok[j] = ((first | was_ok) & in) ? T(1) : T(0);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) {
    const T sx = k->Sx[a][j] + wi * kx[a], sth = k->Sth[a][j] + wi * kth[a];
    k->Sx[a][j] = first ? kx[a] : sx;
    k->Sth[a][j] = first ? kth[a] : sth;
    k->xs[a][j] = x0[a] + ci * h * kx[a];
    k->th[a][j] = ci * h * kth[a];
    k->vs[a][j] = v0[a] + ci * h * kxi[a];
    k->ws[a][j] = w0[a] + ci * h * kxi[3 + a];
  }
#pragma GCC unroll 6
  for (int a = 0; a < 6; ++a) {
    const T s = k->Sxi[a][j] + wi * kxi[a];
    k->Sxi[a][j] = first ? kxi[a] : s;
  }
}

// rk4's four stages on a block: stage(std::integral_constant<int, I>) evaluates stage I at k's
// stage state and adds its rates to k's sums; between stages the field is sampled at the next
// stage's positions (k->xs) and, in a time-dependent field, at its time (t + h/2, t + h/2,
// t + h). The driver's frames (the end of the step) are restored after the last stage. Inlined,
// with the stages, into each multiversioned rk4 loop that calls it.
template <typename T, class Lanes, class Stage>
LRIGID_LANE void rk4_stages(const FieldConsts& fc, const Rk4Frames& frames, Lanes* lanes,
                            Rk4Block<T>* k, Stage stage) {
  const FluidField::FrameBlend at_end = lanes->frames;
  auto sample = [&](const FluidField::FrameBlend& at) LRIGID_LANE_LAMBDA {
    if (!fc.sample) return;
    if (frames.unsteady) lanes->frames = at;
    sample_lanes(fc, k->xs, lanes, 0, lanes->width);
  };
  stage(std::integral_constant<int, 0>{});
  sample(frames.mid);
  stage(std::integral_constant<int, 1>{});
  sample(frames.mid);
  stage(std::integral_constant<int, 2>{});
  sample(frames.end);
  stage(std::integral_constant<int, 3>{});
  lanes->frames = at_end;
}

// The seen fluctuation us of lane j after the step by Euler-Maruyama from the start of the step
// (integrators.cpp step_body: Ito, the start's sample and path velocity V0, world), normals z
// (the whole step's, lane_normals<T, true>)
template <typename T, class Lanes>
LRIGID_LANE void ou_euler_lane(const FieldConsts& fc, const Lanes* lanes, int j, const T* V0,
                               const T (*z)[kBatch], T* us) {
  T decay, noise, decay_a, noise_a;
  ou_crossing_euler_kernel(lanes->alpha[j], lanes->beta[j], lanes->sigma2[j], T(fc.vd2), T(fc.h),
                           &decay, &noise, &decay_a, &noise_a);
  const T cd[3] = {T(fc.cd[0]), T(fc.cd[1]), T(fc.cd[2])};
  // without seen turbulence (tu = 0) the identity, exactly
  lane_ou_update(T(fc.tu), T(fc.wm), decay, noise, decay_a, noise_a, cd, T(fc.h), *lanes, z, j,
                 V0, us);
}

}  // namespace
}  // namespace lrigid
