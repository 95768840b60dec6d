// The quasi-steady centre of pressure of a flat body (docs/physics/lift.md, "The centre
// of pressure"): where the plate's normal force would have to act to give the pitching moment the
// model gives a plate translating steadily through fluid at rest at angle of attack alpha. No new
// equation: the forces are the plate kernel's (effects/plate.h: drag and translational lift, both
// at the centroid) and the moment is the added-mass kernel's Munk couple (effects/added_mass.h,
// from the body type's own 3D Kirchhoff tensor), so the centre of pressure follows the planform's
// aspect ratio through its added mass and its drag and lift coefficients.
#pragma once
#include "model/model.h"

namespace lrigid {

struct PlateCentreOfPressure {
  double alpha = 0;         // angle between the velocity and the plate, rad
  double normal_force = 0;  // |normal component of drag + lift|, N
  double moment = 0;        // pitching moment about the centroid, turning the plate broadside, N m
  double ahead = 0;         // moment / normal force: distance of the centre of pressure ahead of
                            // the centroid along the motion's in-plane direction, m
  double chord = 0;         // the planform's chord along that direction, m
  double from_leading_edge = 0;  // (chord / 2 - ahead) / chord: 0 at the leading edge, 0.5 at the
                                 // centroid, < 0 ahead of the plate
};

// The centre of pressure of flat body type `type` moving at `speed` (m/s) relative to fluid of
// density rho (kg/m^3) and kinematic viscosity nu (m^2/s) at rest, along the in-plane body axis
// `in_plane_axis` (0, 1 or 2, not the normal) tilted by alpha (rad, 0 < alpha <= pi/2) towards the
// normal, without spin, with the effects the type simulates (without added_mass there is no Munk
// couple, and the centre of pressure is the centroid). Throws lrigid::Error if the type is not
// flat or has a mass offset (its Kirchhoff tensor is then about the centre of mass, not the
// centroid), the axis is the normal, or alpha, speed, rho or nu are out of range.
PlateCentreOfPressure plate_centre_of_pressure(const BodyType& type, double rho, double nu,
                                               double speed, double alpha, int in_plane_axis);

}  // namespace lrigid
