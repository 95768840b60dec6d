#include "effects/plate.h"

#include <algorithm>

namespace lrigid {

PlateParams plate_params(const BodyType& type, double rho, double nu, bool drag, bool lift) {
  PlateParams k;
  k.rho = rho;
  k.nu = nu;
  const double mu = rho * nu;
  const int na = type.normal_axis, i1 = (na + 1) % 3, i2 = (na + 2) % 3;
  k.n[na] = k.e1[i1] = k.e2[i2] = 1.0;
  k.S = type.plate_area;
  k.box = type.shape.type == ShapeType::Box ? 1.0 : 0.0;
  const Vec3& ext = type.shape.type == ShapeType::Box ? type.half_extents : type.ell;
  k.c1 = ext[i1];
  k.c2 = ext[i2];
  if (type.flat) k.width_over_nu = plate_width(type) / nu;
  k.apw_speed = type.apw_speed;
  for (int a = 0; a < 3; ++a) {
    k.sf[a] = mu * type.stokes_force[a];
    k.st[a] = mu * type.stokes_torque[a];
  }
  k.c_visc = mu * type.stokes_force.maxCoeff();
  k.st_in = mu * std::max(type.stokes_torque[i1], type.stokes_torque[i2]);
  k.rot_n = 0.5 * rho * kDragRotation * type.rot_drag_len5[na];
  k.drag = drag ? 1.0 : 0.0;
  k.lift = lift ? 1.0 : 0.0;
  return k;
}

}  // namespace lrigid
