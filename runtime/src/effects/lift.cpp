#include "effects/lift.h"

#include <algorithm>
#include <cmath>

namespace lrigid {

double plate_chord(const BodyType& type, const Vec3& d) {
  const int i1 = (type.normal_axis + 1) % 3, i2 = (type.normal_axis + 2) % 3;
  if (type.shape.type == ShapeType::Box) {
    // rectangle: the chord through the centre along d
    const Vec3& h = type.half_extents;
    return 2.0 * std::min(h[i1] / std::max(std::abs(d[i1]), 1e-300),
                          h[i2] / std::max(std::abs(d[i2]), 1e-300));
  }
  const double a = d[i1] / type.ell[i1], b = d[i2] / type.ell[i2];
  return 2.0 / std::sqrt(a * a + b * b);
}

double plate_width(const BodyType& type) {
  const int i1 = (type.normal_axis + 1) % 3, i2 = (type.normal_axis + 2) % 3;
  const Vec3& h = type.shape.type == ShapeType::Box ? type.half_extents : type.ell;
  return 2.0 * std::min(h[i1], h[i2]);
}

double circulation_factor(double re) {
  const double x = std::pow(re / kLiftReCritical, kLiftReExponent);
  return x / (1.0 + x);
}

Wrench lift_wrench(const BodyType& type, const Vec3& u_rel, const Vec3& w, double rho,
                   double nu) {
  const Vec3 u = u_rel + w.cross(type.r_cob);
  const double speed = u.norm();
  if (!(speed > 0)) return Wrench::Zero();
  const Vec3 n = Vec3::Unit(type.normal_axis);
  const double un = u[type.normal_axis];
  const Vec3 ut = u - un * n;
  const double S = type.plate_area;
  const double gate = circulation_factor(speed * plate_width(type) / nu);
  if (!(gate > 0)) return Wrench::Zero();
  Vec3 f = -rho * gate * kLiftTranslational * S * (un / speed) * (ut.squaredNorm() * n - un * ut);
  const Vec3 wp = w - w[type.normal_axis] * n;
  const double wp_norm = wp.norm();
  if (wp_norm > 0) {
    const double chord = plate_chord(type, n.cross(wp) / wp_norm);
    f += 0.5 * rho * gate * kLiftRotational * chord * S * wp.cross(u);
  }
  return make_wrench(f, type.r_cob.cross(f));
}

}  // namespace lrigid
