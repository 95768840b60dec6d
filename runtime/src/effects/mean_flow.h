// Mean flow: the fluid around the body moves with the field's mean velocity U (plus, with the
// "seen" turbulence model, the fluctuation u' the body sees). Drag and added mass act on the
// motion relative to it. Without this effect the fluid is at rest.
#pragma once
#include "fluid/field.h"
#include "util/types.h"

namespace lrigid {

// Fluid acceleration along the fluid's own path (material derivative), world frame, m/s^2:
// Du/Dt = dU/dt + (grad U) U.
inline Vec3 mean_flow_acceleration(const FluidSample& s) { return s.dU_dt + s.grad_U * s.U; }

}  // namespace lrigid
