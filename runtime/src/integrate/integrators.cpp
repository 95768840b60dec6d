#include "integrate/integrators.h"

#include <cmath>

#include "effects/basset.h"
#include "effects/mean_flow.h"
#include "effects/turbulence.h"
#include "integrate/dynamics.h"
#include "model/kirchhoff.h"
#include "util/fast_math.h"
#include "util/lane.h"
#include "util/rng.h"

namespace lrigid {

namespace {

Kinematics kinematics(const BodyState& s) {
  return Kinematics{s.x, s.q.toRotationMatrix(), s.v, s.w, s.u_seen, s.history};
}

bool uses_turbulence(const Model& m, const BodyType& t, TurbulenceModel which) {
  return t.effects.has(Effect::Turbulence) && m.turbulence_model == which;
}

// one turbulence update over h, exact OU (splitting) or Euler-Maruyama (euler, rk4)
// z: 6 standard normals reserved for this update
StepOutcome turbulence_update(const Model& model, const BodyType& type, double t, double h,
                              bool exact, const double* z, BodyState* s) {
  FluidSample fs;
  const bool seen = model.turbulence_model == TurbulenceModel::Seen;
  if (!sample_fluid(model, s->x, t, !model.field.is_uniform(), &fs)) return StepOutcome::Exited;
  // across and along the body type's drift (crossing trajectories; the same pair without one)
  const double vd2 = type.drift_speed * type.drift_speed;
  double decay, noise, decay_a, noise_a;
  if (exact)
    ou_crossing_exact_kernel<ScalarMath>(fs.alpha, fs.beta, fs.sigma2, vd2, h, &decay, &noise,
                                         &decay_a, &noise_a);
  else
    ou_crossing_euler_kernel(fs.alpha, fs.beta, fs.sigma2, vd2, h, &decay, &noise, &decay_a,
                             &noise_a);
  // the turbulent velocity u' (world frame, in u_seen) follows the OU process with Thomson's
  // well-mixed drift in both models: "seen" makes it the fluid velocity around the body (acting
  // through drag and added mass), "body" adds it to the body's own velocity (x' = R v + u').
  // The drift follows the body's path: its velocity x'.
  Vec3 path_velocity = s->q * s->v;
  if (!seen) path_velocity += s->u_seen;
  ou_update_crossing(model.well_mixed_correction ? 1.0 : 0.0, decay, noise, decay_a, noise_a,
                     type.drift_dir.data(), fs.sigma2, path_velocity.data(),
                     fs.grad_sigma2.data(), z, h, s->u_seen.data());
  if (!seen) {
    const Vec3 xi2(z[3], z[4], z[5]);
    s->w = decay * s->w + (noise / type.r_eq) * xi2;
  }
  return StepOutcome::Ok;
}

// rotate the two 3-blocks of a 6-vector
Vec6 rotate6(const Mat3& R, const Vec6& a) {
  Vec6 r;
  r << R * a.head<3>(), R * a.tail<3>();
  return r;
}

// the drag stiffness ds (none: null) as the kernels of model/kirchhoff.h take it
DragOut<double> drag_out(const DragStiffness* ds) {
  DragOut<double> d{};
  if (ds) {
    d.c_lin = ds->c_lin;
    d.p = ds->p;
    for (int a = 0; a < 3; ++a) d.c_ang[a] = ds->c_ang[a];
    for (int a = 0; a < 3; ++a) d.u_hat[a] = ds->u_hat[a];
  }
  return d;
}
// f(M, out) with the body type's M as the kernels take it (diagonal or full); returns out
template <class F>
Vec6 with_mass(const BodyType& type, F f) {
  Vec6 out;
  if (type.M_diagonal)
    f(diagonal_mass(type), out.data());
  else
    f(full_mass(type), out.data());
  return out;
}
// The implicit force step's solve for right-hand side rhs, J the drag stiffness ds (none: null),
// b the Basset history's current interval as a mass (0 without): (M + h J + b P)^-1 rhs, the
// velocity change (implicit_velocity_change; model/kirchhoff.h implicit_velocity, the batched
// steps' kernel), or M times that, the impulse change (implicit_impulse_change)
Vec6 implicit_velocity_change(const BodyType& type, double b, const DragStiffness* ds, double h,
                              const Vec6& rhs) {
  const DragOut<double> d = drag_out(ds);
  return with_mass(type, [&](const auto& m, double* y) {
    implicit_velocity(m, b, d, h, rhs.data(), y);
  });
}
Vec6 implicit_impulse_change(const BodyType& type, double b, const DragStiffness* ds, double h,
                             const Vec6& rhs) {
  const DragOut<double> d = drag_out(ds);
  return with_mass(type, [&](const auto& m, double* x) {
    implicit_impulse(m, b, d, h, rhs.data(), x);
  });
}

// One explicit Euler step in world-frame impulse form (see dynamics.h): forces, Munk moment
// and rotation from the start of the step (euler). The Basset history's current interval is
// implicit (a mass on the left-hand side).
StepOutcome impulse_step(const Model& model, const BodyType& type, double t, double h,
                         BodyState* s) {
  const Kinematics k = kinematics(*s);
  ImpulseRates r;
  if (impulse_rates(model, type, k, t, &r, nullptr) == EvalResult::Outside)
    return StepOutcome::Exited;
  Vec6 dPi = h * r.rate;
  if (type.plan.basset && s->history) {
    // current interval of the history force: 2 C sqrt(h) (du_f - dv) / h
    const double b = type.basset.implicit_mass;
    dPi.head<3>() += b * (k.R.transpose() * (h * r.a_fluid));
    dPi = implicit_impulse_change(type, b, nullptr, h, dPi);
  }
  const Vec6 Pi_world = rotate6(k.R, r.impulse + dPi);
  const Vec3 u_fluid_new = r.u_fluid + h * r.a_fluid;  // world frame
  const Vec3 V0 = k.R * s->v;
  s->q = rotate_body(s->q, h * s->w);
  const Mat3 R1 = s->q.toRotationMatrix();
  const Vec6 xi = velocity_from_impulse(type, rotate6(R1.transpose(), Pi_world),
                                        R1.transpose() * u_fluid_new, r.fluid_inertia);
  s->v = xi.head<3>();
  s->w = xi.tail<3>();
  s->x += h * V0;
  return StepOutcome::Ok;
}

// Deterministic part of the splitting scheme (docs/physics/integrators.md), Lie-Trotter:
//   1. the free Kirchhoff flow of the motion relative to the fluid (gyroscopic and Munk terms,
//      rotation): implicit midpoint + Cayley (kirchhoff_flow), energy-conserving;
//   2. the forces at the new orientation in impulse form, drag implicit: one linearly implicit
//      step (M + h J) dPi = M h G, iterated by Newton to the backward Euler solution when the
//      drag changes the relative velocity by more than kStiffChange in the step;
//   3. x by the trapezoidal rule on the world velocity.
// The field is sampled once, at the start of the step.

StepOutcome split_deterministic_step(const Model& model, const BodyType& type, double t, double h,
                                     BodyState* s) {
  const EffectPlan& plan = type.plan;
  FluidSample fluid;
  if (plan.sample_field && !sample_fluid(model, s->x, t, plan.gradients, &fluid))
    return StepOutcome::Exited;
  // fluid velocity around the body (world), constant over the Kirchhoff flow
  Vec3 uf = Vec3::Zero();
  if (plan.mean_flow) uf += fluid.U;
  if (plan.seen) uf += s->u_seen;
  const Vec3 V0 = s->q * s->v;
  kirchhoff_flow(type, uf, h, &s->q, &s->v, &s->w);
  const Kinematics k = kinematics(*s);
  EffectContext c;
  context_from_sample(model, type, k, true, &fluid, &c, &uf);
  // forces at the new orientation; the added-mass term is all in the Kirchhoff flow
  DragStiffness ds;
  c.stiffness = &ds;
  Vec6 rate = Vec6::Zero(), drag = Vec6::Zero();
  WrenchTerm drag_term = nullptr;
  for (size_t i = 0; i < plan.terms.size(); ++i) {
    const Effect e = plan.term_effect[i];
    if (e == Effect::AddedMass) continue;
    const Vec6 f = plan.terms[i](c);
    rate += f;
    if (e == Effect::Drag) {
      drag = f;
      drag_term = plan.terms[i];
    }
  }
  const bool fluid_inertia = type.effects.has(Effect::AddedMass);
  const Vec3 a_fluid =
      fluid_inertia && plan.mean_flow ? mean_flow_acceleration(fluid) : Vec3::Zero();
  const Vec3 uf_b = c.Rt * uf;
  const Vec3 uf_b_new = c.Rt * (uf + h * a_fluid);
  Vec6 xi;
  xi << s->v, s->w;
  Vec6 Pi = type.M_times(xi);
  if (fluid_inertia) Pi -= type.K_fluid.leftCols<3>() * uf_b;
  // (M + h J + b P) M^-1 dPi = h G + b h a: drag stiffness J, Basset's current interval b
  const double b = plan.basset && s->history ? type.basset.implicit_mass : 0.0;
  const Vec3 basset_rhs = b * (h * (c.Rt * a_fluid));
  // the drag stiffness ds is re-evaluated by each drag evaluation below (Newton)
  const DragStiffness* J = drag_term ? &ds : nullptr;
  Vec6 rhs = h * rate;
  rhs.head<3>() += basset_rhs;
  Vec6 dPi = implicit_impulse_change(type, b, J, h, rhs);
  Vec6 xi_new = velocity_from_impulse(type, Pi + dPi, uf_b_new, fluid_inertia);
  if (drag_term) {
    Vec6 xi_r;
    xi_r << s->v - uf_b, s->w;
    const double norm_r = xi_r.dot(type.M_times(xi_r));
    const Vec6 dxi = type.M_inv_times(dPi);
    if (dxi.dot(type.M_times(dxi)) > kStiffChange * kStiffChange * norm_r) {
      // stiff drag: Newton on R(dPi) = dPi - h (G_other + F_drag(xi(dPi))) - b (h a - dv)
      const Vec6 other = rate - drag;
      EffectContext cd = c;
      for (int it = 0; it < kDragMaxNewton; ++it) {
        cd.v_rel = xi_new.head<3>() - uf_b;
        cd.w = xi_new.tail<3>();
        Vec6 res = dPi - h * (other + drag_term(cd));
        res.head<3>() -= basset_rhs - b * type.M_inv_times(dPi).head<3>();
        const Vec6 d = -implicit_impulse_change(type, b, J, h, res);
        dPi += d;
        xi_new = velocity_from_impulse(type, Pi + dPi, uf_b_new, fluid_inertia);
        const Vec6 dv = type.M_inv_times(d);
        if (dv.dot(type.M_times(dv)) <= kDragTol * kDragTol * norm_r) break;
      }
    }
  }
  s->v = xi_new.head<3>();
  s->w = xi_new.tail<3>();
  s->x += 0.5 * h * (V0 + k.R * s->v);
  return StepOutcome::Ok;
}

// The Strang scheme's force step over h at the body's position and orientation (both held), on
// the fluid sample taken there: ROS2 (model/kirchhoff.h ros2_velocity), the
// stiffness J the drag's. The added-mass term is all in the Kirchhoff flow but for the fluid's
// own acceleration, a constant force K (R^T Du/Dt; 0) here; the forces see the fluid velocity at
// the body's (held) position.
void strang_force_step(const Model& model, const BodyType& type, const FluidSample& fluid,
                       double h, BodyState* s) {
  const EffectPlan& plan = type.plan;
  const Kinematics k = kinematics(*s);
  EffectContext c;
  Vec3 uf;
  context_from_sample(model, type, k, true, &fluid, &c, &uf);
  DragStiffness ds, J;
  bool has_drag = false;
  c.stiffness = &ds;
  const bool fluid_inertia = type.effects.has(Effect::AddedMass);
  const Vec3 uf_b = c.Rt * uf;
  Vec6 drag_along = Vec6::Zero();
  if (fluid_inertia && plan.mean_flow)
    drag_along = type.K_fluid.leftCols<3>() * (c.Rt * mean_flow_acceleration(fluid));
  Vec6 xi0;
  xi0 << s->v, s->w;
  auto forces = [&](const double* dxi, bool first, double* F) {
    c.v_rel = xi0.head<3>() + Eigen::Map<const Vec3>(dxi) - uf_b;
    c.w = xi0.tail<3>() + Eigen::Map<const Vec3>(dxi + 3);
    Vec6 rate = drag_along;
    for (size_t i = 0; i < plan.terms.size(); ++i) {
      const Effect e = plan.term_effect[i];
      if (e == Effect::AddedMass) continue;
      rate += plan.terms[i](c);
      if (first && e == Effect::Drag) has_drag = true;
    }
    if (first) J = ds;
    Eigen::Map<Vec6> out(F);
    out = rate;
  };
  auto solve = [&](double gh, const double* b, double* y) {
    Eigen::Map<Vec6> out(y);
    out = implicit_velocity_change(type, 0.0, has_drag ? &J : nullptr, gh,
                                   Eigen::Map<const Vec6>(b));
  };
  auto m_times = [&](const double* y, double* out) {
    Eigen::Map<Vec6> x(out);
    x = type.M_times(Eigen::Map<const Vec6>(y));
  };
  Vec6 dxi;
  ros2_velocity(h, forces, solve, m_times, dxi.data());
  s->v = xi0.head<3>() + dxi.head<3>();
  s->w = xi0.tail<3>() + dxi.tail<3>();
}

// Deterministic part of the Strang scheme (docs/physics/integrators.md): the symmetric
// composition F(h/2) K(h) F(h/2) of the force step (strang_force_step, position and orientation
// held) and the free Kirchhoff flow (kirchhoff_flow, implicit midpoint + Cayley, with x by the
// trapezoidal rule on the world velocity). Both parts are second order, the composition too.
// The field is sampled at the start and at the end of the step (t_end: (step + 1) dt, as the
// next step's start); the flow moves relative to the fluid velocity at the midpoint,
// U + grad U (h/2 V) from the start's sample.
StepOutcome strang_deterministic_step(const Model& model, const BodyType& type, double t,
                                      double t_end, double h, BodyState* s) {
  const double hh = 0.5 * h;
  const EffectPlan& plan = type.plan;
  FluidSample fluid;
  if (plan.sample_field && !sample_fluid(model, s->x, t, plan.gradients, &fluid))
    return StepOutcome::Exited;
  strang_force_step(model, type, fluid, hh, s);
  Vec3 uf = Vec3::Zero();
  if (plan.mean_flow) uf += fluid.U;
  if (plan.seen) uf += s->u_seen;
  const Vec3 V0 = s->q * s->v;
  // the flow moves relative to the fluid velocity at the step's midpoint, predicted to first
  // order along the start's velocity (second order in a non-uniform mean flow with added mass;
  // without added mass, or for an isotropic M, the flow does not depend on it)
  if (plan.gradients) uf += fluid.grad_U * (hh * V0);
  kirchhoff_flow(type, uf, h, &s->q, &s->v, &s->w);
  s->x += hh * (V0 + s->q * s->v);
  if (plan.sample_field && !sample_fluid(model, s->x, t_end, plan.gradients, &fluid))
    return StepOutcome::Exited;
  strang_force_step(model, type, fluid, hh, s);
  return StepOutcome::Ok;
}

StepOutcome rk4(const Model& model, const BodyType& type, double t, double h, BodyState* s) {
  const Quat q0 = s->q;
  Vec3 kx[4], kth[4];
  Vec6 kxi[4];
  const double c[4] = {0.0, 0.5, 0.5, 1.0};
  for (int i = 0; i < 4; ++i) {
    BodyState st = *s;
    Vec3 theta = Vec3::Zero();
    if (i > 0) {
      st.x = s->x + c[i] * h * kx[i - 1];
      theta = c[i] * h * kth[i - 1];
      st.q = rotate_body(q0, theta);
      st.v = s->v + c[i] * h * kxi[i - 1].head<3>();
      st.w = s->w + c[i] * h * kxi[i - 1].tail<3>();
    }
    const Kinematics k = kinematics(st);
    FluidSample fs;
    if (velocity_derivative(model, type, k, t + c[i] * h, &kxi[i], &fs) == EvalResult::Outside)
      return StepOutcome::Exited;
    kx[i] = k.R * st.v;
    dexpinv(theta.data(), st.w.data(), kth[i].data());  // util/lane.h
  }
  s->x += h / 6.0 * (kx[0] + 2 * kx[1] + 2 * kx[2] + kx[3]);
  s->q = rotate_body(q0, h / 6.0 * (kth[0] + 2 * kth[1] + 2 * kth[2] + kth[3]));
  const Vec6 dxi = h / 6.0 * (kxi[0] + 2 * kxi[1] + 2 * kxi[2] + kxi[3]);
  s->v += dxi.head<3>();
  s->w += dxi.tail<3>();
  if (type.plan.basset && s->history) {
    // current interval of the history force, implicitly: (M + b P) xi = M xi* + b P xi_0
    const Mat3 R10 = s->q.toRotationMatrix().transpose() * q0.toRotationMatrix();
    const Vec3 v0 = R10 * (s->v - dxi.head<3>());
    Vec6 d = Vec6::Zero();
    d.head<3>() = type.basset.implicit_mass * (v0 - s->v);
    const Vec6 corr = type.basset.implicit_inv * d;
    s->v += corr.head<3>();
    s->w += corr.tail<3>();
  }
  return StepOutcome::Ok;
}

// The step's standardized Brownian increments (6: linear then angular), as sums over the
// model's noise_substeps finer increments, and for Strang splitting the two half-step
// increments: sums over each half when the substeps split evenly, else a Brownian bridge
// (W_mid - W_0)/sqrt(h/2) = (z + eta)/sqrt(2), (W_1 - W_mid)/sqrt(h/2) = (z - eta)/sqrt(2).
void brownian_increments(const Model& model, uint32_t body, uint64_t step, double whole[6],
                         double half1[6], double half2[6]) {
  const uint32_t r = model.noise_substeps;
  if (r <= 1) {
    double n[12];
    NormalStream(model.seed, body, step).normals(n);
    for (int c = 0; c < 6; ++c) {
      whole[c] = n[c];
      half1[c] = (n[c] + n[6 + c]) * M_SQRT1_2;
      half2[c] = (n[c] - n[6 + c]) * M_SQRT1_2;
    }
    return;
  }
  double a[6] = {0}, b[6] = {0};
  for (uint32_t j = 0; j < r; ++j) {
    double n[8];
    NormalStream(model.seed, body, uint64_t(step) * r + j).normals(n);
    double* acc = (r % 2 == 0 && j >= r / 2) ? b : a;
    for (int c = 0; c < 6; ++c) acc[c] += n[c];
  }
  for (int c = 0; c < 6; ++c) whole[c] = (a[c] + b[c]) / std::sqrt(double(r));
  if (r % 2 == 0) {
    for (int c = 0; c < 6; ++c) {
      half1[c] = a[c] / std::sqrt(0.5 * r);
      half2[c] = b[c] / std::sqrt(0.5 * r);
    }
  } else {
    double eta[8];
    NormalStream(model.seed, body, ~uint64_t(0) - 16 - step).normals(eta);
    for (int c = 0; c < 6; ++c) {
      half1[c] = (whole[c] + eta[c]) * M_SQRT1_2;
      half2[c] = (whole[c] - eta[c]) * M_SQRT1_2;
    }
  }
}

const char* first_nonfinite(const BodyState& s) {
  if (!s.x.allFinite()) return "position";
  if (!s.q.coeffs().allFinite()) return "orientation";
  if (!s.v.allFinite()) return "velocity";
  if (!s.w.allFinite()) return "angular velocity";
  if (!s.u_seen.allFinite()) return "seen turbulent velocity";
  return nullptr;
}

// The scheme's deterministic part over [t, t_end] (h = t_end - t up to rounding).
StepOutcome deterministic_part(const Model& model, const BodyType& type, double t, double t_end,
                               double h, BodyState* s) {
  switch (model.integrator) {
    case Integrator::Euler: return impulse_step(model, type, t, h, s);
    case Integrator::RK4: return rk4(model, type, t, h, s);
    case Integrator::Strang:
      // strang with the Basset history: the splitting step (its current interval is a
      // first-order implicit term, see the header)
      if (!type.plan.basset) return strang_deterministic_step(model, type, t, t_end, h, s);
      return split_deterministic_step(model, type, t, h, s);
    case Integrator::Splitting: break;
  }
  return split_deterministic_step(model, type, t, h, s);
}

// The deterministic part over the step [t, t_end], whole, or (at_split) in two parts with
// at_split called on the state at t + tau between them.
StepOutcome deterministic_pieces(const Model& model, const BodyType& type, double t,
                                 double t_end, double h, double tau, const SplitAt* at_split,
                                 BodyState* s) {
  if (!at_split) return deterministic_part(model, type, t, t_end, h, s);
  const StepOutcome out = deterministic_part(model, type, t, t + tau, tau, s);
  if (out != StepOutcome::Ok) return out;
  (*at_split)(t + tau, s);
  return deterministic_part(model, type, t + tau, t_end, h - tau, s);
}

StepOutcome step_impl(const Model& model, const BodyType& type, uint32_t body, uint64_t step,
                      double t, BodyState* s, std::string* reason, double tau,
                      const SplitAt* at_split) {
  const BodyState before = *s;
  const double h = model.dt;
  // the end of the step as the next step's start time (step + 1) dt, not t + h (which may
  // differ in the last bit): the sample there is the one the next step starts from
  const double t_end = static_cast<double>(step + 1) * h;
  const bool turb = uses_turbulence(model, type, TurbulenceModel::Seen) ||
                    uses_turbulence(model, type, TurbulenceModel::Body);
  double z[6], z1[6], z2[6];
  if (turb) brownian_increments(model, body, step, z, z1, z2);
  StepOutcome out = StepOutcome::Ok;
  switch (model.integrator) {
    case Integrator::Euler:
    case Integrator::RK4: {
      // the noise uses the state at the start of the step (Ito), one draw per step
      BodyState start = *s;
      out = deterministic_pieces(model, type, t, t_end, h, tau, at_split, s);
      if (out == StepOutcome::Ok && turb) {
        BodyState inc = start;
        out = turbulence_update(model, type, t, h, false, z, &inc);
        s->u_seen = inc.u_seen;
        if (model.turbulence_model == TurbulenceModel::Body) {
          // the body model's turbulent velocity moves the body directly (Ito: start value)
          s->x += h * start.u_seen;
          s->w += inc.w - start.w;
        }
      }
      break;
    }
    case Integrator::Splitting:
    case Integrator::Strang:
      if (turb) out = turbulence_update(model, type, t, 0.5 * h, true, z1, s);
      if (out == StepOutcome::Ok)
        out = deterministic_pieces(model, type, t, t_end, h, tau, at_split, s);
      // body model: the turbulent velocity at mid-step carries the body directly
      if (out == StepOutcome::Ok && turb && model.turbulence_model == TurbulenceModel::Body)
        s->x += h * s->u_seen;
      // the second half step's coefficients at the end of the step, (x1, t_end): symmetric with
      // the first's at (x0, t), and the sample the next step starts from (the batched steps take
      // it once for both)
      if (out == StepOutcome::Ok && turb)
        out = turbulence_update(model, type, t_end, 0.5 * h, true, z2, s);
      break;
  }
  // A step that ends outside the fluid exits the body at the start of the step, its last place
  // in the fluid, as a failing turbulence half step and the batched steps find it. The sample is
  // the one the next step starts from: the field's per-thread cache answers it again.
  if (out == StepOutcome::Ok && type.plan.sample_field && !model.field.is_uniform()) {
    FluidSample end;
    if (!sample_fluid(model, s->x, t_end, turb || type.plan.gradients, &end))
      out = StepOutcome::Exited;
  }
  // checked first: a state that went non-finite within the step also samples as "outside", and
  // it failed, not exited
  if (const char* what = first_nonfinite(*s)) {
    *s = before;
    *reason = std::string("non-finite ") + what;
    return StepOutcome::Failed;
  }
  if (out == StepOutcome::Exited) {
    *s = before;
    *reason = "left the fluid (outside the grid or inside a solid)";
    return out;
  }
  if (type.plan.basset && s->history) {
    // relative velocity g = u_f - v at the end of the step enters the history
    Vec3 uf = Vec3::Zero();
    FluidSample fs;
    if (type.plan.mean_flow && sample_fluid(model, s->x, t_end, false, &fs)) uf += fs.U;
    if (type.plan.seen) uf += s->u_seen;
    basset_push(type.basset, uf - s->q.toRotationMatrix() * s->v, h, s->history);
  }
  return StepOutcome::Ok;
}

}  // namespace

StepOutcome step_body(const Model& model, const BodyType& type, uint32_t body, uint64_t step,
                      double t, BodyState* s, std::string* reason) {
  return step_impl(model, type, body, step, t, s, reason, -1, nullptr);
}

StepOutcome step_body_split(const Model& model, const BodyType& type, uint32_t body,
                            uint64_t step, double t, double tau, const SplitAt& at_split,
                            BodyState* s, std::string* reason) {
  return step_impl(model, type, body, step, t, s, reason, tau, &at_split);
}

StepOutcome deterministic_substep(const Model& model, const BodyType& type, double t, double h,
                                  BodyState* s) {
  const BodyState before = *s;
  StepOutcome out = deterministic_part(model, type, t, t + h, h, s);
  FluidSample end;
  if (out == StepOutcome::Ok && type.plan.sample_field && !model.field.is_uniform() &&
      !sample_fluid(model, s->x, t + h, false, &end))
    out = StepOutcome::Exited;
  if (out == StepOutcome::Ok && first_nonfinite(*s)) out = StepOutcome::Failed;
  if (out != StepOutcome::Ok) *s = before;
  return out;
}

}  // namespace lrigid
