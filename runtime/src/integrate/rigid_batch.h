// The batched step: the schemes of integrate/integrators.h (splitting and strang in
// rigid_batch_step.h, euler and rk4 in rigid_batch_explicit.h) for rigid bodies, advanced kBatch
// at a time in structure-of-arrays blocks, so each stage of the step is one loop across bodies
// that the compiler vectorizes (docs/batched-step.md). The loops are compiled once for each kind
// of generalized mass M (model/kirchhoff.h): IsotropicMass (uniform spheres), DiagonalMass (boxes,
// disks, ellipsoids: leaves, paper, seed pods) and FullMass (meshes, an artist's curled leaf: a
// full symmetric 6 x 6 M with linear-angular coupling). The kernels of a diagonal M stay
// element-wise, a full one pays its 6 x 6 products and LU; for an isotropic M the free Kirchhoff
// flow is a rotation alone (no iteration) and the lanes keep the world velocity, which a sphere's
// forces do not need turned into a body frame.
//
// The physics is the scalar step's, term for term, on the same random numbers (Philox keyed by
// seed, body and step): exact Ornstein-Uhlenbeck half steps with Thomson's drift; the free
// Kirchhoff flow by the implicit midpoint rule, solved by the scalar step's fixed-point iteration
// with a convergence mask per lane, and the Cayley rotation; gravity and buoyancy; the
// Andersen-Pesavento-Wang plate drag and torque with the Stokes terms, and plate lift (flat
// bodies) or the ellipsoid drag (others); Magnus, the Basset history; the linearly implicit force
// step with added mass and the mean-flow acceleration, drag implicit with Newton when stiff. Two
// things differ only in rounding: exp, log and pow are util/fast_math.h's polynomials, and a
// sphere's velocity is kept in the world frame. tests/runtime/integrate/sphere_batch_test.cpp and
// rigid_batch_test.cpp hold the batched step to the scalar one. Precision::Float runs the same
// step in single precision (its speed and accuracy cost are measured by bench/perf/batch_bench.py).
//
// What the loops leave to the scalar step, which then redoes the lane's whole step (so the result
// is the scalar step's): a Kirchhoff flow whose fixed-point iteration and Newton do not converge
// fast (the scalar step's substeps), and an rk4 stage that leaves the fluid. On the leaves scene
// these are rare (bench/perf/batch_bench.py counts them).
//
// What qualifies (rigid_batch_eligible): any body type whose effects all have a batched kernel
// (the registry, effects/registry.cpp; a body whose centre of mass is off its centroid too: the
// fluid's forces and the buoyancy then act at the centroid and turn the body about its centre of
// mass, runtime factors in the loops), and what the step needs of the scene (batch_lanes.h
// batch_exclusion: the seen model, one noise increment per step, a uniform field, a grid or a
// series of grids; any of the four schemes). Other body types take the scalar step; a scene can
// mix both.
#pragma once
#include <cstdint>
#include <string>

#include "model/model.h"
#include "model/state.h"

namespace lrigid {

struct StretchSweep;  // integrate/sweep.h

constexpr int kBatch = 32;  // bodies per block: a multiple of every SIMD width

// A uniform sphere's generalized mass: isotropic, the centre of mass at the centroid (a sphere
// with an offset centre of mass has a diagonal M about it).
inline bool uniform_sphere_mass(const BodyType& type) {
  return type.M_isotropic && type.r_cob.isZero(0.0);
}

// The kinds of M the loops are compiled for
enum class BatchMass { Isotropic, Diagonal, Full };
BatchMass batch_mass(const BodyType& type);
const char* batch_mass_name(BatchMass kind);  // "isotropic M", "diagonal M", "full M"

// Whether bodies of this type take the batched step; when not, `why` says why.
bool rigid_batch_eligible(const Model& model, const BodyType& type, std::string* why = nullptr);

struct BlockStats {
  uint64_t body_steps = 0;
  uint64_t scalar_steps = 0;  // of them, steps a lane handed to the scalar step
  uint64_t newton_steps = 0;  // steps on which the loops ran Newton (stiff drag, the free flow)
};

// Advances up to kBatch bodies of one eligible type (indices body[0..count)) in `state` from
// step `first` to step `last`, with the same statuses, stop times and reasons the scalar loop of
// integrate/simulation.cpp gives (landing, leaving the grid, non-finite state). sweep: null, or
// the stretch's record of the bodies' motion (integrate/sweep.h, batch_lanes.h drive_block).
BlockStats advance_rigid_block(const Model& model, const BodyType& type, State* state,
                               const uint32_t* body, int count, uint64_t first, uint64_t last,
                               StretchSweep* sweep = nullptr);

// The version of the batched step's loops this CPU runs: "AVX-512", "AVX2" or "baseline x86-64"
// (or "baseline" off x86-64 and in Clang builds).
const char* batch_isa();

// advance_rigid_block for each precision and kind of M, in the files
// rigid_batch_{iso,diag,full}_{double,float}.cpp
namespace rigid_batch_detail {
BlockStats advance_iso_double(const Model& model, const BodyType& type, State* state,
                              const uint32_t* body, int count, uint64_t first, uint64_t last,
                              StretchSweep* sweep);
BlockStats advance_iso_float(const Model& model, const BodyType& type, State* state,
                             const uint32_t* body, int count, uint64_t first, uint64_t last,
                             StretchSweep* sweep);
BlockStats advance_diag_double(const Model& model, const BodyType& type, State* state,
                               const uint32_t* body, int count, uint64_t first, uint64_t last,
                               StretchSweep* sweep);
BlockStats advance_diag_float(const Model& model, const BodyType& type, State* state,
                              const uint32_t* body, int count, uint64_t first, uint64_t last,
                              StretchSweep* sweep);
BlockStats advance_full_double(const Model& model, const BodyType& type, State* state,
                               const uint32_t* body, int count, uint64_t first, uint64_t last,
                               StretchSweep* sweep);
BlockStats advance_full_float(const Model& model, const BodyType& type, State* state,
                              const uint32_t* body, int count, uint64_t first, uint64_t last,
                              StretchSweep* sweep);
}  // namespace rigid_batch_detail

}  // namespace lrigid
