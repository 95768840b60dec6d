#include "effects/plate.h"

#include <algorithm>
#include <cmath>

namespace lrigid {

namespace {

// Broadside drag coefficient of rectangular plates against the side ratio (docs/physics/lift.md):
// 1.18 (square) ... 1.5 (20:1) after Hoerner (1965) as tabulated by White (Fluid Mechanics,
// Table 7.3); the infinite strip takes APW's 2D value A + B = 2.4 (Hoerner's steady
// strip: 1.98-2.0), so that long strips keep APW's model. Linear in 1 / aspect between the points.
constexpr double kCd90InvAspect[] = {1.0, 0.2, 0.1, 0.05, 0.0};
constexpr double kCd90Rect[] = {1.18, 1.2, 1.3, 1.5, kPlateDragA + kPlateDragB};
constexpr double kCd90Disk = 1.17;  // circular disk broadside (White Table 7.3; Hoerner)

}  // namespace

double plate_broadside_cd(double aspect, bool box) {
  const double x = 1.0 / std::max(aspect, 1.0);
  double cd = kCd90Rect[4];
  for (int i = 0; i < 4; ++i) {
    if (x <= kCd90InvAspect[i] && x >= kCd90InvAspect[i + 1]) {
      const double s = (x - kCd90InvAspect[i + 1]) / (kCd90InvAspect[i] - kCd90InvAspect[i + 1]);
      cd = kCd90Rect[i + 1] + s * (kCd90Rect[i] - kCd90Rect[i + 1]);
      break;
    }
  }
  // ellipses: the disk's value at aspect 1, the difference fading with 1 / aspect
  return box ? cd : cd + (kCd90Disk - kCd90Rect[0]) * x;
}

double plate_finite_span(double span_aspect) {
  const double ar = std::max(span_aspect, 0.0);
  return ar / (2.0 + std::sqrt(ar * ar + 4.0));
}

PlateCoeffs plate_coefficients(const BodyType& type) {
  PlateCoeffs c;
  // the planform (body/planform.h): w times the rectangle's coefficients and 1 - w times the
  // ellipse's, both of the outline's side ratio
  const Planform& p = type.planform;
  const double w = p.w;
  const double lo = std::min(p.h1, p.h2), hi = std::max(p.h1, p.h2);
  c.aspect = lo > 0 ? hi / lo : 1.0;
  c.cd90 = w * plate_broadside_cd(c.aspect, true) + (1.0 - w) * plate_broadside_cd(c.aspect, false);
  // APW's edgewise coefficient A - B is kept and the normal-force part 2 B scales to the
  // planform's broadside value (docs/physics/lift.md, "The 3D model").
  c.span_factor = (c.cd90 - (kPlateDragA - kPlateDragB)) / (2.0 * kPlateDragB);
  c.B = kPlateDragB * c.span_factor;
  c.A = (kPlateDragA - kPlateDragB) + c.B;
  // The pitch-rate terms, the rotational circulation C_R and the damping torque mu1, mu2, take
  // the finite wing's share of the 2D lift slope (Helmbold) at the planform's aspect ratio
  // span^2 / S: the rectangle's side ratio, 4/pi times an ellipse's axis ratio. The translational
  // circulation C_T stays APW's: its lift peaks at 45 degrees, where a low-aspect-ratio plate's
  // separated-flow lift is not reduced like its attached-flow slope (docs/physics/lift.md,
  // "Finite span: the pitch-rate terms").
  c.span_aspect = w * c.aspect + (1.0 - w) * (4.0 / M_PI * c.aspect);
  c.finite_span = plate_finite_span(c.span_aspect);
  c.C_R = kLiftRotational * c.finite_span;
  c.mu1 = kPlateTorqueMu1 * c.finite_span;
  c.mu2 = kPlateTorqueMu2 * c.finite_span;
  // The Munk couple of the plate's added mass takes the same share (BodyType::munk_back): the
  // 3D tensor's acyclic couple puts a square's centre of pressure at 0.16 of the chord from the
  // leading edge, where a plate in separated flow has it near 0.4 (docs/physics/lift.md, "The
  // Munk couple of a finite plate"); a long strip keeps APW's whole couple.
  c.munk = c.finite_span;
  return c;
}

PlateParams plate_params(const BodyType& type, double rho, double nu, bool drag, bool lift) {
  PlateParams k;
  k.rho = rho;
  k.nu = nu;
  const double mu = rho * nu;
  const int na = type.normal_axis, i1 = (na + 1) % 3, i2 = (na + 2) % 3;
  // the in-plane axes: the planform's (its tightest rectangle's sides, turned with a mesh's
  // outline; the body axes for a box or an ellipsoid)
  k.n[na] = 1.0;
  for (int a = 0; a < 3; ++a) {
    k.e1[a] = type.planform.e1[a];
    k.e2[a] = type.planform.e2[a];
  }
  k.S = type.plate_area;
  k.rect = type.planform.w;
  k.c1 = type.planform.c1;
  k.c2 = type.planform.c2;
  k.a1 = type.planform.a1;
  k.a2 = type.planform.a2;
  if (type.flat) k.width_over_nu = plate_width(type) / nu;
  k.apw_speed = type.apw_speed;
  // the equivalent ellipsoid's Stokes resistance, in the plate's axes (n, e1, e2)
  const int plate_axis[3] = {na, i1, i2};
  for (int a = 0; a < 3; ++a) {
    k.sf[a] = mu * type.stokes_force[plate_axis[a]];
    k.st[a] = mu * type.stokes_torque[plate_axis[a]];
  }
  k.c_visc = mu * type.stokes_force.maxCoeff();
  k.rot_n = 0.5 * rho * kDragRotation * type.rot_drag_len5[na];
  k.drag = drag ? 1.0 : 0.0;
  k.lift = lift ? 1.0 : 0.0;
  const PlateCoeffs c = plate_coefficients(type);
  k.drag_a = c.A;
  k.drag_b = c.B;
  k.lift_t = c.C_T;
  k.lift_r = c.C_R;
  k.mu1 = c.mu1;
  k.mu2 = c.mu2;
  return k;
}

}  // namespace lrigid
