// Lift of flat bodies: the quasi-steady circulation model of Andersen, Pesavento & Wang
// (JFM 541, 2005, "Analysis of transitions between fluttering, tumbling and steady descent of
// falling cards"), generalized to 3D (docs/physics/lift.md). Per unit span APW write the
// circulation Gamma = -C_T l v_x v_y / |v| + 1/2 C_R l^2 w and the lift rho Gamma z x v. In 3D,
// with n the plate normal, u the velocity of the centroid relative to the fluid, u_n = u . n,
// u_t = u - u_n n, w_p the in-plane part of the angular velocity, S the planform area and l(s)
// the chords across w_p:
//   translational  F = -rho C_T S (u_n / |u|) (|u_t|^2 n - u_n u_t)   (normal to u, in span(u, n))
//   rotational     F = 1/2 rho C_R K_R  w_p x u,  K_R = int l(s)^2 ds (l S for a strip;
//                  plate_strips, effects/plate.h)
// Both act at the centroid and fade below Re ~ 200 (circulation_factor). The added-mass (Munk)
// torque and the plate drag and dissipative torque (effects/drag.h) complete APW's model. Only
// for flat bodies (BodyType::flat).
#pragma once
#include "effects/wrench.h"
#include "model/model.h"

namespace lrigid {

constexpr double kLiftTranslational = 1.2;  // C_T, APW 2005 (fit to experiments and DNS)
constexpr double kLiftRotational = M_PI;    // C_R, APW 2005 (2D; a plate's: PlateCoeffs)
// The circulation (both terms) is scaled by f(Re) = x / (1 + x), x = (Re / Re_c)^n, Re = |u| w / nu
// (w: planform width): APW's circulation comes from separated, shedding flow at Re ~ 10^3; below
// the wake instability the flow stays steady and plates descend steadily (Field et al. 1997:
// steady below Re ~ 100, by the mean descent speed). Re_c and n are calibrated so that the steady
// boundary of validation/falling_plates, measured with the mean descent speed as Field et al.
// do, lies near Re = 100 (docs/physics/lift.md): f(100) = 0.06, f(200) = 0.5, f(400) = 0.94.
constexpr double kLiftReCritical = 200.0;
constexpr int kLiftReExponent = 4;

// chord through the centre of the planform (body/planform.h: w x its rectangle's + (1 - w) x its
// ellipse's) along the in-plane unit direction d, m
double plate_chord(const BodyType& type, const Vec3& d);

// width of the planform (the smallest in-plane extent of its rectangle and of its ellipse, weighted
// as the chord: a disk's diameter), m
double plate_width(const BodyType& type);

// share of APW's circulation present at Re = |u| width / nu (0 ... 1): effects/plate.h
// circulation_gate
double circulation_factor(double re);

// The scalar step's wrapper of effects/plate.h plate_kernel (the lift alone, the centre of
// buoyancy anywhere). u_rel: velocity of the centre of mass relative to the fluid, w: angular
// velocity (body frame), rho: fluid density (kg/m^3), nu: kinematic viscosity (m^2/s)
Wrench lift_wrench(const BodyType& type, const Vec3& u_rel, const Vec3& w, double rho, double nu);

// the scalar step's term (the registry's row: flat bodies only), on the body type's cached
// kernel parameters (effects/plan.h)
struct EffectContext;
Vec6 lift_term(const EffectContext& c);

}  // namespace lrigid
