#include "effects/plate_cop.h"

#include <cmath>
#include <string>

#include "effects/added_mass.h"
#include "effects/lift.h"
#include "effects/plate.h"
#include "util/error.h"

namespace lrigid {

PlateCentreOfPressure plate_centre_of_pressure(const BodyType& type, double rho, double nu,
                                               double speed, double alpha, int in_plane_axis) {
  auto bad = [](const std::string& what) {
    throw Error(ExitCode::BadInput, "plate_centre_of_pressure: " + what);
  };
  if (!type.flat) bad("body type \"" + type.name + "\" is not flat");
  if (in_plane_axis < 0 || in_plane_axis > 2 || in_plane_axis == type.normal_axis)
    bad("in_plane_axis " + std::to_string(in_plane_axis) + " is not an in-plane body axis");
  if (!(alpha > 0 && alpha <= 0.5 * M_PI)) bad("alpha must be in (0, pi/2] rad");
  if (!(speed > 0) || !(rho > 0) || !(nu > 0)) bad("speed, rho and nu must be > 0");
  if (type.r_cob.norm() > 0)
    bad("body type \"" + type.name + "\" has a mass offset: its Kirchhoff tensor is about the " +
        "centre of mass, not the centroid the plate's forces act at");
  Vec3 n = Vec3::Zero(), e = Vec3::Zero();
  n[type.normal_axis] = 1.0;
  e[in_plane_axis] = 1.0;
  const Vec3 u = speed * (std::cos(alpha) * e + std::sin(alpha) * n);
  const Vec3 w = Vec3::Zero(), acc = Vec3::Zero();
  // the forces: the plate kernel's drag and translational lift at the centroid, as far as the
  // type simulates them
  const PlateParams k =
      plate_params(type, rho, nu, type.effects.has(Effect::Drag), type.effects.has(Effect::Lift));
  DragOut<double> d;
  Vec3 lift;
  plate_kernel<double>(k, u.data(), w.data(), &d, lift.data());
  const Vec3 force = Vec3(d.f[0], d.f[1], d.f[2]) + lift;
  // the moment: the Munk couple of the type's own Kirchhoff tensor, when the type simulates its
  // added mass (the plate kernel's torque is the damping of spin, zero here)
  double f[6] = {0, 0, 0, 0, 0, 0};
  if (type.effects.has(Effect::AddedMass))
    added_mass_kernel<false>(fluid_tensor(type), u.data(), w.data(), acc.data(), f);
  const Vec3 moment = Vec3(f[3], f[4], f[5]) + Vec3(d.tq[0], d.tq[1], d.tq[2]);
  PlateCentreOfPressure c;
  c.alpha = alpha;
  const double normal = force.dot(n);  // < 0: the fluid pushes against the motion
  c.normal_force = std::abs(normal);
  // a normal force N n at a distance x e from the centroid has the moment x N (e x n)
  c.ahead = normal != 0 ? moment.dot(e.cross(n)) / normal : 0.0;
  c.moment = c.ahead * c.normal_force;
  c.chord = plate_chord(type, e);
  c.from_leading_edge = (0.5 * c.chord - c.ahead) / c.chord;
  return c;
}

}  // namespace lrigid
