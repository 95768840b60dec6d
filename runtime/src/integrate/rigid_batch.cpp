#include "integrate/rigid_batch.h"

#include "integrate/batch_lanes.h"

namespace lrigid {

BatchMass batch_mass(const BodyType& type) {
  // an isotropic M: a uniform sphere (the loops take its drag's projected area as the same
  // across every direction)
  if (type.shape.type == ShapeType::Sphere && uniform_sphere_mass(type))
    return BatchMass::Isotropic;
  // M (and K's first three columns) diagonal: the diagonal kernels; otherwise the full ones
  const bool k_diag = !type.effects.has(Effect::AddedMass) ||
                      (type.K_fluid.leftCols<3>().bottomRows<3>().isZero(0.0) &&
                       Mat3(type.K_fluid.topLeftCorner<3, 3>().diagonal().asDiagonal()) ==
                           type.K_fluid.topLeftCorner<3, 3>());
  return type.M_diagonal && k_diag ? BatchMass::Diagonal : BatchMass::Full;
}

const char* batch_mass_name(BatchMass kind) {
  switch (kind) {
    case BatchMass::Isotropic: return "isotropic M";
    case BatchMass::Diagonal: return "diagonal M";
    case BatchMass::Full: return "full M";
  }
  return "full M";
}

bool rigid_batch_eligible(const Model& model, const BodyType& type, std::string* why) {
  const std::string all = batch_exclusion(model, type, true);
  if (all.empty()) return true;
  if (why) *why = all;
  return false;
}

const char* batch_isa() {
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
  // the same tests the loader's choice among the target_clones versions makes
  if (__builtin_cpu_supports("x86-64-v4")) return "AVX-512";
  if (__builtin_cpu_supports("x86-64-v3")) return "AVX2";
  return "baseline x86-64";
#else
  return "baseline";
#endif
}

BlockStats advance_rigid_block(const Model& model, const BodyType& type, State* state,
                               const uint32_t* body, int count, uint64_t first, uint64_t last,
                               StretchSweep* sweep) {
  using namespace rigid_batch_detail;  // NOLINT(build/namespaces)
  const bool f = model.precision == Precision::Float;
  switch (batch_mass(type)) {
    case BatchMass::Isotropic:
      return f ? advance_iso_float(model, type, state, body, count, first, last, sweep)
               : advance_iso_double(model, type, state, body, count, first, last, sweep);
    case BatchMass::Diagonal:
      return f ? advance_diag_float(model, type, state, body, count, first, last, sweep)
               : advance_diag_double(model, type, state, body, count, first, last, sweep);
    case BatchMass::Full:
      break;
  }
  return f ? advance_full_float(model, type, state, body, count, first, last, sweep)
           : advance_full_double(model, type, state, body, count, first, last, sweep);
}

}  // namespace lrigid
