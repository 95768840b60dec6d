#include "model/effects.h"

namespace lrigid {

const std::vector<EffectInfo>& all_effects() {
  static const std::vector<EffectInfo> list = {
      {Effect::Gravity, "gravity", "weight m g at the centre of mass"},
      {Effect::Buoyancy, "buoyancy", "-rho_f V g at the centre of buoyancy"},
      {Effect::AddedMass, "added_mass", "Kirchhoff tensor of the displaced fluid"},
      {Effect::Drag, "drag", "quasi-steady drag on the velocity relative to the fluid"},
      {Effect::MeanFlow, "mean_flow", "the fluid moves with the field's mean velocity U"},
      {Effect::Turbulence, "turbulence", "Langevin model from k and epsilon"},
      {Effect::Lift, "lift", "circulation lift of flat bodies (Andersen, Pesavento & Wang 2005)"},
      {Effect::Magnus, "magnus", "lift of a spinning body, C_M rho V w x v_r"},
      {Effect::Basset, "basset", "history force, window plus exponential-sum tail"},
  };
  return list;
}

bool effect_from_name(const std::string& name, Effect* out) {
  for (const auto& e : all_effects())
    if (name == e.name) {
      *out = e.effect;
      return true;
    }
  return false;
}

std::vector<std::string> effect_names(EffectSet set) {
  std::vector<std::string> names;
  for (const auto& e : all_effects())
    if (set.has(e.effect)) names.push_back(e.name);
  return names;
}

}  // namespace lrigid
