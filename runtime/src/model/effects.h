// The physical effects a scene can select, as a set (the scene's and each body type's choice).
// What each effect is (its name, field need, "auto" rule, cost, batched support) is the
// registry's row: effects/registry.h. An effect that is not selected is never evaluated.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace lrigid {

enum class Effect : uint32_t {
  Gravity = 1u << 0,     // weight m g at the centre of mass
  Buoyancy = 1u << 1,    // -rho_f V g at the centre of buoyancy
  AddedMass = 1u << 2,   // fluid Kirchhoff tensor in the generalized mass + its gyroscopic terms
  Drag = 1u << 3,        // quasi-steady linear and angular drag on the relative velocity
  MeanFlow = 1u << 4,    // the body sees the field's mean velocity U (else the fluid is at rest)
  Turbulence = 1u << 5,  // Langevin model from k and epsilon
  Lift = 1u << 6,        // circulation lift of flat bodies (Andersen, Pesavento & Wang 2005)
  Magnus = 1u << 7,      // lift of a spinning body, C_M rho V w x v_r
  Basset = 1u << 8,      // Basset-Boussinesq history force (window + exponential-sum tail)
};

struct EffectSet {
  uint32_t bits = 0;
  bool has(Effect e) const { return bits & static_cast<uint32_t>(e); }
  void add(Effect e) { bits |= static_cast<uint32_t>(e); }
  void remove(Effect e) { bits &= ~static_cast<uint32_t>(e); }
  bool operator==(const EffectSet& o) const { return bits == o.bits; }
};

}  // namespace lrigid
