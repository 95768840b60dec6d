// Grid hard cases: a flow that carries bodies through a slab where k = 0 and
// epsilon = 0, a slab where k = 0 but epsilon > 0 (eps/k infinite), past a block of invalid
// grid points, and out of the grid. Every body must stay finite and bounded while inside and
// end "exited" (never "failed") at a position inside the grid box.
#include <gtest/gtest.h>

#include "compile/compile_model.h"
#include "effects/registry.h"
#include "stability/hard_case.h"

namespace lrigid {
namespace {

constexpr double kGridRhoAir = 1.204, kGridNuAir = 1.5e-5;
const Vec3 kGridU(2, 0, 0);

// [0, 2] x [0, 1] x [0, 1] m, spacing 0.1 m
FluidField hard_grid() {
  const GridGeometry g = test::grid_geometry(21, 11, 11, Vec3::Zero(), Vec3(0.1, 0.1, 0.1));
  const RawGridFrame f = test::grid_frame(g, [](const Vec3& p, Vec3* U, double* k, double* eps) {
    const double x = p.x(), y = p.y();
    *U = kGridU;
    *k = 0.3;
    *eps = 1.0;
    if (x >= 0.55 && x <= 0.85) *k = *eps = 0.0;  // no turbulence at all
    if (x >= 0.95 && x <= 1.25) {                  // eps/k infinite
      *k = 0.0;
      *eps = 5.0;
    }
    // a solid block over the lower half of the channel
    return !(x >= 1.35 && x <= 1.55 && y <= 0.45);
  });
  return FluidField::grid(g, {f}, kGridNuAir, Drift::Stationary, TimeMode::Clamp);
}

struct GridCase {
  double density_ratio;
  double aspect;
  double dt;
};

class GridHardCases : public ::testing::TestWithParam<GridCase> {};

TEST_P(GridHardCases, BodiesCrossKZeroAndInvalidRegionsAndExitCleanly) {
  const GridCase c = GetParam();
  Scene s = test::sphere_scene(0.01, c.density_ratio * kGridRhoAir, kGridRhoAir, kGridNuAir, 64);
  s.uniform_field = false;
  if (c.aspect > 1) s.bodies[0].shape = Shape::ellipsoid(0.01, 0.01, 0.01 / c.aspect);
  s.bodies[0].spawn_in_box = true;
  s.bodies[0].box_lo = Vec3(0.1, 0.1, 0.3);
  s.bodies[0].box_hi = Vec3(0.3, 0.9, 0.9);
  s.bodies[0].random_orientation = true;
  s.effects = stability::base_effects();
  s.gravity = Vec3(9.81, 0, 0);  // a vertical channel flowing down: heavy bodies cross it too
  s.integrator = Integrator::Splitting;
  s.dt = c.dt;
  s.duration = 4;  // 2 m at 2 m/s, twice over
  const Model m = test::compile(s, hard_grid());
  State st = initial_state(m, s);
  std::ostringstream id;
  id << "rho_b/rho_f = " << c.density_ratio << ", aspect " << c.aspect << ", dt = " << c.dt;
  SCOPED_TRACE(id.str());
  const stability::Observed o = stability::run_observed(m, &st, kGridU);
  EXPECT_EQ(o.failure, "");
  EXPECT_EQ(o.stats.failed, 0u);
  EXPECT_EQ(o.stats.exited, st.size()) << "every body leaves the grid (through a side or the "
                                          "solid block)";
  const Vec3 hi = m.field.geometry().upper();
  size_t crossed_k0 = 0;
  for (size_t i = 0; i < st.size(); ++i) {
    EXPECT_EQ(st.status[i], BodyStatus::Exited) << "body " << i << ": " << st.reason[i];
    EXPECT_FALSE(st.reason[i].empty());
    EXPECT_GT(st.t_stop[i], 0);
    EXPECT_TRUE((st.x[i].array() >= -1e-12).all() && (st.x[i].array() <= hi.array() + 1e-12).all())
        << "body " << i << " stopped outside the grid at " << st.x[i].transpose();
    if (st.x[i].x() > 1.25) ++crossed_k0;
  }
  // the test means something only if bodies went through both k = 0 slabs
  EXPECT_GT(crossed_k0, st.size() / 4) << "bodies that crossed the k = 0 slabs";
}

INSTANTIATE_TEST_SUITE_P(
    Grid, GridHardCases,
    ::testing::Values(GridCase{1, 1, 1e-4}, GridCase{1, 1, 1e-3}, GridCase{1, 1, 0.05},
                      GridCase{0.001, 1, 1e-3}, GridCase{0.001, 100, 1e-3},
                      GridCase{1000, 1, 1e-3}, GridCase{1000, 1000, 0.05},
                      GridCase{0.01, 1000, 0.05}),
    [](const auto& info) {
      std::ostringstream n;
      n << "ratio" << info.param.density_ratio << "_aspect" << info.param.aspect << "_dt"
        << info.param.dt;
      std::string s = n.str();
      for (char& ch : s)
        if (ch == '.' || ch == '-') ch = 'p';
      return s;
    });

}  // namespace
}  // namespace lrigid
