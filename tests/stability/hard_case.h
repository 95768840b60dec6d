// Shared machinery of the stability suite: run a model step by step and check, at
// every step, that the state is finite, |q| stays 1 to round-off, and the body's speed and
// kinetic energy stay under a bound derived from the case's physics (see Bound below).
#pragma once
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "effects/drag.h"
#include "effects/registry.h"
#include "integrate/simulation.h"
#include "support/fixture.h"

namespace lrigid::stability {

// The effects every case of the suite selects: a fixed set of six, not the registry's list
// (lift, Magnus and the Basset history are not in the cases; a new effect does not join them by
// itself).
inline EffectSet base_effects() {
  return test::effects({Effect::Gravity, Effect::Buoyancy, Effect::AddedMass, Effect::Drag,
                        Effect::MeanFlow, Effect::Turbulence});
}

// Physical speed bound of one body type.
//   v_T   terminal speed relative to the fluid under the net weight |m - rho_f V| g with the
//         smallest drag the drag law can give: C_D(Re) >= 0.43 (Schiller-Naumann's minimum)
//         and the edgewise coefficient C_s = 0.1 < C_D, so the drag is at least
//         1/2 rho_f C_s A_max |u|^2 in any orientation.
//   G     the largest velocity response of the body to a change of the fluid velocity (Tchen):
//         (rho_f V + K_ii) / (m + K_ii) over the translational axes (>= 1); a bubble follows
//         the fluid's accelerations up to 3 times (sphere), a weightless plate edgewise more.
//   speed |V - U| <= S (|U| + (G + 1) u'_max + v_T), S = 2 (safety): the body starts at rest in
//         the mean flow U, the fluctuation it sees is at most u'_max (measured), and it can
//         not exceed the fluid's motion amplified by G plus what gravity drives it to.
//   energy 1/2 xi_r^T M xi_r <= 1/2 lambda_max(M) speed^2 with xi_r the velocity relative to the
//         fluid (body frame, angular velocity included): rotation only gets energy from
//         translation (Munk moment) when the centre of mass is the centroid.
struct Bound {
  double v_T = 0;       // m/s
  double G = 1;         // -
  double lambda_max = 0;  // largest eigenvalue of M (kg or kg m^2)
  static constexpr double kSafety = 2;

  static Bound of(const Model& m, const BodyType& t) {
    Bound b;
    const double rho = m.fluid_density;
    const double weight = std::abs(t.mass - rho * t.volume) * m.gravity.norm();
    b.v_T = std::sqrt(2 * weight / (rho * kDragEdgewise * t.area_max));
    for (int i = 0; i < 3; ++i) {
      const double K = t.K_fluid(i, i);
      b.G = std::max(b.G, (rho * t.volume + K) / (t.mass + K));
    }
    Eigen::SelfAdjointEigenSolver<Mat6> es(0.5 * (t.M + t.M.transpose()));
    b.lambda_max = es.eigenvalues().maxCoeff();
    return b;
  }
  double speed(double U, double u_max) const { return kSafety * (U + (G + 1) * u_max + v_T); }
};

// What one run saw, for messages and statistics.
struct Observed {
  std::string failure;          // first violated check ("" if none)
  double max_speed = 0;         // max |V - U|, m/s
  double max_energy_ratio = 0;  // max of relative kinetic energy / its bound
  double max_u_seen = 0;        // max |u_seen|, m/s
  double max_q_err = 0;         // max ||q| - 1|
  double seen_var = 0;          // mean over steps and components of u_seen_i^2, m^2/s^2
  double body_var = 0;          // mean over steps and components of (V - U)_i^2, m^2/s^2
  size_t samples = 0;
  RunStats stats;
};

// Runs `model` from `state` observing every step (one thread), body 0 only for statistics.
// U: the mean flow at the body (uniform field).
inline Observed run_observed(const Model& model, State* state, const Vec3& U) {
  Observed o;
  const BodyType& type = model.types[0];
  const Bound b = Bound::of(model, type);
  RunOptions opt;
  opt.threads = 1;
  opt.every = model.dt;
  double seen2 = 0, body2 = 0;
  opt.on_output = [&](const State& s) {
    for (size_t i = 0; i < s.size(); ++i) {
      if (!o.failure.empty()) return;
      const bool finite = s.x[i].allFinite() && s.q[i].coeffs().allFinite() &&
                          s.v[i].allFinite() && s.w[i].allFinite() && s.u_seen[i].allFinite();
      std::ostringstream where;
      where << "body " << i << " at t = " << s.t << " s: ";
      if (!finite) {
        o.failure = where.str() + "non-finite state";
        return;
      }
      const double qerr = std::abs(s.q[i].norm() - 1);
      o.max_q_err = std::max(o.max_q_err, qerr);
      if (qerr >= 1e-12) {
        o.failure = where.str() + "||q| - 1| = " + std::to_string(qerr);
        return;
      }
      const Mat3 R = s.q[i].toRotationMatrix();
      const Vec3 V = R * s.v[i] - U;
      o.max_u_seen = std::max(o.max_u_seen, s.u_seen[i].norm());
      o.max_speed = std::max(o.max_speed, V.norm());
      const double vmax = b.speed(U.norm(), o.max_u_seen);
      if (V.norm() > vmax) {
        o.failure = where.str() + "speed relative to the mean flow " + std::to_string(V.norm()) +
                    " m/s > bound " + std::to_string(vmax) + " m/s";
        return;
      }
      Vec6 xi;
      xi << s.v[i] - R.transpose() * (U + s.u_seen[i]), s.w[i];
      const double e = 0.5 * xi.dot(type.M * xi);
      const double ebound = 0.5 * b.lambda_max * vmax * vmax;
      o.max_energy_ratio = std::max(o.max_energy_ratio, e / ebound);
      if (e > ebound) {
        o.failure = where.str() + "relative kinetic energy " + std::to_string(e) + " J > bound " +
                    std::to_string(ebound) + " J";
        return;
      }
      if (i == 0 && s.status[0] == BodyStatus::Moving) {
        seen2 += s.u_seen[0].squaredNorm() / 3;
        body2 += V.squaredNorm() / 3;
        ++o.samples;
      }
    }
  };
  o.stats = simulate(model, state, opt);
  if (o.samples > 0) {
    o.seen_var = seen2 / double(o.samples);
    o.body_var = body2 / double(o.samples);
  }
  return o;
}

// The fluid sample at the origin (uniform fields: everywhere).
inline FluidSample sample_at(const Model& m, const Vec3& x) {
  FluidSample fs;
  m.field.sample(x, 0, false, &fs);
  return fs;
}

}  // namespace lrigid::stability
