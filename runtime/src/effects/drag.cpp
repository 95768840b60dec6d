#include "effects/drag.h"

#include <algorithm>
#include <cmath>

#include "body/added_mass.h"
#include "effects/plan.h"
#include "effects/plate.h"

namespace lrigid {

double schiller_naumann(double re) {
  if (re >= 1000.0) return 0.44;
  return 24.0 / re * (1.0 + 0.15 * std::pow(re, 0.687));
}

DragParams drag_params(const BodyType& type, double rho, double nu) {
  DragParams k;
  k.rho = rho;
  k.nu = nu;
  k.area_max = type.area_max;
  const double r_m = type.ell.mean();
  k.c_ang0 = 8.0 * M_PI * rho * nu * r_m * r_m * r_m;
  for (int a = 0; a < 3; ++a) k.rot[a] = 0.5 * rho * kDragRotation * type.rot_drag_len5[a];
  k.rot_max = rho * kDragRotation * type.rot_drag_len5.maxCoeff();
  const Vec3& l = type.ell;
  k.l12 = l[1] * l[2];
  k.l02 = l[0] * l[2];
  k.l01 = l[0] * l[1];
  return k;
}

namespace {

// a kernel's result as the wrench about the centre of mass (the force acts at the centroid,
// r_cob from it) and its stiffness
Wrench wrench_about_com(const BodyType& type, const DragOut<double>& d, DragStiffness* stiffness) {
  const Vec3 force(d.f[0], d.f[1], d.f[2]);
  if (stiffness) {
    stiffness->c_lin = d.c_lin;
    stiffness->p = d.p;
    stiffness->u_hat = Vec3(d.u_hat[0], d.u_hat[1], d.u_hat[2]);
    for (int a = 0; a < 3; ++a) stiffness->c_ang[a] = d.c_ang[a];
  }
  return wrench_at_centroid(type.r_cob, force, Vec3(d.tq[0], d.tq[1], d.tq[2]));
}

Wrench ellipsoid_drag(const BodyType& type, const DragParams& k, const Vec3& u_rel, const Vec3& w,
                      DragStiffness* stiffness) {
  // relative velocity of the volume centroid (where the drag acts)
  const Vec3 u = centroid_velocity(type.r_cob, u_rel, w);
  return wrench_about_com(type, ellipsoid_drag_kernel<ScalarMath>(k, u.data(), w.data()), stiffness);
}

Wrench plate_drag(const BodyType& type, const PlateParams& k, const Vec3& u_rel, const Vec3& w,
                  DragStiffness* stiffness) {
  const Vec3 u = centroid_velocity(type.r_cob, u_rel, w);
  DragOut<double> d;
  double lift[3];
  plate_kernel<double, true, false>(k, u.data(), w.data(), &d, lift);
  return wrench_about_com(type, d, stiffness);
}

}  // namespace

Wrench drag_wrench(const BodyType& type, const Vec3& u_rel, const Vec3& w, double rho, double nu,
                   DragStiffness* stiffness) {
  return ellipsoid_drag(type, drag_params(type, rho, nu), u_rel, w, stiffness);
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
  return plate_drag(type, plate_params(type, rho, nu, true, false), u_rel, w, stiffness);
}

Vec6 drag_term(const EffectContext& c) {
  return ellipsoid_drag(*c.type, c.type->plan.params->drag, c.v_rel, c.w, c.stiffness);
}

Vec6 plate_drag_term(const EffectContext& c) {
  return plate_drag(*c.type, c.type->plan.params->plate_drag, c.v_rel, c.w, c.stiffness);
}

}  // namespace lrigid
