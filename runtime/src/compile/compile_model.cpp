#include "compile/compile_model.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>

#include "body/mass_properties.h"
#include "contact/pair_geometry.h"
#include "contact/points.h"
#include "effects/basset.h"
#include "effects/drag.h"
#include "effects/plan.h"
#include "effects/plate.h"
#include "effects/registry.h"
#include "fluid/turbulence_coefficients.h"
#include "model/release.h"
#include "util/error.h"
#include "util/quantile.h"
#include "util/rng.h"
#include "util/rng_uniform.h"

namespace lrigid {

namespace {

// kinetic energy is invariant under a change of reference point: with xi_c = T xi,
// K_com = T^T K_c T, T = [[I, -[r]x], [0, I]], r = centroid - com
Mat6 shift_tensor(const Mat6& K_centroid, const Vec3& r) {
  Mat6 T = Mat6::Identity();
  T.block<3, 3>(0, 3) = -skew(r);
  return T.transpose() * K_centroid * T;
}

// drag force on the body at relative speed U (quasi-steady, broadside for flat bodies), N
double drag_force(const BodyType& t, double U, double rho, double nu) {
  if (!(U > 0)) return 0;
  if (t.flat) return 0.5 * rho * t.plate_area * plate_coefficients(t).cd90 * U * U;
  const double d = 2.0 * t.r_eq;
  return 0.5 * rho * schiller_naumann(U * d / nu) * M_PI * t.r_eq * t.r_eq * U * U;
}

// U with drag_force(U) = F (bisection in log U)
double speed_for_force(const BodyType& t, double F, double rho, double nu) {
  if (!(F > 0)) return 0;
  double lo = 1e-12, hi = 1e4;
  for (int i = 0; i < 200; ++i) {
    const double mid = std::sqrt(lo * hi);
    (drag_force(t, mid, rho, nu) < F ? lo : hi) = mid;
  }
  return std::sqrt(lo * hi);
}

Shape scaled_shape(const Shape& s, double f) {
  if (f == 1.0) return s;
  switch (s.type) {
    case ShapeType::Sphere: return Shape::sphere(f * s.half_extents.x());
    case ShapeType::Ellipsoid:
      return Shape::ellipsoid(f * s.half_extents.x(), f * s.half_extents.y(),
                              f * s.half_extents.z());
    case ShapeType::Box:
      return Shape::box(2 * f * s.half_extents.x(), 2 * f * s.half_extents.y(),
                        2 * f * s.half_extents.z());
    case ShapeType::Mesh: {
      auto m = std::make_shared<TriangleMesh>(*s.mesh);
      for (Vec3& v : m->vertices) v *= f;
      Shape r = Shape::from_mesh(std::move(m), s.source);
      r.scale = f * s.scale;
      r.thickness = f * s.thickness;
      return r;
    }
  }
  return s;
}

}  // namespace

FlowScales flow_scales(const Scene& scene, const FluidField& field) {
  FlowScales f;
  const double ms = scene.mean_flow_scale, ts2 = scene.turbulence_scale * scene.turbulence_scale;
  if (scene.uniform_field) {
    f.U = ms * scene.uniform_U.norm();
    f.k = ts2 * scene.uniform_k;
    f.eps = ts2 * scene.uniform_epsilon;
    f.source = "uniform field";
    return f;
  }
  // up to ~32^3 grid points of the first frame; k, eps recovered from the median sigma2, beta^2
  const GridGeometry& g = field.geometry();
  int stride[3];
  for (int a = 0; a < 3; ++a) stride[a] = std::max(1, (g.n[a] + 31) / 32);
  std::vector<double> U, s2, b2;
  const double t0 = field.times().empty() ? 0.0 : field.times().front();
  for (int i = 0; i < g.n[0]; i += stride[0])
    for (int j = 0; j < g.n[1]; j += stride[1])
      for (int k = 0; k < g.n[2]; k += stride[2]) {
        const Vec3 x = g.origin + Vec3(i * g.spacing.x(), j * g.spacing.y(), k * g.spacing.z());
        FluidSample s;
        if (!field.sample(x, t0, false, &s)) continue;
        U.push_back(s.U.norm());
        s2.push_back(s.sigma2);
        b2.push_back(s.beta * s.beta);
      }
  const double sigma2 = median(s2), beta2 = median(b2);
  double c0 = 6.5;
  for (int it = 0; it < 30 && sigma2 > 0; ++it) {
    f.k = scene.drift == Drift::Stationary ? 1.5 * sigma2 : sigma2 * (1 + 1.5 * c0) / c0;
    f.eps = beta2 / c0;
    c0 = std::max(1.0, c0_of_reynolds(taylor_reynolds(f.k, f.eps, scene.kinematic_viscosity)));
  }
  f.U = ms * median(U);
  f.k *= ts2;
  f.eps *= ts2;
  f.source = "grid: medians over " + std::to_string(U.size()) +
             " valid points of |U|, and k, eps from the median Langevin sigma2, beta^2";
  return f;
}

EffectAnalysis analyze_effects(const Scene& scene, const BodyType& t, const FlowScales& flow,
                               const BodySpec& spec) {
  EffectAnalysis a;
  const double rho = scene.fluid_density, nu = scene.kinematic_viscosity;
  const double g = scene.gravity.norm();
  const double W = t.mass * g, B = rho * t.volume * g;
  const double m_a = t.K_fluid.block<3, 3>(0, 0).diagonal().maxCoeff();
  const double m_eff = t.mass + t.K_fluid.block<3, 3>(0, 0).trace() / 3.0;
  Vec3 sorted = t.ell;
  std::sort(sorted.data(), sorted.data() + 3);
  a.density_ratio = rho / t.density;
  a.aspect_ratio = sorted[0] / sorted[2];
  a.size = t.flat ? 2.0 * sorted[1] : 2.0 * t.r_eq;
  a.terminal_speed = speed_for_force(t, std::abs(W - B), rho, nu);
  const double u_turb = std::sqrt(2.0 * flow.k / 3.0);
  const double T_flow = flow.k > 0 && flow.eps > 0 ? flow.k / flow.eps : 0;
  const double tau_eta = flow.eps > 0 ? std::sqrt(nu / flow.eps) : 0;
  // characteristic relative speed: settling plus the part of the turbulent velocity the body
  // does not follow (first-order filter of an exponentially correlated velocity)
  double U = std::max(a.terminal_speed, 1e-12), c = 0;
  for (int it = 0; it < 20; ++it) {
    const double Ue = std::max(U, 1e-9);
    c = drag_force(t, Ue, rho, nu) / Ue;
    a.tau_p = c > 0 ? m_eff / c : 0;
    const double st = T_flow > 0 ? a.tau_p / T_flow : 0;
    const double u_rel = u_turb * std::sqrt(st / (1.0 + st));
    U = std::sqrt(a.terminal_speed * a.terminal_speed + u_rel * u_rel);
  }
  a.speed = U;
  a.reynolds = U * a.size / nu;
  a.stokes_k_eps = T_flow > 0 ? a.tau_p / T_flow : 0;
  a.stokes_kolmogorov = tau_eta > 0 ? a.tau_p / tau_eta : 0;
  const double spin = spec.angular_velocity.norm() + std::max(spec.spin_min, spec.spin_max);
  a.spin_ratio = U > 0 ? t.r_eq * spin / U : 0;
  const double F_drag = c * U;
  // the quantities the registry's rules weigh (effects/registry.h AutoInputs)
  AutoInputs in;
  in.weight = W;
  in.buoyancy = B;
  in.F_ref = std::max({std::abs(W - B), F_drag, 1e-300});
  in.drag_per_speed = c;
  in.speed = U;
  in.mass = t.mass;
  in.added_mass_max = m_a;
  in.flow_U = flow.U;
  in.flow_k = flow.k;
  in.u_turb = u_turb;
  in.stokes_k_eps = a.stokes_k_eps;
  in.spin = spin;
  in.rho = rho;
  in.nu = nu;
  in.volume = t.volume;
  in.r_eq = t.r_eq;
  in.tau_p = a.tau_p;
  in.reynolds = a.reynolds;
  in.flat = t.flat;
  in.plate_area = t.plate_area;
  in.thickness_ratio = sorted[0] / sorted[1];
  for (const EffectInfo& info : all_effects()) {
    const AutoDecision d = info.rule(in);
    a.size_rel.emplace_back(info.effect, d.size);
    if (d.keep) a.chosen.add(info.effect);
    else a.skipped.emplace_back(info.effect, d.why_not);
  }
  return a;
}

EffectSet auto_effects(const Scene& scene, const BodyType& type, const FlowScales& flow,
                       const BodySpec& spec) {
  return analyze_effects(scene, type, flow, spec).chosen;
}

namespace {

// The axis of the equivalent ellipsoid's smallest semi-axis (the plate normal when flat), and
// whether the body is flat: that semi-axis is at most kFlatRatio of the middle one
bool flat_axis(const Vec3& ell, int* axis) {
  Vec3 s = ell;
  std::sort(s.data(), s.data() + 3);
  ell.minCoeff(axis);
  return s[0] <= kFlatRatio * s[1];
}

// A shape's equivalent ellipsoid (drag, flatness) and, when it is flat, its plate normal and
// planform (BodyType::ell, flat, normal_axis, planform)
struct Outline {
  Vec3 ell = Vec3::Ones();
  bool flat = false;
  int normal_axis = 2;
  Planform planform;
};

Outline outline_of(const Shape& shape) {
  // exact for spheres/ellipsoids; boxes and meshes use their bounding box scaled by sqrt(4/pi),
  // so face areas match (pi l1 l2 = 4 h1 h2); a flat mesh's in-plane axes then take its
  // outline's: its planform's ellipse, of the outline's area and its tightest rectangle's side
  // ratio, along that rectangle's sides e1, e2 (body/planform.h)
  Outline o;
  const Vec3 h = shape.half_extents;
  o.ell = (shape.type == ShapeType::Sphere || shape.type == ShapeType::Ellipsoid)
              ? h
              : Vec3(h * std::sqrt(4.0 / M_PI));
  int na = 0;
  Planform p;
  if (shape.type == ShapeType::Mesh && flat_axis(o.ell, &na)) {
    p = planform_of(shape, na);
    o.ell[(na + 1) % 3] = p.a1;
    o.ell[(na + 2) % 3] = p.a2;
  }
  o.flat = flat_axis(o.ell, &o.normal_axis);
  if (o.flat)
    o.planform = shape.type == ShapeType::Mesh && o.normal_axis == na
                     ? p
                     : planform_of(shape, o.normal_axis);
  return o;
}

// A flat body whose surfaces are planes: a box, an ellipsoid, or a mesh whose extent along its
// normal is at most 1.5 times its mean thickness (volume / planform area; a cut-out plate: 1). A
// curled leaf is not (a 4 mm sag on a 0.4 mm leaf: 11): its own panels give the coupling of
// the curl, which the planform's tensor has not.
bool planar(const Shape& shape, double volume, const Outline& o) {
  if (shape.type != ShapeType::Mesh) return true;
  const double thickness = o.planform.area > 0 ? volume / o.planform.area : 0.0;
  return 2.0 * shape.half_extents[o.normal_axis] <= 1.5 * thickness;
}

// The added mass of a flat body type: its planform's (body/planform.h), w times the rectangle's
// (a box of the planform's half sides and the shape's thickness, by the panel method) and 1 - w
// times the ellipse's (Lamb's ellipsoid of the planform's semi-axes and the equivalent
// ellipsoid's thickness), about the centroid: both in the planform's axes (e1, e2, n), then
// turned into the shape axes, K = T K' T^T with T = diag(Q, Q) and Q's columns e1, e2 and n in
// the places of the shape axes (normal_axis + 1, + 2, normal_axis). A box (w = 1) and an
// ellipsoid (w = 0) get their own tensors; a flat mesh the tensor of the shape of its planform,
// turned as its outline is, not the panel solution of its own triangles: a thin prism's few
// large triangles, split evenly, leave its edges unresolved (a square's normal added mass +8 % at
// 768 panels, +1 % at 3072, against the box's graded 1792; docs/physics/added-mass.md).
AddedMass planform_added_mass(const Shape& shape, const Outline& o, double rho, int panels,
                              const AddedMassProvider& added_mass) {
  const Planform& p = o.planform;
  const int na = o.normal_axis, i1 = (na + 1) % 3, i2 = (na + 2) % 3;
  AddedMass am, rect, ell;
  if (p.w > 0) {
    Vec3 size;
    size[na] = 2.0 * shape.half_extents[na];
    size[i1] = 2.0 * p.c1;
    size[i2] = 2.0 * p.c2;
    rect = added_mass(Shape::box(size[0], size[1], size[2]), rho, panels);
  }
  if (p.w < 1) {
    Vec3 semi;
    semi[na] = o.ell[na];
    semi[i1] = p.a1;
    semi[i2] = p.a2;
    ell = added_mass(Shape::ellipsoid(semi[0], semi[1], semi[2]), rho, panels);
  }
  if (p.w == 1) {
    am = rect;
  } else if (p.w == 0) {
    am = ell;
  } else {
    am = rect;
    am.tensor = p.w * rect.tensor + (1.0 - p.w) * ell.tensor;
    am.method = rect.method + "+" + ell.method;
  }
  // a planform along the shape axes (every box and ellipsoid) keeps its tensor as computed
  if (p.angle != 0) {
    Mat3 q = Mat3::Zero();
    q.col(i1) = p.e1;
    q.col(i2) = p.e2;
    q(na, na) = 1.0;
    Mat6 t = Mat6::Zero();
    t.block<3, 3>(0, 0) = q;
    t.block<3, 3>(3, 3) = q;
    am.tensor = (t * am.tensor * t.transpose()).eval();
  }
  return am;
}

// The fluid tensor of a body type of `shape` (volume: its volume), about its volume centroid in
// the shape axes: a flat body's whose surfaces are planes its planform's, any other its own
// (type_added_mass in compile_model.h)
TypeAddedMass added_mass_of(const Shape& shape, double volume, const Outline& o, double rho,
                            int panels, const AddedMassProvider& added_mass) {
  TypeAddedMass r;
  r.flat = o.flat;
  r.normal_axis = o.normal_axis;
  r.planform = o.planform;
  r.from_planform = o.flat && planar(shape, volume, o);
  r.added_mass = r.from_planform ? planform_added_mass(shape, o, rho, panels, added_mass)
                                 : added_mass(shape, rho, panels);
  return r;
}

}  // namespace

TypeAddedMass type_added_mass(const Shape& shape, double fluid_density, int panels,
                              const AddedMassProvider& added_mass) {
  return added_mass_of(shape, mass_properties(shape).volume, outline_of(shape), fluid_density,
                       panels, added_mass);
}

namespace {

BodyType make_body_type(const Scene& scene, const BodySpec& b, const Shape& shape,
                        double density, const FluidField& field, const FlowScales& flow,
                        const AddedMassProvider& added_mass, const std::string& key) {
  BodyType t;
  t.name = b.name;
  t.shape = shape;
  t.density = density;
  const MassProperties mp = mass_properties(shape);
  t.volume = mp.volume;
  t.mass = density * mp.volume;
  t.centroid = mp.centroid;
  t.com = mp.centroid + b.mass_offset;
  t.r_cob = -b.mass_offset;
  // inertia: the uniform body's inertia, taken about the (possibly offset) centre of mass
  t.M_body.setZero();
  t.M_body.block<3, 3>(0, 0) = t.mass * Mat3::Identity();
  t.M_body.block<3, 3>(3, 3) = density * mp.inertia;

  // the equivalent ellipsoid for drag and flatness, and a flat body's planform (outline_of): a
  // flat mesh's is its own outline (a disk's pi r^2, a leaf's), not its bounding box's 4 h1 h2
  const Outline outline = outline_of(shape);
  t.half_extents = shape.half_extents;
  t.ell = outline.ell;
  Vec3 sorted = t.ell;
  std::sort(sorted.data(), sorted.data() + 3);
  t.area_max = M_PI * sorted[1] * sorted[2];
  t.r_eq = std::cbrt(3.0 * t.volume / (4.0 * M_PI));
  for (int a = 0; a < 3; ++a) {
    const double lj = t.ell[(a + 1) % 3], lk = t.ell[(a + 2) % 3];
    // rotation about axis a pushes fluid in proportion to the body's out-of-roundness
    t.rot_drag_len5[a] = t.ell[a] * std::abs(std::pow(lj, 4) - std::pow(lk, 4));
  }
  t.flat = outline.flat;
  t.normal_axis = outline.normal_axis;
  t.plate_area = t.area_max;
  if (t.flat) t.planform = outline.planform;
  t.apw_speed =
      std::sqrt(std::abs(density / scene.fluid_density - 1.0) * scene.gravity.norm() * sorted[0]);
  if (t.flat) ellipsoid_stokes_resistance(t.ell, &t.stokes_force, &t.stokes_torque);

  // the fluid tensor is computed for every body type: "auto" needs its size
  AddedMass am;
  try {
    am = added_mass_of(shape, t.volume, outline, scene.fluid_density, b.panels, added_mass)
             .added_mass;
  } catch (const Error& e) {
    // named with the body type's key and the mesh file. The boundary elements find no
    // (positive) solution only for a surface they cannot solve: a fault of the input. Other
    // codes stay (a mesh of more panels than the dense solve takes is a resource limit)
    const bool mesh = shape.type == ShapeType::Mesh;
    const std::string at = where(scene.file, key + (mesh ? ".shape.file" : ".shape"),
                                 (mesh ? shape.source + ": " : std::string()) + e.what());
    throw Error(e.code() == ExitCode::Runtime ? ExitCode::BadInput : e.code(), at);
  }
  t.K_fluid = shift_tensor(am.tensor, t.centroid - t.com);
  // exactly symmetric, as M: the kernels read it in either order (effects/added_mass.h)
  t.K_fluid = 0.5 * (t.K_fluid + t.K_fluid.transpose()).eval();
  t.added_mass_method = am.method;
  t.added_mass_panels = am.panels;

  t.effects = scene.effects_auto ? auto_effects(scene, t, flow, b) : scene.effects;
  // A flat body's separated flow keeps only the share PlateCoeffs::munk of its added mass's Munk
  // couple (docs/physics/lift.md, "The Munk couple of a finite plate"): the plate model's, so
  // with its drag; in an ideal fluid (no drag) the Kirchhoff equations stay whole. The couple
  // -v x K_tt v comes from K_tt's anisotropic part, K_tt less its smallest eigenvalue.
  if (t.flat && t.effects.has(Effect::AddedMass) && t.effects.has(Effect::Drag)) {
    const Mat3 ktt = t.K_fluid.block<3, 3>(0, 0);
    const double lo =
        Eigen::SelfAdjointEigenSolver<Mat3>(ktt, Eigen::EigenvaluesOnly).eigenvalues().minCoeff();
    t.munk_back = (1.0 - plate_coefficients(t).munk) * (ktt - lo * Mat3::Identity());
  }
  t.M = t.M_body;
  if (t.effects.has(Effect::AddedMass)) t.M += t.K_fluid;
  t.M = 0.5 * (t.M + t.M.transpose());
  Eigen::LDLT<Mat6> ldlt(t.M);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive() || ldlt.vectorD().minCoeff() <= 0) {
    fail_input(scene.file, key, "generalized mass matrix is not positive definite");
  }
  t.M_inv = ldlt.solve(Mat6::Identity());
  t.M_inv = 0.5 * (t.M_inv + t.M_inv.transpose());  // exactly symmetric (model/kirchhoff.h)
  t.M_diagonal = Mat6(t.M.diagonal().asDiagonal()) == t.M;
  if (t.M_diagonal) t.M_inv_diagonal = t.M.diagonal().cwiseInverse();
  auto equal3 = [](const Vec3& d) {
    return (d.array() - d.mean()).abs().maxCoeff() <= 1e-13 * d.mean();
  };
  t.M_isotropic =
      t.M_diagonal && equal3(t.M.diagonal().head<3>()) && equal3(t.M.diagonal().tail<3>());
  if (t.effects.has(Effect::Basset)) {
    const double coef =
        6.0 * t.r_eq * t.r_eq * scene.fluid_density * std::sqrt(M_PI * scene.kinematic_viscosity);
    t.basset = make_basset_kernel(coef, scene.dt, kBassetWindow, scene.duration);
    Mat6 A = t.M;
    A.block<3, 3>(0, 0) += t.basset.implicit_mass * Mat3::Identity();
    t.basset.implicit_inv = A.inverse();
  }
  build_effect_plan(&t, scene.turbulence_model, scene.fluid_density, scene.kinematic_viscosity);
  // the drift of the crossing trajectories: the speed at which drag balances the weight and
  // buoyancy the type simulates, along their resultant
  if (scene.crossing_trajectories && scene.turbulence_model == TurbulenceModel::Seen &&
      t.effects.has(Effect::Turbulence)) {
    Vec3 F = Vec3::Zero();
    if (t.effects.has(Effect::Gravity)) F += t.mass * scene.gravity;
    if (t.effects.has(Effect::Buoyancy)) F -= scene.fluid_density * t.volume * scene.gravity;
    const double Fn = F.norm();
    if (Fn > 0) {
      t.drift_speed = speed_for_force(t, Fn, scene.fluid_density, scene.kinematic_viscosity);
      t.drift_dir = F / Fn;
    }
  }
  (void)field;
  return t;
}

}  // namespace

namespace {

// What of a body entry its type is made from (make_body_type, auto_effects, the contact's
// parameters): not its name, count, placement, start velocity or release. Two entries of equal
// keys give equal types.
std::string physics_key(const BodySpec& b) {
  std::string k;
  auto add = [&k](const void* p, size_t n) { k.append(static_cast<const char*>(p), n); };
  auto num = [&add](double x) { add(&x, sizeof x); };
  auto vec = [&num](const Vec3& v) { num(v.x()), num(v.y()), num(v.z()); };
  const Shape& s = b.shape;
  const int kind = static_cast<int>(s.type);
  add(&kind, sizeof kind);
  vec(s.half_extents);
  const void* mesh = s.mesh.get();
  add(&mesh, sizeof mesh);
  num(s.scale), num(s.thickness);
  add(&b.panels, sizeof b.panels);
  num(b.density);
  vec(b.mass_offset);
  vec(b.angular_velocity);
  num(b.spin_min), num(b.spin_max);
  num(b.size_min), num(b.size_max), num(b.density_min), num(b.density_max);
  add(&b.variants, sizeof b.variants);
  num(b.contact.restitution), num(b.contact.friction), num(b.contact.rolling_resistance);
  const bool given[3] = {b.restitution_given, b.friction_given, b.rolling_given};
  add(given, sizeof given);
  k += s.source;
  return k;
}

// BodyType::steps_as: each type of an entry without variants (one type) that another entry
// before it repeats, that entry's. A pile or a stack placed body by body, one entry each, then
// steps in blocks of kBatch instead of one body a block.
void share_steps(const Scene& scene, Model* m) {
  std::map<std::string, uint16_t> first;
  for (size_t t = 0; t < m->types.size(); ++t) {
    BodyType& type = m->types[t];
    type.steps_as = static_cast<uint16_t>(t);
    const BodySpec& b = scene.bodies[type.spec];
    if (b.variants > 1) continue;
    const auto [it, added] = first.emplace(physics_key(b), static_cast<uint16_t>(t));
    if (added) continue;
    const BodyType& u = m->types[it->second];
    // (the key holds what the type is made from: a difference here is a key too short)
    if (!(u.M == type.M && u.M_inv == type.M_inv && u.K_fluid == type.K_fluid &&
          u.effects == type.effects && u.contact->friction == type.contact->friction &&
          u.contact->restitution == type.contact->restitution && u.reach == type.reach))
      throw std::logic_error("body types of " + std::string("bodies[") + std::to_string(u.spec) +
                             "] and bodies[" + std::to_string(type.spec) +
                             "] share a key but differ");
    type.steps_as = it->second;
  }
}

}  // namespace

Model compile_model(const Scene& scene, FluidField field, const AddedMassProvider& added_mass) {
  Model m;
  m.scene_file = scene.file;
  m.fluid_density = scene.fluid_density;
  m.nu = scene.kinematic_viscosity;
  m.gravity = scene.gravity;
  m.integrator = scene.integrator;
  m.batched = scene.batched;
  m.precision = scene.precision;
  m.dt = scene.dt;
  m.duration = scene.duration;
  m.seed = scene.seed;
  m.turbulence_model = scene.turbulence_model;
  m.drift = scene.drift;
  m.crossing_trajectories = scene.crossing_trajectories;
  m.has_ground = scene.has_ground;
  m.ground_z = scene.ground_z;
  m.ground_contact = scene.ground_contact;
  m.walls_contact = scene.walls_contact;
  m.outside = scene.outside;
  m.body_contact = scene.body_contact;
  // an impact slower than what gravity adds in a few steps does not bounce (no jitter at rest)
  m.rest_speed = std::max(0.02, 4 * scene.gravity.norm() * scene.dt);
  m.mean_flow_scale = scene.mean_flow_scale;
  m.turbulence_scale = scene.turbulence_scale;
  const FlowScales flow = scene.effects_auto ? flow_scales(scene, field) : FlowScales();

  size_t first = 0;
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodySpec& b = scene.bodies[i];
    const std::string key = "bodies[" + std::to_string(i) + "]";
    const bool varied = b.variants > 1 && (b.size_max != b.size_min ||
                                           b.density_max != b.density_min);
    const int nv = varied ? std::min(b.variants, b.count) : 1;
    for (int j = 0; j < nv; ++j) {
      double f_size = b.size_min, f_rho = b.density_min;
      if (varied) {
        // variant j's factors, keyed by (seed, body entry, variant)
        double u[4];
        uniforms4(scene.seed, static_cast<uint32_t>(i), 0x76000000u + uint32_t(j), u);
        f_size = b.size_min + u[0] * (b.size_max - b.size_min);
        f_rho = b.density_min + u[1] * (b.density_max - b.density_min);
      }
      BodyType t = make_body_type(scene, b, scaled_shape(b.shape, f_size), f_rho * b.density,
                                  field, flow, added_mass, key);
      t.spec = i;
      t.variant = j;
      t.first_body = first;
      t.count = size_t(b.count / nv + (j < b.count % nv ? 1 : 0));
      first += t.count;
      m.types.push_back(std::move(t));
    }
  }
  if (m.types.size() > 65535) fail_input(scene.file, "bodies", "more than 65535 body variants");
  m.body_count = first;
  // release over time: body k of an entry counts from the entry's first body (its variants are
  // contiguous)
  bool any_release = false;
  for (const BodySpec& b : scene.bodies) any_release = any_release || b.released_over_time();
  if (any_release) {
    m.release_step.assign(m.body_count, 0);
    std::vector<size_t> entry_first(scene.bodies.size(), ~size_t(0));
    for (const BodyType& t : m.types)
      entry_first[t.spec] = std::min(entry_first[t.spec], t.first_body);
    for (const BodyType& t : m.types)
      for (size_t i = t.first_body; i < t.first_body + t.count; ++i)
        m.release_step[i] = first_step_at(
            release_time(scene.bodies[t.spec], static_cast<int>(i - entry_first[t.spec])), m.dt);
  }
  m.field = std::move(field);
  // the solids' surface an entry spawns on (fluid/solid_surface.h)
  m.spawn_sites.resize(scene.bodies.size());
  for (size_t e = 0; e < scene.bodies.size(); ++e) {
    const BodySpec& b = scene.bodies[e];
    if (!b.spawn_on_solids) continue;
    const std::string key = "bodies[" + std::to_string(e) + "].spawn";
    if (m.field.is_uniform())
      fail_input(scene.file, key, "spawns on the grid's solids, but the flow is uniform (no grid, "
                                  "no solids): give fluid.field or a spawn_box");
    const double inf = std::numeric_limits<double>::infinity();
    const Vec3 lo = b.spawn_surface_box ? b.box_lo : Vec3::Constant(-inf);
    const Vec3 hi = b.spawn_surface_box ? b.box_hi : Vec3::Constant(inf);
    m.spawn_sites[e] = solid_surface_sites(m.field, lo, hi);
    if (m.spawn_sites[e].empty()) {
      std::ostringstream msg;
      msg << "no surface of the grid's solids lies ";
      if (b.spawn_surface_box)
        msg << "in the box [[" << lo.x() << ", " << lo.y() << ", " << lo.z() << "], [" << hi.x()
            << ", " << hi.y() << ", " << hi.z() << "]] (m)";
      else
        msg << "in the grid: every point has flow";
      msg << "; lrigid info GRID lists the solids and their boxes";
      fail_input(scene.file, b.spawn_surface_box ? key + ".box" : key, msg.str());
    }
  }
  m.field.set_walls_collide(m.walls_contact == ContactMode::Collide);
  // a colliding ground at (or just below) the grid's bottom
  m.field.set_floor_clamp(m.ground_collides() && !m.field.is_uniform() &&
                          m.ground_z <= m.field.geometry().origin.z() + 1e-9);
  // the shapes' contact points: edge points of boxes at most half a grid cell apart (below that
  // the interpolated wall distance rounds a solid's corner off anyway)
  const double gap = m.field.is_uniform() ? 0.0 : 0.5 * m.field.geometry().spacing.minCoeff();
  for (BodyType& t : m.types) {
    const BodySpec& b = scene.bodies[t.spec];
    auto k = std::make_shared<ContactParams>(
        contact_params(t, b.contact.restitution, b.contact.friction, gap,
                       b.contact.rolling_resistance));
    k->rest_speed = m.rest_speed;
    t.contact = std::move(k);
    t.reach = t.half_extents.norm() + t.com.norm();
    if (m.body_contact) t.pair = pair_shape(t.shape, t.com);
  }
  share_steps(scene, &m);
  return m;
}

// the purposes of uniforms4 for a body's start: 1 its place in the spawn box, 2 its spin,
// 16 to 47 its draws on the solids' surface
constexpr uint32_t kSurfaceDraws = 16;

Vec3 initial_position(const Model& model, const BodySpec& spec, size_t entry, uint32_t id) {
  double u[4];
  if (spec.spawn_on_solids) {
    // a site of the solids' surface and a place on its face; drawn again (up to 32 times) where
    // the place is not in the fluid (a solid beyond the offset, a corner the interpolation
    // takes as outside), else the site's fluid point itself
    const std::vector<SurfaceSite>& sites = model.spawn_sites[entry];
    const GridGeometry& g = model.field.geometry();
    auto site = [&]() -> const SurfaceSite& {
      return sites[std::min(sites.size() - 1, size_t(u[0] * double(sites.size())))];
    };
    FluidSample fs;
    for (uint32_t draw = 0; draw < 32; ++draw) {
      uniforms4(model.seed, id, kSurfaceDraws + draw, u);
      const Vec3 x = surface_site_position(g, site(), spec.spawn_offset, u[1], u[2]);
      if (model.field.sample(x, 0.0, false, &fs)) return x;
    }
    return surface_site_position(g, site(), 0.5 * g.spacing[site().axis], 0.5, 0.5);
  }
  if (!spec.spawn_in_box) return spec.position;
  uniforms4(model.seed, id, 1, u);
  Vec3 x;
  for (int a = 0; a < 3; ++a) x[a] = spec.box_lo[a] + u[a] * (spec.box_hi[a] - spec.box_lo[a]);
  return x;
}

State initial_state(const Model& model, const Scene& scene) {
  State s;
  const size_t n = model.body_count;
  s.x.resize(n);
  s.q.resize(n);
  s.v.resize(n);
  s.w.resize(n);
  s.u_seen.assign(n, Vec3::Zero());
  s.type.resize(n);
  s.status.assign(n, BodyStatus::Moving);
  s.t_stop.assign(n, 0.0);
  s.reason.assign(n, std::string());
  s.contact.assign(n, ContactState::Flying);
  s.rest_steps.assign(n, 0);
  s.impacts.assign(n, 0);
  s.t_touch.assign(n, std::nan(""));
  s.x_touch.assign(n, Vec3::Zero());
  s.hidden.assign(n, 0);
  // the sleeping bodies' gust watches: only where bodies can come to rest on a surface
  s.watch.assign(model.contacts() ? n : 0, GustWatch{});
  s.history_offset.assign(n, State::kNoHistory);
  size_t hist = 0;
  for (const BodyType& type : model.types)
    if (type.plan.basset) hist += type.count * type.basset.stride();
  s.history.assign(hist, 0.0);
  hist = 0;
  for (size_t ti = 0; ti < model.types.size(); ++ti) {
    const BodyType& type = model.types[ti];
    const BodySpec& spec = scene.bodies[type.spec];
    for (size_t i = type.first_body; i < type.first_body + type.count; ++i) {
      const uint32_t id = static_cast<uint32_t>(i);
      s.type[i] = static_cast<uint16_t>(ti);
      if (!model.release_step.empty() && model.release_step[i] > 0) {
        s.status[i] = BodyStatus::Unreleased;  // simulate() releases it (model/release.h)
        s.hidden[i] = 1;
      }
      s.x[i] = initial_position(model, spec, type.spec, id);
      if (spec.random_orientation) {
        // uniform on SO(3): a normalized 4D Gaussian (Shoemake's method is equivalent)
        NormalStream ns(model.seed, id, ~uint64_t(0));
        double z[4];
        ns.normals(z);
        s.q[i] = Quat(z[0], z[1], z[2], z[3]).normalized();
      } else {
        s.q[i] = spec.orientation.normalized();
      }
      const Mat3 Rt = s.q[i].toRotationMatrix().transpose();
      s.v[i] = Rt * spec.velocity;
      s.w[i] = Rt * spec.angular_velocity;
      if (spec.spin_max > 0) {
        // art direction: spin of a uniformly drawn magnitude about a uniformly random axis
        double u[4];
        uniforms4(model.seed, id, 2, u);
        NormalStream ns(model.seed, id, ~uint64_t(2));
        double z[4];
        ns.normals(z);
        const Vec3 axis = Vec3(z[0], z[1], z[2]).normalized();
        s.w[i] += (spec.spin_min + u[0] * (spec.spin_max - spec.spin_min)) * axis;
      }
      // seen model: the fluid's fluctuation starts stationary; body model: the body starts with
      // exactly the scene's velocity (its turbulent velocity starts at 0)
      if (type.effects.has(Effect::Turbulence) &&
          model.turbulence_model == TurbulenceModel::Seen) {
        FluidSample fs;
        if (model.field.sample(s.x[i], 0.0, false, &fs)) {
          NormalStream ns(model.seed, id, ~uint64_t(1));
          double z[4];
          ns.normals(z);
          s.u_seen[i] = model.turbulence_scale * std::sqrt(fs.sigma2) * Vec3(z[0], z[1], z[2]);
        }
      }
      if (type.plan.basset) {
        // the history starts from the relative velocity at t = 0 (no initial-jump term)
        s.history_offset[i] = hist;
        hist += type.basset.stride();
        Vec3 uf = Vec3::Zero();
        FluidSample fs;
        if (type.plan.mean_flow && model.field.sample(s.x[i], 0.0, false, &fs))
          uf += model.mean_flow_scale * fs.U;
        if (type.plan.seen) uf += s.u_seen[i];
        basset_reset(type.basset, uf - s.q[i].toRotationMatrix() * s.v[i], s.history_of(i));
      }
    }
  }
  return s;
}

}  // namespace lrigid
