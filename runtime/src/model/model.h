// The constant model a run steps with (the mjModel of this project): body types with their
// generalized mass matrices and drag parameters, the fluid field and the options. Built once by
// compile_model(); never changed by the step. The body frame of every body type has its origin
// at the centre of mass and the axes of the shape.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "body/added_mass.h"
#include "fluid/field.h"
#include "model/scene.h"

namespace lrigid {

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
  Mat6 M = Mat6::Zero();         // what the step inverts: M_body (+ K_fluid with added_mass)
  Mat6 M_inv = Mat6::Zero();
  std::string added_mass_method;  // "analytic", "bem" or "" (not computed)
  int added_mass_panels = 0;
  // drag: the body's equivalent ellipsoid (semi-axes ell) gives its projected areas
  Vec3 ell = Vec3::Ones();       // m
  double area_max = 0;           // largest projected area, m^2
  double r_eq = 0;               // radius of the sphere of equal volume, m
  Vec3 rot_drag_len5 = Vec3::Zero();  // per body axis, integral r^3 dA of the swept body, m^5
  Vec3 half_extents = Vec3::Zero();   // of the shape's bounding box, m (ground contact)
  size_t first_body = 0, count = 0;   // bodies [first, first + count) are of this type
};

struct Model {
  std::string scene_file;
  double fluid_density = 1000;   // kg/m^3
  double nu = 1e-6;              // kinematic viscosity, m^2/s
  Vec3 gravity = Vec3(0, 0, -9.81);
  FluidField field;
  Integrator integrator = Integrator::Splitting;
  double dt = 1e-3;              // s
  double duration = 1;           // s
  uint64_t seed = 1;
  TurbulenceModel turbulence_model = TurbulenceModel::Seen;
  Drift drift = Drift::Stationary;
  bool has_ground = false;
  double ground_z = 0;           // m
  // Thomson's well-mixed drift for the seen model; off only to show what it prevents
  bool well_mixed_correction = true;
  // Brownian path resolution: each step's noise is the sum of this many finer increments, so a
  // run with dt = r h sees the same path as a run with dt = h and 1 (accuracy study, issue 8)
  uint32_t noise_substeps = 1;
  std::vector<BodyType> types;
  size_t body_count = 0;
  EffectSet union_effects() const;
};

using AddedMassProvider = std::function<AddedMass(const Shape&, double fluid_density, int panels)>;

// Effects chosen for "effects": "auto": a body type keeps an effect unless it is negligible
// (see docs/effects.md). `type` must have its mass properties and fluid tensor filled in.
// Returns the set and, per skipped effect, the reason.
EffectSet auto_effects(const Scene& scene, const BodyType& type,
                       std::vector<std::string>* reasons = nullptr);

// Throws lrigid::Error naming the scene file and key for physically impossible input.
Model compile_model(const Scene& scene, FluidField field, const AddedMassProvider& added_mass);

}  // namespace lrigid
