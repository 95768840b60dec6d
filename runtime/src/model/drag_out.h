// A drag (or plate) kernel's result (effects/drag.h, effects/plate.h): force and torque about
// the point where u is taken, and the stiffness the implicit step needs (DragStiffness). Here,
// below the effects, because the generalized mass's implicit solve (model/kirchhoff.h) takes it.
#pragma once

namespace lrigid {

template <typename T>
struct DragOut {
  T f[3], tq[3];
  T c_lin, p, c_ang[3];  // c_ang per body axis
  T u_hat[3];
};

}  // namespace lrigid
