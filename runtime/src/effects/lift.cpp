#include "effects/lift.h"

#include <algorithm>
#include <cmath>

#include "effects/plan.h"
#include "effects/plate.h"

namespace lrigid {

double plate_chord(const BodyType& type, const Vec3& d) {
  const Planform& p = type.planform;
  // the chord through the centre along d of the planform's rectangle and of its ellipse, both
  // along the planform's axes e1, e2
  const double d1 = p.e1.dot(d), d2 = p.e2.dot(d);
  const double rect = 2.0 * std::min(p.c1 / std::max(std::abs(d1), 1e-300),
                                     p.c2 / std::max(std::abs(d2), 1e-300));
  const double a = d1 / p.a1, b = d2 / p.a2;
  const double ell = 2.0 / std::sqrt(a * a + b * b);
  return p.w * rect + (1.0 - p.w) * ell;
}

double plate_width(const BodyType& type) {
  const Planform& p = type.planform;
  return p.w * 2.0 * std::min(p.c1, p.c2) + (1.0 - p.w) * 2.0 * std::min(p.a1, p.a2);
}

double circulation_factor(double re) { return circulation_gate(re); }

namespace {

Wrench plate_lift(const BodyType& type, const PlateParams& k, const Vec3& u_rel, const Vec3& w) {
  const Vec3 u = centroid_velocity(type.r_cob, u_rel, w);
  DragOut<double> d;
  double lift[3];
  plate_kernel<double, false, true>(k, u.data(), w.data(), &d, lift);
  return wrench_at_centroid(type.r_cob, Vec3(lift[0], lift[1], lift[2]));
}

}  // namespace

Wrench lift_wrench(const BodyType& type, const Vec3& u_rel, const Vec3& w, double rho, double nu) {
  return plate_lift(type, plate_params(type, rho, nu, false, true), u_rel, w);
}

Vec6 lift_term(const EffectContext& c) {
  return plate_lift(*c.type, c.type->plan.params->plate_lift, c.v_rel, c.w);
}

}  // namespace lrigid
