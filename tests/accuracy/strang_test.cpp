// The Strang scheme (integrator "strang", docs/physics/integrators.md): its measured
// orders on smooth cases (turbulence off, no ground, no kinks in the forces along the path),
// against rk4 at a tiny step, and the weak order of its noise part.
//   deterministic: order 2 (splitting: 1) on a sinking sphere, a tumbling ellipsoid with added
//   mass, a falling plate with lift in a uniform wind, a sphere in a smooth non-uniform field;
//   noise: exact in distribution for the OU part alone (the variance of u' at any dt), weak order
//   2 measured for the position variance of the coupled system.
// Slopes are least-squares fits of log(error) against log(dt) over halvings of dt.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "compile/compile_model.h"
#include "integrate/simulation.h"
#include "accuracy/cases.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

using test::effects;
using accuracy::sinking_sphere;
using accuracy::tumbling_ellipsoid;

struct FinalState {
  std::vector<Vec3> x;  // final positions, m
  std::vector<Vec3> v;  // final body-frame velocities, m/s
  std::vector<Vec3> u;  // final seen turbulent velocities, m/s
};

FinalState run(const Scene& scene, const FluidField& field, Integrator integ, double dt) {
  Scene s = scene;
  s.integrator = integ;
  s.dt = dt;
  Model m = test::compile(s, field);
  State st = initial_state(m, s);
  RunOptions opt;
  opt.every = s.duration;
  opt.threads = 1;
  const RunStats stats = simulate(m, &st, opt);
  EXPECT_EQ(stats.failed, 0u);
  for (size_t i = 0; i < st.size(); ++i) EXPECT_EQ(st.status[i], BodyStatus::Moving) << i;
  return {st.x, st.v, st.u_seen};
}

FluidField uniform_field(const Scene& s) {
  return FluidField::uniform(s.uniform_U, s.uniform_k, s.uniform_epsilon, s.kinematic_viscosity,
                             s.drift);
}

double strang_rms_diff(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double s = 0;
  for (size_t i = 0; i < a.size(); ++i) s += (a[i] - b[i]).squaredNorm();
  return std::sqrt(s / double(a.size()));
}

double strang_log_log_slope(const std::vector<double>& dt, const std::vector<double>& err) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = double(dt.size());
  for (size_t i = 0; i < dt.size(); ++i) {
    const double x = std::log(dt[i]), y = std::log(err[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// slope of the final-position error against rk4 at dt_ref; also prints the errors
double slope(const Scene& s, const FluidField& f, Integrator integ, const std::vector<double>& dts,
             double dt_ref, const char* label, std::vector<double>* errors = nullptr) {
  const FinalState ref = run(s, f, Integrator::RK4, dt_ref);
  std::vector<double> err;
  for (double dt : dts) {
    err.push_back(strang_rms_diff(run(s, f, integ, dt).x, ref.x));
    std::printf("%s %s dt %.3g s: error %.3e m\n", label, integrator_name(integ), dt, err.back());
  }
  const double p = strang_log_log_slope(dts, err);
  std::printf("%s %s: slope %.2f\n", label, integrator_name(integ), p);
  if (errors) *errors = err;
  return p;
}

// a leaf (6 x 4 x 0.04 cm box, 600 kg/m^3) in a uniform 2 m/s wind, tilted, with plate drag,
// lift and added mass: the case where splitting's error constant is large. Short
// enough that it neither tumbles through an edgewise flow nor turns its relative velocity
// through zero (the plate law's non-smooth points).
Scene leaf_in_wind() {
  Scene s = test::sphere_scene(0.01, 600, 1.2, 1.5e-5, 1);
  s.bodies[0].shape = Shape::box(0.06, 0.04, 4e-4);
  s.bodies[0].orientation = Quat(Eigen::AngleAxisd(0.5, Vec3(1, 0.4, 0).normalized()));
  s.bodies[0].velocity = Vec3(0.0, 0.0, -0.2);
  s.bodies[0].angular_velocity = Vec3(0.3, -0.2, 0.1);
  s.uniform_U = Vec3(2.0, 0.5, 0.0);
  s.effects = effects({Effect::Gravity, Effect::Buoyancy, Effect::Drag, Effect::Lift,
                       Effect::AddedMass, Effect::MeanFlow});
  s.duration = 0.05;
  return s;
}

TEST(Strang, SecondOrderOnASinkingSphere) {
  const Scene s = sinking_sphere();
  const std::vector<double> dts = {2e-3, 1e-3, 5e-4, 2.5e-4};
  EXPECT_GE(slope(s, uniform_field(s), Integrator::Strang, dts, 1e-5, "sphere"), 1.8);
}

TEST(Strang, SecondOrderOnATumblingEllipsoid) {
  const Scene s = tumbling_ellipsoid();
  const std::vector<double> dts = {4e-3, 2e-3, 1e-3, 5e-4};
  EXPECT_GE(slope(s, uniform_field(s), Integrator::Strang, dts, 5e-5, "ellipsoid"), 1.8);
}

TEST(Strang, SecondOrderOnALeafWithLiftInAUniformWind) {
  const Scene s = leaf_in_wind();
  const FluidField f = uniform_field(s);
  const std::vector<double> dts = {1e-3, 5e-4, 2.5e-4, 1.25e-4};
  std::vector<double> e_strang, e_split;
  EXPECT_GE(slope(s, f, Integrator::Strang, dts, 1e-6, "leaf", &e_strang), 1.8);
  // splitting on the same case: first order, and strang far more accurate at each step
  EXPECT_NEAR(slope(s, f, Integrator::Splitting, dts, 1e-6, "leaf", &e_split), 1.0, 0.3);
  for (size_t i = 0; i < dts.size(); ++i) EXPECT_LT(e_strang[i], 0.2 * e_split[i]) << dts[i];
}

// the falling-plate study's 2D limit (validation/falling_plates, limit_strip_scene): an elliptic
// strip of half chord 1 cm and side ratio 1000 in water at APW's mass ratio 1.1 and Reynolds
// number 10^3, released from rest at 10° pitch, over its first swing (3 a/U). Its damping about
// the plate's normal (the Stokes torque of a 20 m long body spinning flat) is about 10^5 times
// its pitch damping: with one angular stiffness for all three axes (the largest) the implicit
// force step would damp the pitch by that: strang at 0.2 ms pitched 41° where rk4 pitches 22°,
// and its end point was 1.25, 1.14, 0.96, 0.72 mm off rk4's at 0.4, 0.2, 0.1, 0.05 ms (a slope
// of 0.25); with one stiffness per axis it is second order.
Scene long_strip() {
  const double a = 0.01, rho_s = 11000, rho_f = 1000, mass_ratio = 1.1;
  const double b = mass_ratio * a * rho_f / rho_s;
  const double U = std::sqrt((rho_s / rho_f - 1) * 9.81 * b);
  Scene s = test::sphere_scene(0.01, rho_s, rho_f, U * 2 * a / 1000.0, 1);
  s.bodies[0].shape = Shape::ellipsoid(a, 1000 * a, b);
  s.bodies[0].orientation = Quat(Eigen::AngleAxisd(0.1745, Vec3::UnitY()));
  s.effects = effects({Effect::Gravity, Effect::Buoyancy, Effect::Drag, Effect::Lift,
                       Effect::AddedMass});
  s.duration = 4e-4 * std::round(3 * a / U / 4e-4);  // a whole number of every step below
  return s;
}

TEST(Strang, SecondOrderOnALongStripsFirstSwing) {
  const Scene s = long_strip();
  const std::vector<double> dts = {4e-4, 2e-4, 1e-4, 5e-5};
  std::vector<double> err;
  EXPECT_GE(slope(s, uniform_field(s), Integrator::Strang, dts, 2e-6, "strip", &err), 1.8);
  // at the study's step (0.2 ms) within a tenth of a millimetre of rk4's end point (the strip
  // falls 1.6 cm)
  EXPECT_LT(err[1], 1e-4);
}

// a 2 mm glass sphere in water in a smooth non-uniform steady field (a sheared, converging flow
// on a grid; trilinear interpolation is smooth within a cell, so the box keeps the sphere inside
// one cell): drag and added mass (with the fluid acceleration (grad U) U) see a mean flow that
// changes along the path
Scene sphere_in_shear() {
  Scene s = test::sphere_scene(2e-3, 2500, 998.2, 1e-6, 3);
  s.effects = effects({Effect::Gravity, Effect::Buoyancy, Effect::AddedMass, Effect::Drag,
                       Effect::MeanFlow});
  s.bodies[0].spawn_in_box = true;
  s.bodies[0].box_lo = Vec3(0.2, 0.2, 0.7);
  s.bodies[0].box_hi = Vec3(0.3, 0.3, 0.8);
  s.bodies[0].velocity = Vec3(0.05, -0.02, 0.0);
  s.duration = 0.3;
  s.seed = 3;
  return s;
}

FluidField shear_field() {
  const GridGeometry g = test::grid_geometry(2, 2, 2, Vec3::Zero(), Vec3(1, 1, 1));
  RawGridFrame fr = test::grid_frame(g, [](const Vec3& x, Vec3* U, double* k, double* eps) {
    *U = Vec3(0.3 * x.z() - 0.1 * x.x(), 0.2 * x.x(), 0.05 * x.x() - 0.1);
    *k = 1e-4;
    *eps = 1e-4;
    return true;
  });
  return FluidField::grid(g, {fr}, 1e-6, Drift::Stationary, TimeMode::Clamp);
}

TEST(Strang, OrderInASmoothNonUniformField) {
  const Scene s = sphere_in_shear();
  const FluidField f = shear_field();
  const std::vector<double> dts = {4e-3, 2e-3, 1e-3, 5e-4};
  EXPECT_GE(slope(s, f, Integrator::Strang, dts, 1e-5, "shear"), 1.8);
}

// the leaf of leaf_in_wind in a sheared, non-uniform wind (linear in x and z: one grid cell,
// trilinear interpolation exact and smooth): with added mass the free flow depends on the fluid
// velocity it moves relative to, taken at the step's midpoint (at the start it was first order:
// slope 1.02, errors 8.8e-7 .. 1.0e-7 m)
FluidField air_shear_field() {
  const GridGeometry g = test::grid_geometry(2, 2, 2, Vec3(-10, -10, -10), Vec3(20, 20, 20));
  RawGridFrame fr = test::grid_frame(g, [](const Vec3& x, Vec3* U, double* k, double* eps) {
    *U = Vec3(2.0 + 0.8 * x.z(), 0.5 + 0.6 * x.x(), 0.2 * x.x());
    *k = 1e-3;
    *eps = 1e-3;
    return true;
  });
  return FluidField::grid(g, {fr}, 1.5e-5, Drift::Stationary, TimeMode::Clamp);
}

TEST(Strang, LeafInAShearedWind) {
  Scene s = leaf_in_wind();
  s.uniform_field = false;
  const FluidField f = air_shear_field();
  const std::vector<double> dts = {1e-3, 5e-4, 2.5e-4, 1.25e-4};
  std::vector<double> e_strang, e_split;
  const double p = slope(s, f, Integrator::Strang, dts, 1e-6, "sheared leaf", &e_strang);
  slope(s, f, Integrator::Splitting, dts, 1e-6, "sheared leaf", &e_split);
  EXPECT_GE(p, 1.8);
  for (size_t i = 0; i < dts.size(); ++i) EXPECT_LT(e_strang[i], 0.2 * e_split[i]) << dts[i];
}

// The noise part. The seen velocity u' starts from its stationary distribution (initial_state) and
// follows an OU process that each half step advances exactly in distribution (uniform k and
// epsilon: no drift gradients), so Var u' stays sigma2 at any dt, alpha dt large included. The
// position couples to u' through the drag; the symmetric composition around exact OU half steps
// (the BAOAB idea, Leimkuhler and Matthews 2013) gives its variance weak order 2 here (splitting:
// 1, convergence_test.cpp), measured on the same Brownian path at every dt.
Scene strang_ou_scene(int count) {
  Scene s = test::sphere_scene(2e-3, 1000, 998.2, 1e-6, count);
  s.uniform_k = 1e-3;
  s.uniform_epsilon = 5e-4;
  s.effects = effects({Effect::Buoyancy, Effect::Gravity, Effect::AddedMass, Effect::Drag,
                       Effect::MeanFlow, Effect::Turbulence});
  s.duration = 0.5;
  s.seed = 11;
  return s;
}

TEST(Strang, OUVarianceStaysStationaryAtAnyStep) {
  const Scene s = strang_ou_scene(20000);
  const FluidField f = uniform_field(s);
  FluidSample fs;
  f.sample(Vec3::Zero(), 0.0, false, &fs);
  const double exact = fs.sigma2;
  for (double dt : {0.5, 0.1, 1e-3}) {
    const FinalState r = run(s, f, Integrator::Strang, dt);
    double v = 0;
    for (const Vec3& u : r.u) v += u.squaredNorm();
    v /= 3.0 * double(r.u.size());
    // Monte Carlo: the variance estimate of 3 N normals has relative std sqrt(2 / 3N)
    const double se = exact * std::sqrt(2.0 / (3.0 * double(r.u.size())));
    std::printf("ou strang dt %.3g s (alpha dt %.2f): Var u' %.4e, exact %.4e (+- %.1e)\n", dt,
                fs.alpha * dt, v, exact, se);
    EXPECT_NEAR(v, exact, 4 * se) << dt;
  }
}

TEST(Strang, WeakOrderOfThePositionVariance) {
  // every dt sees the same Brownian path (noise substeps), so the paired differences of the
  // variance have a small Monte Carlo error; reference: strang at a 20 times finer step
  Scene s = strang_ou_scene(1000);
  s.duration = 2.0;
  const double h = 1e-3;
  auto run_sub = [&](double dt, uint32_t sub) {
    Scene c = s;
    c.integrator = Integrator::Strang;
    c.dt = dt;
    Model m = test::compile(c);
    m.noise_substeps = sub;
    State st = initial_state(m, c);
    RunOptions opt;
    opt.every = c.duration;
    opt.threads = 1;
    simulate(m, &st, opt);
    return st.x;
  };
  auto variance = [](const std::vector<Vec3>& x) {
    Vec3 m = Vec3::Zero();
    for (const auto& p : x) m += p;
    m /= double(x.size());
    double v = 0;
    for (const auto& p : x) v += (p - m).squaredNorm();
    return v / double(x.size() - 1);
  };
  const std::vector<Vec3> ref = run_sub(h, 1);
  const double var_ref = variance(ref);
  std::vector<double> dts, weak;
  for (int r : {10, 20, 40, 80}) {
    const std::vector<Vec3> x = run_sub(r * h, static_cast<uint32_t>(r));
    dts.push_back(r * h);
    weak.push_back(std::abs(variance(x) - var_ref));
    std::printf("ou strang dt %.3g s: weak (variance) %.3e m^2 of %.3e\n", r * h, weak.back(),
                var_ref);
  }
  const double p = strang_log_log_slope(dts, weak);
  std::printf("ou strang: weak slope %.2f\n", p);
  EXPECT_GE(p, 1.6);
}

}  // namespace
}  // namespace lrigid
