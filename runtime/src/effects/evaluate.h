// The effects' wrench on one body at one instant: the fluid sampled at the body (with the
// scene's art-direction scales), the context the wrench terms see, and the sum of the terms of
// the body type's plan (effects/plan.h). The steps (integrate/dynamics.h) and the contact's
// sleeping test (contact/sleep.h) evaluate the effects through these.
#pragma once
#include "effects/context.h"
#include "effects/drag.h"
#include "effects/plan.h"
#include "fluid/field.h"
#include "model/model.h"

namespace lrigid {

struct Kinematics {
  Vec3 x;       // world, m
  Mat3 R;       // body -> world
  Vec3 v;       // body frame, m/s
  Vec3 w;       // body frame, rad/s
  Vec3 u_seen;  // seen fluctuation, world frame, m/s
  const double* history = nullptr;  // Basset history (BassetKernel::stride() doubles) or null
};

enum class EvalResult { Ok, Outside };

// Does the body need the fluid field sampled at all?
inline bool needs_field(const BodyType& t) { return t.plan.sample_field; }

// Applies the scene's art-direction scales to a field sample: U (and its derivatives) by
// model.mean_flow_scale, the turbulent velocity by model.turbulence_scale (sigma2 and its
// gradient by its square, beta by it).
inline void apply_art_scales(const Model& m, FluidSample* s) {
  if (m.mean_flow_scale != 1.0) {
    s->U *= m.mean_flow_scale;
    s->grad_U *= m.mean_flow_scale;
    s->dU_dt *= m.mean_flow_scale;
  }
  if (m.turbulence_scale != 1.0) {
    const double t2 = m.turbulence_scale * m.turbulence_scale;
    s->beta *= m.turbulence_scale;
    s->sigma2 *= t2;
    s->grad_sigma2 *= t2;
  }
}

// model.field.sample followed by apply_art_scales
inline bool sample_fluid(const Model& m, const Vec3& x, double t, bool gradients,
                         FluidSample* out) {
  if (!m.field.sample(x, t, gradients, out)) return false;
  apply_art_scales(m, out);
  return true;
}

// Sum of the wrenches of the selected effects (the plan's terms), body frame.
inline Vec6 sum_effect_wrenches(const EffectContext& c) {
  Vec6 f = Vec6::Zero();
  for (WrenchTerm term : c.type->plan.terms) f += term(c);
  return f;
}

// Sum of the effect wrenches alone in the velocity form (no rigid gyroscopic term): used by
// tests to check each effect's exact contribution.
EvalResult effect_wrench(const Model& model, const BodyType& type, const Kinematics& k, double t,
                         Vec6* wrench, FluidSample* fluid, DragStiffness* stiffness = nullptr);

// The context the wrench terms see (velocity form unless impulse_form); u_fluid: the fluid
// velocity around the body, world frame. false when the body is outside the fluid.
bool effect_context(const Model& model, const BodyType& type, const Kinematics& k, double t,
                    bool impulse_form, FluidSample* fluid, EffectContext* c, Vec3* u_fluid);

// effect_context on a fluid sample taken before (the sample is not repeated): the context
// keeps a pointer to `fluid`.
void context_from_sample(const Model& model, const BodyType& type, const Kinematics& k,
                         bool impulse_form, const FluidSample* fluid, EffectContext* c,
                         Vec3* u_fluid);

}  // namespace lrigid
