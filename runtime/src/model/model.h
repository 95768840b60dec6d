// The constant model a run steps with (the mjModel of this project): body types with their
// generalized mass matrices and drag parameters, the fluid field and the options. Built once by
// compile_model() (compile/compile_model.h); never changed by the step. The body frame of every body type has its origin
// at the centre of mass and the axes of the shape.
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "body/added_mass.h"
#include "body/planform.h"
#include "fluid/field.h"
#include "fluid/solid_surface.h"
#include "model/scene.h"

namespace lrigid {

// The selected wrench terms of a body type, built once by compile_model (effects/plan.h): the
// step loops over these only, so an effect that is not selected costs nothing.
struct EffectContext;  // effects/context.h
struct EffectParams;   // effects/plan.h: the kernels' Params of the body type
struct ContactParams;  // contact/points.h: restitution, friction, the shape's contact points
struct PairShape;      // contact/pair_geometry.h: the convex shape of contacts between bodies
using WrenchTerm = Vec6 (*)(const EffectContext&);
struct EffectPlan {
  std::vector<WrenchTerm> terms;   // evaluation order of all_effects()
  std::vector<Effect> term_effect; // which effect each term belongs to
  bool sample_field = false;       // mean flow or turbulence: the field is sampled
  bool gradients = false;          // added mass in a mean flow: grad U and dU/dt are needed
  bool mean_flow = false;
  bool seen = false;               // seen turbulence moves the surrounding fluid
  bool basset = false;
  // the effect kernels' parameters (effects/plan.h), built once per body type with the plan:
  // the scalar step's terms and the batched loops read the same
  std::shared_ptr<const EffectParams> params;
};

// Basset history kernel of a body type (effects/basset.h), for the model's fixed dt.
struct BassetKernel {
  double coef = 0;                 // 6 a^2 rho sqrt(pi nu), a = r_eq, N s^0.5 / (m/s)
  int window = 0;                  // steps kept exactly
  std::vector<double> lambda;      // (modes) rates of the exponential-sum tail, 1/s
  std::vector<double> weight;      // (modes) s^-1/2 ~ sum weight_i exp(-lambda_i s), s^-1/2
  std::vector<double> window_w;    // (window) kernel integral over the interval of age m, s^0.5
  std::vector<double> decay;       // (modes) exp(-lambda_i dt)
  std::vector<double> inject;      // (modes) weight of an interval leaving the window, s^0.5
  double implicit_mass = 0;        // 2 coef sqrt(dt): current interval on the left-hand side, kg
  Mat6 implicit_inv = Mat6::Zero();  // (M + implicit P_lin)^-1 for the rk4 correction
  // doubles of one body's history (effects/basset.h): 4 per vector (3 and a pad)
  size_t stride() const { return 4 * (2 + size_t(window) + decay.size()) + 1; }
};

struct BodyType {
  std::string name;
  Shape shape;
  EffectSet effects;          // what this body type simulates
  double density = 0;         // kg/m^3
  double volume = 0;          // m^3
  double mass = 0;            // kg
  Vec3 centroid = Vec3::Zero();  // volume centroid in shape coordinates, m
  Vec3 com = Vec3::Zero();       // centre of mass in shape coordinates, m
  Vec3 r_cob = Vec3::Zero();     // centre of buoyancy minus centre of mass, body frame, m
  Mat6 M_body = Mat6::Zero();    // rigid-body generalized mass about the COM (kg, kg m^2)
  Mat6 K_fluid = Mat6::Zero();   // fluid Kirchhoff tensor about the COM
  // The share of its Munk couple a flat body's separated flow takes back (kg; zero unless
  // flat with added mass and drag): the couple is -v x (K_tt - munk_back) v
  // (compile/compile_model.cpp, docs/physics/lift.md "The Munk couple of a finite plate")
  Mat3 munk_back = Mat3::Zero();
  Mat6 M = Mat6::Zero();         // what the step inverts: M_body (+ K_fluid with added_mass)
  Mat6 M_inv = Mat6::Zero();
  // M is diagonal (boxes, ellipsoids, spheres with the centre of mass at the centroid): M^-1 is
  // applied as the element-wise product with M_inv_diagonal
  bool M_diagonal = false;
  Vec6 M_inv_diagonal = Vec6::Zero();
  // M = diag(m, m, m, J, J, J) to round-off (spheres): the free Kirchhoff flow is a rotation of
  // the impulse, integrated in closed form (integrate/dynamics.cpp)
  bool M_isotropic = false;
  // M^-1 y and M y, element-wise when M is diagonal
  Vec6 M_inv_times(const Vec6& y) const {
    return M_diagonal ? Vec6(M_inv_diagonal.cwiseProduct(y)) : Vec6(M_inv * y);
  }
  Vec6 M_times(const Vec6& y) const {
    return M_diagonal ? Vec6(M.diagonal().cwiseProduct(y)) : Vec6(M * y);
  }
  std::string added_mass_method;  // "analytic", "bem" or "" (not computed)
  int added_mass_panels = 0;
  // drag: the body's equivalent ellipsoid (semi-axes ell) gives its projected areas; a flat
  // mesh's in-plane semi-axes are its planform's ellipse's, along the planform's e1, e2 (its
  // outline's tightest rectangle's sides, which may be turned from the body axes)
  Vec3 ell = Vec3::Ones();       // m
  double area_max = 0;           // largest projected area, m^2
  double r_eq = 0;               // radius of the sphere of equal volume, m
  Vec3 rot_drag_len5 = Vec3::Zero();  // per body axis, integral r^3 dA of the swept body, m^5
  Vec3 half_extents = Vec3::Zero();   // of the shape's bounding box, m (ground contact)
  size_t first_body = 0, count = 0;   // bodies [first, first + count) are of this type
  size_t spec = 0;                    // index of the scene's body entry (variants share one)
  int variant = 0;                    // index among that entry's variants, 0 without "variation"
  // the first type whose bodies move as this type's (the same physics from another body entry,
  // one placed elsewhere: compile_model): the batched step takes their bodies in the same blocks
  uint16_t steps_as = 0;
  // flat bodies (thickness <= kFlatRatio x width of the equivalent ellipsoid): lift and the
  // Andersen-Pesavento-Wang drag and torque (effects/lift.h, effects/drag.h)
  bool flat = false;
  int normal_axis = 2;                // body axis normal to the plate
  double plate_area = 0;              // planform area, m^2
  // flat bodies: the outline seen along the normal, and the rectangle and ellipse of its area
  // that the plate model and the added mass weigh (body/planform.h)
  Planform planform;
  double apw_speed = 0;               // APW velocity scale sqrt(|rho_b/rho_f - 1| g b), m/s
  // the Stokes resistance of the ellipsoid ell, along its axes (a flat body's in-plane ones along
  // planform.e1, e2: effects/plate.cpp reads them in the plate's axes)
  Vec3 stokes_force = Vec3::Zero();   // Stokes drag F_i = -mu k_i u_i of the ellipsoid ell, m
  Vec3 stokes_torque = Vec3::Zero();  // Stokes torque T_i = -mu r_i w_i of the ellipsoid, m^3
  BassetKernel basset;
  EffectPlan plan;
  // contact (docs/contacts.md): the material and the shape's contact points (contact/points.h),
  // built once by compile_model; and the distance from the centre of mass to the farthest point
  // of the shape's bounding box, m: a body whose centre is farther than this from the ground
  // and from the walls cannot touch them (the one comparison bodies far from surfaces pay)
  std::shared_ptr<const ContactParams> contact;
  double reach = 0;
  // contacts between bodies (Model::body_contact): the convex shape the narrow phase takes
  // (contact/pair_geometry.h), built once by compile_model; null without body contacts
  std::shared_ptr<const PairShape> pair;
  // crossing trajectories of the seen model (effects/turbulence.h): the body's drift through the
  // fluid, its settling (or rising) velocity in still fluid under the weight and buoyancy it
  // simulates, as a unit direction (world) and a speed (m/s); zero for tracers, without the seen
  // model or with "crossing_trajectories": false
  Vec3 drift_dir = Vec3::Zero();
  double drift_speed = 0;
};

// thickness / width below which a body counts as flat
constexpr double kFlatRatio = 0.25;

struct Model {
  std::string scene_file;
  double fluid_density = 1000;   // kg/m^3
  double nu = 1e-6;              // kinematic viscosity, m^2/s
  Vec3 gravity = Vec3(0, 0, -9.81);
  FluidField field;
  Integrator integrator = kDefaultIntegrator;
  // body types take the batched step (integrate/rigid_batch.h) unless the scene says otherwise,
  // in double or single precision
  bool batched = true;
  Precision precision = Precision::Double;
  double dt = 1e-3;              // s
  double duration = 1;           // s
  uint64_t seed = 1;
  TurbulenceModel turbulence_model = TurbulenceModel::Seen;
  Drift drift = Drift::Stationary;
  bool has_ground = false;
  double ground_z = 0;           // m
  // how bodies meet the ground, the grid's solids and the grid's edge (docs/contacts.md). The
  // scene's defaults are collide and remove (compile_model copies them); a Model built by hand
  // keeps the seed's behaviour: stop at the ground and at solids, stay where the grid ends
  ContactMode ground_contact = ContactMode::Stop;
  ContactMode walls_contact = ContactMode::Stop;
  OutsideMode outside = OutsideMode::Stop;
  // resting (contact/pass.h): an impact slower than rest_speed does not bounce (m/s); a
  // body whose contact points all move slower than rest_speed rests, and one that rested for
  // sleep_time (s) sleeps: it is not stepped until the flow around it changes
  double rest_speed = 0.05;
  double sleep_time = 0.5;
  bool ground_collides() const { return has_ground && ground_contact == ContactMode::Collide; }
  // the grid's solids collide: walls.contact = "collide" and the grid has the wall distance
  bool walls_collide() const {
    return walls_contact == ContactMode::Collide && field.has_wall_distance();
  }
  bool contacts() const { return ground_collides() || walls_collide(); }
  // bodies collide with each other (scene key body_contact "collide"; contact/bodies.h): the
  // bodies are stepped together, one step at a time, and the pair contacts follow each step
  bool body_contact = false;
  // Thomson's well-mixed drift for the seen model; off only to show what it prevents
  bool well_mixed_correction = true;
  // crossing trajectories in the seen model (effects/turbulence.h): the drift of heavy and light
  // bodies shortens the time scale of the velocity they see (BodyType::drift_speed)
  bool crossing_trajectories = true;
  // Brownian path resolution: each step's noise is the sum of this many finer increments, so a
  // run with dt = r h sees the same path as a run with dt = h and 1 (docs/accuracy.md)
  uint32_t noise_substeps = 1;
  double mean_flow_scale = 1;    // art direction: U seen by the bodies is scaled by this
  double turbulence_scale = 1;   // art direction: u' seen by the bodies is scaled by this
  std::vector<BodyType> types;
  size_t body_count = 0;
  // (nbody, or empty when every body starts at t = 0) the step body i is released at
  // (bodies[i].release, model/release.h); before it the body waits, unstepped and hidden
  std::vector<uint64_t> release_step;
  // (scene entries) the sites of the solids' surface an entry spawns on (bodies[i].spawn);
  // empty for the other entries
  std::vector<std::vector<SurfaceSite>> spawn_sites;
  EffectSet union_effects() const;
};

// The fluid Kirchhoff tensor of a shape (body/added_mass.h), analytic or by BEM, as the app
// provides it (cached); compile_model (compile/compile_model.h) asks it once per body type.
using AddedMassProvider = std::function<AddedMass(const Shape&, double fluid_density, int panels)>;

}  // namespace lrigid
