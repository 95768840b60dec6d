// One plain sentence per body type for `lrigid explain`, for readers who do not
// speak in Stokes numbers: how much turbulence moves it, how fast it falls or rises, what its
// shape does, whether the flow carries it farther than it falls. Built from explain's data
// (io/explain.h) only; the thresholds are stated in docs/effects.md ("In plain words").
#pragma once
#include <string>

#include <nlohmann/json.hpp>

namespace lrigid {

// `type`: one of explain_scene()'s body_types; `scene`: explain_scene()'s whole result
std::string plain_words(const nlohmann::json& type, const nlohmann::json& scene);

}  // namespace lrigid
