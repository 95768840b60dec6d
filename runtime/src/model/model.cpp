#include "model/model.h"

namespace lrigid {

const char* integrator_name(Integrator i) {
  switch (i) {
    case Integrator::Euler: return "euler";
    case Integrator::RK4: return "rk4";
    case Integrator::Splitting: return "splitting";
    case Integrator::Strang: return "strang";
  }
  return "?";
}

bool integrator_from_name(const std::string& name, Integrator* out) {
  for (Integrator i :
       {Integrator::Euler, Integrator::RK4, Integrator::Splitting, Integrator::Strang}) {
    if (name == integrator_name(i)) {
      *out = i;
      return true;
    }
  }
  return false;
}

const char* turbulence_model_name(TurbulenceModel m) {
  return m == TurbulenceModel::Body ? "body" : "seen";
}

const char* drift_name(Drift d) { return d == Drift::Original ? "original" : "stationary"; }
const char* contact_mode_name(ContactMode m) {
  return m == ContactMode::Collide ? "collide" : "stop";
}
const char* outside_mode_name(OutsideMode m) { return m == OutsideMode::Remove ? "remove" : "stop"; }

EffectSet Model::union_effects() const {
  EffectSet s;
  for (const auto& t : types) s.bits |= t.effects.bits;
  return s;
}

}  // namespace lrigid
