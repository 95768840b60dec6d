#include "model/model.h"

#include <cmath>
#include <algorithm>

#include "body/mass_properties.h"
#include "util/error.h"

namespace lrigid {

const char* integrator_name(Integrator i) {
  switch (i) {
    case Integrator::Euler: return "euler";
    case Integrator::RK4: return "rk4";
    case Integrator::Splitting: return "splitting";
  }
  return "?";
}

const char* turbulence_model_name(TurbulenceModel m) {
  return m == TurbulenceModel::Body ? "body" : "seen";
}

const char* drift_name(Drift d) { return d == Drift::Original ? "original" : "stationary"; }

EffectSet Model::union_effects() const {
  EffectSet s;
  for (const auto& t : types) s.bits |= t.effects.bits;
  return s;
}

namespace {

// kinetic energy is invariant under a change of reference point: with xi_c = T xi,
// K_com = T^T K_c T, T = [[I, -[r]x], [0, I]], r = centroid - com
Mat6 shift_tensor(const Mat6& K_centroid, const Vec3& r) {
  Mat6 T = Mat6::Identity();
  T.block<3, 3>(0, 3) = -skew(r);
  return T.transpose() * K_centroid * T;
}

bool field_has_flow(const Scene& s) { return !s.uniform_field || s.uniform_U.norm() > 0; }
bool field_has_turbulence(const Scene& s) { return !s.uniform_field || s.uniform_k > 0; }

}  // namespace

EffectSet auto_effects(const Scene& scene, const BodyType& type,
                       std::vector<std::string>* reasons) {
  auto skip = [&](const std::string& why) {
    if (reasons) reasons->push_back(why);
  };
  EffectSet s;
  if (scene.gravity.norm() > 0) s.add(Effect::Gravity);
  else skip("gravity: the scene's gravity is zero");
  const double ratio = scene.fluid_density / type.density;
  if (ratio >= 1e-3) s.add(Effect::Buoyancy);
  else skip("buoyancy: rho_f/rho_b = " + std::to_string(ratio) + " < 1e-3");
  // largest added mass (any direction) relative to the body's mass
  const double am = type.K_fluid.block<3, 3>(0, 0).diagonal().maxCoeff() / type.mass;
  if (am >= 1e-2) s.add(Effect::AddedMass);
  else skip("added_mass: largest added mass / mass = " + std::to_string(am) + " < 1e-2");
  s.add(Effect::Drag);
  if (field_has_flow(scene)) s.add(Effect::MeanFlow);
  else skip("mean_flow: the uniform field has U = 0");
  if (field_has_turbulence(scene)) s.add(Effect::Turbulence);
  else skip("turbulence: the uniform field has k = 0");
  return s;
}

Model compile_model(const Scene& scene, FluidField field, const AddedMassProvider& added_mass) {
  Model m;
  m.scene_file = scene.file;
  m.fluid_density = scene.fluid_density;
  m.nu = scene.kinematic_viscosity;
  m.gravity = scene.gravity;
  m.field = std::move(field);
  m.integrator = scene.integrator;
  m.dt = scene.dt;
  m.duration = scene.duration;
  m.seed = scene.seed;
  m.turbulence_model = scene.turbulence_model;
  m.drift = scene.drift;
  m.has_ground = scene.has_ground;
  m.ground_z = scene.ground_z;

  size_t first = 0;
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodySpec& b = scene.bodies[i];
    const std::string key = "bodies[" + std::to_string(i) + "]";
    BodyType t;
    t.name = b.name;
    t.shape = b.shape;
    t.density = b.density;
    const MassProperties mp = mass_properties(b.shape);
    t.volume = mp.volume;
    t.mass = b.density * mp.volume;
    t.centroid = mp.centroid;
    t.com = mp.centroid + b.mass_offset;
    t.r_cob = -b.mass_offset;
    // inertia: the uniform body's inertia, taken about the (possibly offset) centre of mass
    t.M_body.setZero();
    t.M_body.block<3, 3>(0, 0) = t.mass * Mat3::Identity();
    t.M_body.block<3, 3>(3, 3) = b.density * mp.inertia;

    // equivalent ellipsoid for drag: exact for spheres/ellipsoids; boxes and meshes use their
    // bounding box scaled by sqrt(4/pi), so face areas match (pi l1 l2 = 4 h1 h2)
    const Vec3 h = b.shape.half_extents;
    t.half_extents = h;
    t.ell = (b.shape.type == ShapeType::Sphere || b.shape.type == ShapeType::Ellipsoid)
                ? h
                : Vec3(h * std::sqrt(4.0 / M_PI));
    Vec3 sorted = t.ell;
    std::sort(sorted.data(), sorted.data() + 3);
    t.area_max = M_PI * sorted[1] * sorted[2];
    t.r_eq = std::cbrt(3.0 * t.volume / (4.0 * M_PI));
    for (int a = 0; a < 3; ++a) {
      const double lj = t.ell[(a + 1) % 3], lk = t.ell[(a + 2) % 3];
      // rotation about axis a pushes fluid in proportion to the body's out-of-roundness
      t.rot_drag_len5[a] = t.ell[a] * std::abs(std::pow(lj, 4) - std::pow(lk, 4));
    }

    // the fluid tensor is computed for every body type: "auto" needs its size
    const AddedMass am = added_mass(b.shape, scene.fluid_density, b.panels);
    t.K_fluid = shift_tensor(am.tensor, t.centroid - t.com);
    t.added_mass_method = am.method;
    t.added_mass_panels = am.panels;

    t.effects = scene.effects_auto ? auto_effects(scene, t) : scene.effects;
    t.M = t.M_body;
    if (t.effects.has(Effect::AddedMass)) t.M += t.K_fluid;
    t.M = 0.5 * (t.M + t.M.transpose());
    Eigen::LDLT<Mat6> ldlt(t.M);
    if (ldlt.info() != Eigen::Success || !ldlt.isPositive() ||
        ldlt.vectorD().minCoeff() <= 0) {
      fail_input(scene.file, key, "generalized mass matrix is not positive definite");
    }
    t.M_inv = ldlt.solve(Mat6::Identity());
    t.first_body = first;
    t.count = size_t(b.count);
    first += t.count;
    m.types.push_back(std::move(t));
  }
  m.body_count = first;
  return m;
}

}  // namespace lrigid
