// The batched step for plates, ellipsoids and meshes: the schemes of integrate/integrators.h
// (splitting and strang here, euler and rk4 in rigid_batch_explicit.h) for rigid bodies whose
// generalized mass M is not isotropic (boxes, disks, ellipsoids: a diagonal M; leaves, paper, seed
// pods; and meshes, an artist's curled leaf: a full symmetric 6 x 6 M with linear-angular
// coupling), advanced kBatch at a time in structure-of-arrays blocks like the sphere step
// (integrate/sphere_batch.h, docs/batched-step.md). The loops are compiled once for each kind of M
// (model/kirchhoff.h DiagonalMass, FullMass): the kernels of a diagonal M stay element-wise, a
// full one pays its 6 x 6 products and LU.
//
// The splitting step: the scalar step's physics, term for term, on the same random numbers: exact
// Ornstein-Uhlenbeck half steps with Thomson's drift; the free Kirchhoff flow by the implicit
// midpoint rule, solved by the scalar step's fixed-point iteration with a convergence mask per
// lane, and the Cayley rotation; gravity and buoyancy; the Andersen-Pesavento-Wang plate drag and
// torque with the Stokes terms, and plate lift (flat bodies) or the ellipsoid drag (others); the
// linearly implicit force step with added mass and the mean-flow acceleration.
//
// What the loops leave to the scalar step, which then redoes the lane's whole step (so the result
// is the scalar step's): a Kirchhoff flow whose fixed-point iteration does not converge fast (the
// scalar step's Newton fallback) and drag stiff enough for the Newton iteration of the force step.
// On the leaves scene these are rare (bench/perf/batch_bench.py counts them).
//
// What qualifies (rigid_batch_eligible): a type that is not a uniform sphere (a sphere whose
// centre of mass is off its centroid is this step's; with such an offset the fluid's forces and the
// buoyancy act at the centroid and turn the body about its centre of mass, runtime factors in the
// loops), with any effect whose registry row is batched, and what every batched step needs
// (batch_lanes.h batch_exclusion: the seen model, one noise increment per step, a steady field or
// a series; any of the four schemes).
#pragma once
#include <cstdint>
#include <string>

#include "integrate/sphere_batch.h"
#include "model/model.h"
#include "model/state.h"

namespace lrigid {

// Whether bodies of this type take the batched rigid-body step; when not, `why` says why.
bool rigid_batch_eligible(const Model& model, const BodyType& type, std::string* why = nullptr);

// As advance_sphere_block, for a type that rigid_batch_eligible accepts.
BlockStats advance_rigid_block(const Model& model, const BodyType& type, State* state,
                               const uint32_t* body, int count, uint64_t first, uint64_t last);

// advance_rigid_block for each precision and kind of M (model/kirchhoff.h DiagonalMass,
// FullMass), in the files rigid_batch_{diag,full}_{double,float}.cpp
namespace rigid_batch_detail {
BlockStats advance_diag_double(const Model& model, const BodyType& type, State* state,
                              const uint32_t* body, int count, uint64_t first, uint64_t last);
BlockStats advance_diag_float(const Model& model, const BodyType& type, State* state,
                             const uint32_t* body, int count, uint64_t first, uint64_t last);
BlockStats advance_full_double(const Model& model, const BodyType& type, State* state,
                              const uint32_t* body, int count, uint64_t first, uint64_t last);
BlockStats advance_full_float(const Model& model, const BodyType& type, State* state,
                             const uint32_t* body, int count, uint64_t first, uint64_t last);
}  // namespace rigid_batch_detail

}  // namespace lrigid
