#include "integrate/dynamics.h"

#include "effects/mean_flow.h"
#include "effects/wrench.h"
#include "model/kirchhoff.h"
#include "util/lane.h"

namespace lrigid {

EvalResult impulse_rates(const Model& model, const BodyType& type, const Kinematics& k, double t,
                         ImpulseRates* out, DragStiffness* stiffness) {
  FluidSample fluid;
  EffectContext c;
  Vec3 uf;
  if (!effect_context(model, type, k, t, true, &fluid, &c, &uf)) return EvalResult::Outside;
  c.stiffness = stiffness;
  Vec6 xi;
  xi << k.v, k.w;
  out->fluid_inertia = type.effects.has(Effect::AddedMass);
  out->impulse = type.M_times(xi);
  out->u_fluid = uf;
  out->a_fluid.setZero();
  if (out->fluid_inertia) {
    Vec6 ufb;
    ufb << c.Rt * uf, Vec3::Zero();
    out->impulse -= type.K_fluid * ufb;
    if (type.plan.mean_flow) out->a_fluid = mean_flow_acceleration(fluid);
  }
  out->rate = sum_effect_wrenches(c);
  return EvalResult::Ok;
}

namespace {

// One implicit-midpoint step of the free Kirchhoff flow from Y0 (see kirchhoff_flow) on the
// kernels of model/kirchhoff.h: false when Newton did not converge. w_mid: the angular
// velocity at the midpoint.
template <class Mass>
bool kirchhoff_midpoint(const Mass& mass, double h, const Vec6& Y0, Vec6* Y1, Vec3* w_mid,
                        int* iterations) {
  const double norm0 = energy_norm2(mass, Y0.data());  // twice the relative kinetic energy
  const double tol2 = kKirchhoffTol * kKirchhoffTol * norm0;
  auto finish = [&](const Vec6& Y) {
    *Y1 = Y;
    const Vec6 Ym = 0.5 * (Y0 + Y);
    Vec6 xm;
    mass_inv_times(mass, Ym.data(), xm.data());
    *w_mid = xm.tail<3>();
    return true;
  };
  // fixed-point iteration first (cheap; contracts by about h |dg/dY| / 2 per iteration, fast
  // for most bodies); Newton from where it stopped when it contracts slowly or diverges
  Vec6 Y;
  kirchhoff_predictor(mass, h, Y0.data(), Y.data());
  double last = 0;
  for (int it = 0; it < kKirchhoffMaxFixedPoint; ++it) {
    ++*iterations;
    Vec6 next;
    const double step = kirchhoff_fixed_point(mass, h, Y0.data(), Y.data(), next.data());
    if (!next.allFinite()) break;
    Y = next;
    if (step <= tol2) return finish(Y);
    if (it > 0 && step > kKirchhoffSlowContraction * last) break;
    last = step;
  }
  {
    const Vec6 d = Y - Y0;
    if (!Y.allFinite() || energy_norm2(mass, d.data()) > 4 * norm0) Y = Y0;
  }
  // Newton, simplified: the Jacobian is factored once and kept while the iteration contracts
  // by at least kKirchhoffRefactor per step; otherwise it is refactored at the current iterate
  // (a full Newton step)
  double A[36];
  bool refactor = true;
  double last_step = 0;
  for (int it = 0; it < kKirchhoffMaxNewton; ++it) {
    ++*iterations;
    Vec6 d;
    kirchhoff_residual(mass, h, Y0.data(), Y.data(), d.data());
    if (refactor) {
      const Vec6 Ym = 0.5 * (Y0 + Y);
      kirchhoff_newton_matrix(mass, Ym.data(), 0.5 * h, A);
      if (!lu_factor<6>(A)) return false;
    }
    lu_solve<6>(A, d.data());
    Y += d;
    if (!Y.allFinite()) return false;
    const double step = energy_norm2(mass, d.data());
    if (step <= tol2) return finish(Y);
    refactor = it > 0 && step > kKirchhoffRefactor * kKirchhoffRefactor * last_step;
    last_step = step;
  }
  return false;
}

// q cay(theta): the rotation by the Cayley map of the body-frame vector theta (rad), the
// quaternion (1, theta/2) normalized (angle 2 atan(|theta|/2))
Quat rotate_cayley(const Quat& q, const Vec3& theta) {
  const double q0[4] = {q.w(), q.x(), q.y(), q.z()};
  const double a[3] = {0.5 * theta.x(), 0.5 * theta.y(), 0.5 * theta.z()};
  double qn[4];
  cayley_rotate(q0, a, qn);
  return Quat(qn[0], qn[1], qn[2], qn[3]);
}

// kirchhoff_flow on the relative impulse Y over h, split into n equal substeps
template <class Mass>
bool kirchhoff_substeps(const Mass& mass, double h, int n, Quat* q, Vec6* Y, int* iterations) {
  Quat qn = *q;
  Vec6 Yn = *Y;
  for (int i = 0; i < n; ++i) {
    Vec6 Y1;
    Vec3 w_mid;
    if (!kirchhoff_midpoint(mass, h / n, Yn, &Y1, &w_mid, iterations)) return false;
    qn = rotate_cayley(qn, (h / n) * w_mid);
    Yn = Y1;
  }
  *q = qn;
  *Y = Yn;
  return true;
}

}  // namespace

int kirchhoff_flow(const BodyType& type, const Vec3& u_fluid, double h, Quat* q, Vec3* v,
                   Vec3* w) {
  const Vec3 uf_b = q->toRotationMatrix().transpose() * u_fluid;
  Vec6 xi_r;
  xi_r << *v - uf_b, *w;
  Vec6 Y = type.M_times(xi_r);
  int iterations = 0;
  if (type.M_isotropic) {
    // M = diag(m, m, m, J, J, J) (spheres): v x P = 0 and w x L = 0, so L and w are constant
    // and the midpoint equation is linear, P1 = (I + a^)^-1 (I - a^) P0 with a = h w / 2,
    // solved in closed form (the Cayley transform)
    const Vec3 a = 0.5 * h * Vec3(type.M_inv_diagonal.tail<3>().cwiseProduct(Y.tail<3>()));
    const Vec3 P = Y.head<3>(), aP = a.cross(P);
    Y.head<3>() = P + (2.0 / (1.0 + a.squaredNorm())) * (a.cross(aP) - aP);
    *q = rotate_cayley(*q, 2.0 * a);
  } else {
    auto substeps = [&](const auto& mass) {
      int n = 1;
      while (!kirchhoff_substeps(mass, h, n, q, &Y, &iterations) && n < kKirchhoffMaxSubsteps)
        n *= 2;
    };
    if (type.M_diagonal)
      substeps(diagonal_mass(type));
    else
      substeps(full_mass(type));
  }
  // (after the last substep count the state is left unchanged if Newton still failed: the
  // step keeps the start orientation and velocity, which is finite and conserves the energy)
  xi_r = type.M_inv_times(Y);
  *v = xi_r.head<3>() + q->toRotationMatrix().transpose() * u_fluid;
  *w = xi_r.tail<3>();
  return iterations;
}

Vec6 velocity_from_impulse(const BodyType& type, const Vec6& impulse, const Vec3& u_fluid_body,
                           bool fluid_inertia) {
  if (!fluid_inertia) return type.M_inv_times(impulse);
  Vec6 uf;
  uf << u_fluid_body, Vec3::Zero();
  return type.M_inv_times(impulse + type.K_fluid * uf);
}

EvalResult velocity_derivative(const Model& model, const BodyType& type, const Kinematics& k,
                               double t, Vec6* xi_dot, FluidSample* fluid,
                               DragStiffness* stiffness) {
  Vec6 f;
  if (effect_wrench(model, type, k, t, &f, fluid, stiffness) == EvalResult::Outside)
    return EvalResult::Outside;
  // rigid body's own gyroscopic terms (about the COM, v x m v = 0)
  Vec6 xi;
  xi << k.v, k.w;
  f -= kirchhoff_gyro(k.v, k.w, type.M_body * xi);
  *xi_dot = type.M_inv_times(f);
  return EvalResult::Ok;
}

}  // namespace lrigid
