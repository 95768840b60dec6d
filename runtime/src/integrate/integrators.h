// Time integrators for one body over one step h = model.dt (docs/physics/integrators.md).
//   euler      explicit Euler for the deterministic part, Euler-Maruyama for the noise.
//              Order 1 (strong and weak). Stable only for h < 2/lambda_drag and alpha h < 2
//              (noise variance biased by 2/(2 - alpha h)).
//   rk4        classic Runge-Kutta (RKMK4 on SO(3): the rotation is q exp(theta) with theta
//              integrated through dexp^-1) for the deterministic part, order 4; the noise is
//              added once per step with sqrt(h) scaling as in the seed method, so the stochastic
//              order is 1. Stable for h < 2.79/lambda_drag, alpha h < 2.
//   splitting  Strang splitting: exact Ornstein-Uhlenbeck half step, the deterministic step,
//              exact OU half step. The deterministic step is itself split (Lie-Trotter): the
//              free Kirchhoff flow (gyroscopic and Munk terms, rotation) by the implicit
//              midpoint rule with the Cayley rotation, which conserves the relative kinetic
//              energy exactly; then the forces with the drag implicit (linearly implicit Euler,
//              Newton-iterated to backward Euler when the drag is stiff). Order 1
//              deterministic, stable for any alpha h, any drag stiffness and any added-mass
//              anisotropy (paper-thin plates).
//   strang     the same OU half steps around a symmetric deterministic step: force half step,
//              free Kirchhoff flow (implicit midpoint, full step), force half step, the force
//              steps by the Rosenbrock-W method ROS2 (drag stiffness in its matrix; second order
//              for any such matrix, L-stable; the flow relative to the fluid velocity at the
//              midpoint). Order 2 deterministic, weak order 2 measured on a smooth case (the OU
//              part exact); stable for any alpha h and drag stiffness. Body types with the
//              Basset history take the splitting step.
// Basset history force: its past part is a wrench term like any other effect; the current
// interval's part acts as a mass 2 C sqrt(h) on the translation and is taken implicitly (impulse
// step: on the left-hand side with the drag stiffness; rk4: a correction after the step). The
// history is appended once the step succeeded.
// Orientation is always updated by multiplying by a unit quaternion and renormalized, so
// |q| - 1 stays at round-off.
#pragma once
#include <cstdint>
#include <functional>
#include <string>

#include "model/body_state.h"
#include "model/model.h"
#include "model/state.h"

namespace lrigid {

// The splitting step's implicit drag (the batched steps follow the same rule): one linearly
// implicit step, iterated by Newton to the backward Euler solution when it changes the relative
// velocity by more than kStiffChange (energy norm), at most kDragMaxNewton times, until the
// update is below kDragTol of the relative velocity.
constexpr double kStiffChange = 0.1;
constexpr int kDragMaxNewton = 12;
constexpr double kDragTol = 1e-10;

// Advances `s` from time t by model.dt. Random numbers are keyed by (seed, body, step).
// On Exited/Failed `s` is left at its value before the step and `reason` says why.
StepOutcome step_body(const Model& model, const BodyType& type, uint32_t body, uint64_t step,
                      double t, BodyState* s, std::string* reason);

// step_body with its deterministic part split at t + tau (0 < tau < model.dt): the part from t
// to t + tau, at_split(t + tau, s) (an impact's impulses: integrate/impacts.h), the part from
// there to the step's end. The turbulence update is step_body's (the same normals, at the same
// ends of the step).
using SplitAt = std::function<void(double t, BodyState* s)>;
StepOutcome step_body_split(const Model& model, const BodyType& type, uint32_t body,
                            uint64_t step, double t, double tau, const SplitAt& at_split,
                            BodyState* s, std::string* reason);

// The deterministic part of the model's scheme over h (any h > 0, not only model.dt) from time
// t: the step without its turbulence update (u_seen held) and without appending to the Basset
// history. What a step split at an event inside it takes on each side (integrate/impacts.h).
// On Exited/Failed `s` is left as it was.
StepOutcome deterministic_substep(const Model& model, const BodyType& type, double t, double h,
                                  BodyState* s);

}  // namespace lrigid
