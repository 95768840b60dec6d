// The batched step for small spheres: the schemes of integrate/integrators.h for bodies whose
// generalized mass is isotropic (uniform spheres), advanced kBatch at a time in
// structure-of-arrays blocks, so each stage of the step is one loop across bodies that the
// compiler vectorizes (docs/batched-step.md).
//
// The physics is the scalar step's, term for term, on the same random numbers (Philox keyed by
// seed, body and step): exact Ornstein-Uhlenbeck half steps with Thomson's drift, the free
// Kirchhoff flow (for an isotropic M a pure rotation, q <- q cay(h w)), gravity and buoyancy,
// sphere drag implicit with Newton when stiff, added mass with the mean-flow acceleration. Two
// things differ only in rounding: the velocity is kept in the world frame (for an isotropic M the
// equations do not depend on the orientation) and exp, log and pow are util/fast_math.h's
// polynomials. tests/runtime/integrate/sphere_batch_test.cpp holds the batched step to the scalar
// one. Precision::Float runs the same step in single precision (its speed and accuracy cost are
// measured by bench/perf/batch_bench.py).
//
// What qualifies (sphere_batch_eligible): a uniform sphere (centre of mass at the centroid) with
// effects among gravity, buoyancy, drag, added mass, mean flow, turbulence, Basset and Magnus;
// the seen turbulence model; any integrator (splitting, strang, and euler and rk4 in
// sphere_batch_explicit.h); one noise increment per step; a uniform field, a grid or a series of
// grids. Other body types take the scalar step; a scene can mix both.
#pragma once
#include <cstdint>
#include <string>

#include "model/model.h"
#include "model/state.h"

namespace lrigid {

constexpr int kBatch = 32;  // bodies per block: a multiple of every SIMD width

// A uniform sphere's generalized mass: isotropic, the centre of mass at the centroid. The sphere
// step's loops keep no body frame, so only such types are theirs (any other takes the plates'
// step, integrate/rigid_batch.h).
inline bool uniform_sphere_mass(const BodyType& type) {
  return type.M_isotropic && type.r_cob.isZero(0.0);
}

// Whether bodies of this type take the batched step; when not, `why` says what excludes it.
bool sphere_batch_eligible(const Model& model, const BodyType& type, std::string* why = nullptr);

struct BlockStats {
  uint64_t body_steps = 0;
  uint64_t scalar_steps = 0;  // of them, steps a lane handed to the scalar step
  uint64_t newton_steps = 0;  // steps on which the loops ran Newton (stiff drag, the free flow)
};

// Advances up to kBatch bodies of one eligible type (indices body[0..count)) in `state` from
// step `first` to step `last`, with the same statuses, stop times and reasons the scalar loop of
// integrate/simulation.cpp gives (landing, leaving the grid, non-finite state).
BlockStats advance_sphere_block(const Model& model, const BodyType& type, State* state,
                                const uint32_t* body, int count, uint64_t first, uint64_t last);

// The version of the batched step's loops this CPU runs: "AVX-512", "AVX2" or "baseline x86-64"
// (or "baseline" off x86-64 and in Clang builds).
const char* sphere_batch_isa();

}  // namespace lrigid
