#include "integrate/rigid_batch.h"

#include "integrate/batch_lanes.h"

namespace lrigid {

namespace {
// M (and K's first three columns) diagonal: the diagonal kernels; otherwise the full ones
bool diagonal_step(const BodyType& type) {
  const bool k_diag = !type.effects.has(Effect::AddedMass) ||
                      (type.K_fluid.leftCols<3>().bottomRows<3>().isZero(0.0) &&
                       Mat3(type.K_fluid.topLeftCorner<3, 3>().diagonal().asDiagonal()) ==
                           type.K_fluid.topLeftCorner<3, 3>());
  return type.M_diagonal && k_diag;
}

}  // namespace

bool rigid_batch_eligible(const Model& model, const BodyType& type, std::string* why) {
  auto no = [why](const std::string& reason) {
    if (why) *why = reason;
    return false;
  };
  if (const std::string all = batch_exclusion(model, type, true); !all.empty()) return no(all);
  if (uniform_sphere_mass(type)) return no("an isotropic generalized mass (the sphere step's)");
  return true;
}

BlockStats advance_rigid_block(const Model& model, const BodyType& type, State* state,
                               const uint32_t* body, int count, uint64_t first, uint64_t last) {
  using namespace rigid_batch_detail;  // NOLINT(build/namespaces)
  const bool diag = diagonal_step(type);
  if (model.precision == Precision::Float)
    return diag ? advance_diag_float(model, type, state, body, count, first, last)
                : advance_full_float(model, type, state, body, count, first, last);
  return diag ? advance_diag_double(model, type, state, body, count, first, last)
              : advance_full_double(model, type, state, body, count, first, last);
}

}  // namespace lrigid
