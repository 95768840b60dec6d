// What a wrench term sees of one body at one instant (built once per evaluation by
// effects/evaluate.cpp and shared by all selected terms).
#pragma once
#include "effects/drag.h"
#include "fluid/field.h"
#include "model/model.h"

namespace lrigid {

struct EffectContext {
  const Model* model = nullptr;
  const BodyType* type = nullptr;
  Mat3 Rt = Mat3::Identity();        // world -> body
  Vec3 v_rel = Vec3::Zero();         // velocity relative to the surrounding fluid, body, m/s
  Vec3 w = Vec3::Zero();             // angular velocity, body frame, rad/s
  Vec3 g_body = Vec3::Zero();        // gravity, body frame, m/s^2
  Vec3 fluid_acc = Vec3::Zero();     // d/dt of the fluid velocity in body axes (added mass), m/s^2
  const FluidSample* fluid = nullptr;
  const double* history = nullptr;   // Basset history of this body (null without Basset)
  bool impulse_form = false;         // euler/splitting: added mass enters as -v_r x P_f only
  DragStiffness* stiffness = nullptr;  // filled by drag when not null
};

}  // namespace lrigid
