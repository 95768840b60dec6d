#include "effects/drag.h"

#include <algorithm>
#include <cmath>

#include "body/added_mass.h"
#include "effects/lift.h"

namespace lrigid {

double schiller_naumann(double re) {
  if (re >= 1000.0) return 0.44;
  return 24.0 / re * (1.0 + 0.15 * std::pow(re, 0.687));
}

Wrench drag_wrench(const BodyType& type, const Vec3& u_rel, const Vec3& w, double rho, double nu,
                   DragStiffness* stiffness) {
  // relative velocity of the volume centroid (where the drag acts)
  const Vec3 u = u_rel + w.cross(type.r_cob);
  const double speed = u.norm();
  Vec3 force = Vec3::Zero();
  double c_lin = 0, p = 0;
  Vec3 u_hat = Vec3::Zero();
  if (speed > 0) {
    u_hat = u / speed;
    const Vec3& l = type.ell;
    const double a_perp = M_PI * std::sqrt(std::pow(l.y() * l.z() * u_hat.x(), 2) +
                                           std::pow(l.x() * l.z() * u_hat.y(), 2) +
                                           std::pow(l.x() * l.y() * u_hat.z(), 2));
    const double d_perp = 2.0 * std::sqrt(a_perp / M_PI);
    const double re = speed * d_perp / nu;
    double cd;
    if (re >= 1000.0) {
      cd = 0.44;
      p = 1.0;
    } else {
      // C_D Re = 24 (1 + 0.15 Re^0.687): force ~ speed^(1+p)
      const double s = 0.15 * std::pow(re, 0.687);
      cd = 24.0 / re * (1.0 + s);
      p = 0.687 * s / (1.0 + s);
    }
    c_lin = 0.5 * rho * speed * (cd * a_perp + kDragEdgewise * (type.area_max - a_perp));
    force = -c_lin * u;
  }
  const double r_m = type.ell.mean();
  const double w_norm = w.norm();
  Vec3 torque = type.r_cob.cross(force);
  double c_ang = 8.0 * M_PI * rho * nu * r_m * r_m * r_m;
  for (int a = 0; a < 3; ++a) {
    const double c = c_ang + 0.5 * rho * kDragRotation * type.rot_drag_len5[a] * w_norm;
    torque[a] -= c * w[a];
  }
  if (stiffness) {
    stiffness->c_lin = c_lin;
    stiffness->p = p;
    stiffness->u_hat = u_hat;
    stiffness->c_ang = c_ang + rho * kDragRotation * type.rot_drag_len5.maxCoeff() * w_norm;
  }
  return make_wrench(force, torque);
}

void ellipsoid_stokes_resistance(const Vec3& s, Vec3* k, Vec3* r) {
  // Lamb's constants are s1 s2 s3 a_i
  const Vec3 a = ellipsoid_constants(s) / s.prod();
  const Vec3 s2 = s.cwiseProduct(s);
  const double chi = s2.dot(a);
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, l = (i + 2) % 3;
    (*k)[i] = 16.0 * M_PI / (chi + s2[i] * a[i]);
    (*r)[i] = 16.0 * M_PI * (s2[j] + s2[l]) / (3.0 * (s2[j] * a[j] + s2[l] * a[l]));
  }
}

Wrench plate_drag_wrench(const BodyType& type, const Vec3& u_rel, const Vec3& w, double rho,
                         double nu, DragStiffness* stiffness) {
  const Vec3 u = u_rel + w.cross(type.r_cob);
  const double speed = u.norm();
  const int na = type.normal_axis;
  const double S = type.plate_area;
  Vec3 force = Vec3::Zero();
  double c_lin = 0;
  if (speed > 0) {
    const double un = u[na];
    const double cos2a = (speed * speed - 2.0 * un * un) / (speed * speed);
    c_lin = 0.5 * rho * S * (kPlateDragA - kPlateDragB * cos2a) * speed;
    force = -c_lin * u;
  }
  // viscous (Stokes) part, linear in u
  const double mu = rho * nu;
  force -= mu * type.stokes_force.cwiseProduct(u);
  const double c_visc = mu * type.stokes_force.maxCoeff();
  Vec3 torque = type.r_cob.cross(force);
  // pitching (in-plane axes): APW's dissipative torque
  const Vec3 n = Vec3::Unit(na);
  const Vec3 wp = w - w[na] * n;
  const double wp_norm = wp.norm();
  double c_ang = 0;
  if (wp_norm > 0) {
    const double c = 0.5 * plate_chord(type, n.cross(wp) / wp_norm);
    const double span = S / (2.0 * c);
    const double U = type.apw_speed > 0 ? type.apw_speed : speed;
    const double k = M_PI * rho * std::pow(c, 4) * span;
    // APW's linear (viscous) damping, fitted at Re ~ 10^3, scaled as a laminar boundary layer
    const double re = std::max(speed * plate_width(type) / nu, kPlateTorqueReMin);
    const double mu1 = kPlateTorqueMu1 * std::sqrt(kPlateTorqueFitRe / re);
    torque -= k * (mu1 * U / c + kPlateTorqueMu2 * wp_norm) * wp;
    c_ang = k * (mu1 * U / c + 2.0 * kPlateTorqueMu2 * wp_norm);
  }
  // viscous (Stokes) torque about the in-plane axes
  torque -= mu * type.stokes_torque.cwiseProduct(wp);
  c_ang += mu * std::max(type.stokes_torque[(na + 1) % 3], type.stokes_torque[(na + 2) % 3]);
  // spin about the normal: Stokes torque plus out-of-roundness drag, as for any body
  const double c_n = mu * type.stokes_torque[na] +
                     0.5 * rho * kDragRotation * type.rot_drag_len5[na] * std::abs(w[na]);
  torque[na] -= c_n * w[na];
  if (stiffness) {
    // quadratic part c_lin (I + u^ u^T), viscous part c_visc I
    stiffness->c_lin = c_lin + c_visc;
    stiffness->p = c_lin + c_visc > 0 ? c_lin / (c_lin + c_visc) : 0.0;
    stiffness->u_hat = speed > 0 ? Vec3(u / speed) : Vec3::Zero();
    stiffness->c_ang = std::max(c_ang, 2.0 * c_n);
  }
  return make_wrench(force, torque);
}

}  // namespace lrigid
