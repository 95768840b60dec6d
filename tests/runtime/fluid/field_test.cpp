#include "fluid/field.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lrigid {
namespace {

// a 5 x 4 x 3 grid with U linear in x, y, z and constant k, eps
RawGridFrame linear_frame(const GridGeometry& g, double t, double scale) {
  RawGridFrame f;
  f.time = t;
  const size_t np = g.points();
  f.U.resize(3 * np);
  f.k.assign(np, 0.1f);
  f.epsilon.assign(np, 0.01f);
  f.valid.assign(np, 1);
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) {
        const size_t p = i + size_t(g.n[0]) * (j + size_t(g.n[1]) * k);
        const Vec3 x = g.origin + Vec3(i * g.spacing.x(), j * g.spacing.y(), k * g.spacing.z());
        f.U[3 * p + 0] = float(scale * (1 + 2 * x.x()));
        f.U[3 * p + 1] = float(scale * (-x.y() + 0.5 * x.z()));
        f.U[3 * p + 2] = float(scale * 3 * x.z());
      }
  return f;
}

GridGeometry geometry() {
  GridGeometry g;
  g.n[0] = 5;
  g.n[1] = 4;
  g.n[2] = 3;
  g.origin = Vec3(-1, 0, 2);
  g.spacing = Vec3(0.5, 0.25, 1.0);
  return g;
}

TEST(FluidField, TrilinearIsExactForLinearFieldsWithGradients) {
  const GridGeometry g = geometry();
  const FluidField f =
      FluidField::grid(g, {linear_frame(g, 0, 1)}, 1e-6, Drift::Stationary, TimeMode::Clamp);
  FluidSample s;
  const Vec3 x(-0.13, 0.61, 3.3);
  ASSERT_TRUE(f.sample(x, 0, true, &s));
  EXPECT_NEAR(s.U.x(), 1 + 2 * x.x(), 1e-6);
  EXPECT_NEAR(s.U.y(), -x.y() + 0.5 * x.z(), 1e-6);
  EXPECT_NEAR(s.U.z(), 3 * x.z(), 1e-5);
  Mat3 G;
  G << 2, 0, 0, 0, -1, 0.5, 0, 0, 3;
  EXPECT_LT((s.grad_U - G).cwiseAbs().maxCoeff(), 1e-5);
  EXPECT_NEAR(s.sigma2, 2.0 / 3.0 * 0.1, 1e-6);
}

TEST(FluidField, OutsideTheGridIsNotSampled) {
  const GridGeometry g = geometry();
  const FluidField f =
      FluidField::grid(g, {linear_frame(g, 0, 1)}, 1e-6, Drift::Stationary, TimeMode::Clamp);
  FluidSample s;
  EXPECT_FALSE(f.sample(Vec3(-1.01, 0.5, 2.5), 0, false, &s));
  EXPECT_FALSE(f.sample(Vec3(0, 0.76, 2.5), 0, false, &s));
  EXPECT_FALSE(f.sample(Vec3(0, 0.5, std::nan("")), 0, false, &s));
  EXPECT_TRUE(f.sample(g.upper(), 0, false, &s));  // the last point is inside
  EXPECT_TRUE(f.sample(g.origin, 0, false, &s));
}

TEST(FluidField, InvalidPointsGetNoWeight) {
  const GridGeometry g = geometry();
  RawGridFrame fr = linear_frame(g, 0, 1);
  // invalidate point (1,1,1) and give it a wild value that must never leak out
  const size_t p = 1 + 5 * (1 + 4 * 1);
  fr.valid[p] = 0;
  fr.U[3 * p] = 1e6f;
  fr.k[p] = 0;
  const FluidField f = FluidField::grid(g, {fr}, 1e-6, Drift::Stationary, TimeMode::Clamp);
  FluidSample s;
  // a point in a cell touching the invalid corner: a convex blend of the valid corners
  // (cell (0,0,0) at fractions 0.5: the invalid corner (1,1,1) has weight 1/8)
  ASSERT_TRUE(f.sample(Vec3(-0.75, 0.125, 2.5), 0, true, &s));
  EXPECT_LT(s.U.x(), 1.0);  // valid corners have U_x in [-1, 1]
  EXPECT_GT(s.U.x(), -1.0);
  EXPECT_TRUE(s.grad_U.isZero());  // no gradient next to invalid points
  // exactly at the invalid point: the blend of its neighbours has no weight there -> outside
  EXPECT_FALSE(f.sample(Vec3(-0.5, 0.25, 3.0), 0, false, &s));
  // nearer the invalid point than halfway (fractions 0.8: its weight 0.512 > 1/2): in the solid
  EXPECT_FALSE(f.sample(Vec3(-0.6, 0.2, 2.8), 0, false, &s));
  // nearer the valid side (fractions 0.75: weight 0.42): still in the fluid
  EXPECT_TRUE(f.sample(Vec3(-0.625, 0.1875, 2.75), 0, false, &s));
}

TEST(FluidField, TimeSeriesInterpolatesLinearlyAndLoopsOrClamps) {
  const GridGeometry g = geometry();
  const std::vector<RawGridFrame> frames = {linear_frame(g, 0, 1), linear_frame(g, 2, 3)};
  const Vec3 x(0.2, 0.3, 2.4);
  const double u0 = 1 + 2 * x.x();
  FluidSample s;
  const FluidField clamp = FluidField::grid(g, frames, 1e-6, Drift::Stationary, TimeMode::Clamp);
  ASSERT_TRUE(clamp.sample(x, 0.5, false, &s));
  EXPECT_NEAR(s.U.x(), u0 * (1 + 2 * 0.25), 1e-5);  // scale 1 -> 3 over 2 s
  EXPECT_NEAR(s.dU_dt.x(), u0 * 1.0, 1e-5);
  ASSERT_TRUE(clamp.sample(x, 7.0, false, &s));
  EXPECT_NEAR(s.U.x(), 3 * u0, 1e-5);
  const FluidField loop = FluidField::grid(g, frames, 1e-6, Drift::Stationary, TimeMode::Loop);
  ASSERT_TRUE(loop.sample(x, 4.5, false, &s));  // 4.5 s wraps to 0.5 s
  EXPECT_NEAR(s.U.x(), u0 * 1.5, 1e-5);
}

// the per-thread last-sample cache answers repeats with what a fresh sample gives, never with
// another field's values, and drops the gradients when they are not asked for
TEST(FluidField, RepeatedSamplesAreServedCorrectly) {
  const GridGeometry g = geometry();
  const Vec3 x(0.3, 0.4, 2.7);
  FluidSample a, b, c, d;
  {
    const FluidField f1 =
        FluidField::grid(g, {linear_frame(g, 0, 1)}, 1e-6, Drift::Stationary, TimeMode::Clamp);
    ASSERT_TRUE(f1.sample(x, 0.0, true, &a));
    ASSERT_TRUE(f1.sample(x, 0.0, true, &b));  // repeat
    EXPECT_EQ(a.U, b.U);
    EXPECT_EQ(a.grad_U, b.grad_U);
    EXPECT_NEAR(b.U.x(), 1 + 2 * x.x(), 1e-6);
    ASSERT_TRUE(f1.sample(x, 5.0, false, &c));  // steady field: any time, no gradients
    EXPECT_EQ(c.U, a.U);
    EXPECT_EQ(c.grad_U, Mat3::Zero());
  }
  // a second field (possibly at the same address) with twice the velocity, same point
  const FluidField f2 =
      FluidField::grid(g, {linear_frame(g, 0, 2)}, 1e-6, Drift::Stationary, TimeMode::Clamp);
  ASSERT_TRUE(f2.sample(x, 0.0, true, &d));
  EXPECT_NEAR(d.U.x(), 2 * a.U.x(), 1e-6);
  // a time series: the same x at another time is sampled afresh
  const FluidField ts = FluidField::grid(g, {linear_frame(g, 0, 1), linear_frame(g, 1, 3)}, 1e-6,
                                         Drift::Stationary, TimeMode::Clamp);
  FluidSample e, h;
  ASSERT_TRUE(ts.sample(x, 0.0, false, &e));
  ASSERT_TRUE(ts.sample(x, 0.5, false, &h));
  EXPECT_NEAR(h.U.x(), 2 * e.U.x(), 1e-5);
}

// The wall z = 2.7 m, solid below, as foam2grid writes it: valid = 0 and a negative distance
// in the solid. The sample's distance is the plain trilinear blend, exact for a plane, also
// where sample() reports the point outside the fluid.
RawGridFrame walled_frame(const GridGeometry& g, double t) {
  RawGridFrame f = linear_frame(g, t, 1);
  f.wall_distance.resize(g.points());
  for (size_t p = 0; p < g.points(); ++p) {
    const double z = g.origin.z() + double(p / (size_t(g.n[0]) * g.n[1])) * g.spacing.z();
    f.wall_distance[p] = float(z - 2.7);
    f.valid[p] = z > 2.7;
  }
  return f;
}

TEST(FluidField, WallDistanceIsTheTrilinearBlendAndCrossesZeroAtThePlane) {
  const GridGeometry g = geometry();  // z from 2 to 4 m
  const FluidField f =
      FluidField::grid(g, {walled_frame(g, 0)}, 1e-5, Drift::Stationary, TimeMode::Clamp);
  EXPECT_TRUE(f.has_wall_distance());
  FluidSample s;
  for (double z : {2.05, 2.5, 2.69, 2.71, 3.0, 3.3, 3.99}) {
    const Vec3 x(-0.3, 0.37, z);
    const bool in = f.sample(x, 0, false, &s);
    EXPECT_NEAR(s.wall_distance, z - 2.7, 1e-6) << z;
    if (z < 2.5) {
      EXPECT_FALSE(in) << z;  // all corners below the plane are solid
    }
  }
  // outside the grid's box there is no wall: +infinity
  EXPECT_FALSE(f.sample(Vec3(5, 0.5, 3), 0, false, &s));
  EXPECT_EQ(s.wall_distance, HUGE_VAL);
  // the same frames in a series: the distance does not depend on time
  const FluidField series = FluidField::grid(g, {walled_frame(g, 0), walled_frame(g, 1)}, 1e-5,
                                             Drift::Stationary, TimeMode::Clamp);
  ASSERT_TRUE(series.sample(Vec3(0.1, 0.2, 3.2), 0.3, false, &s));
  EXPECT_NEAR(s.wall_distance, 0.5, 1e-6);
  EXPECT_FALSE(series.sample(Vec3(0.1, 0.2, 2.2), 0.3, false, &s));
  EXPECT_NEAR(s.wall_distance, -0.5, 1e-6);
}

// wall_distance on a distance that is not a plane (a value per grid point, no pattern): the
// trilinear blend of the cell's 8 corners with their weights written out, and a gradient that is
// the blend's derivative (central differences inside a cell, where the blend is smooth).
TEST(FluidField, WallDistanceAndItsGradientAreTheCellsTrilinearBlend) {
  const GridGeometry g = geometry();
  RawGridFrame fr = linear_frame(g, 0, 1);
  fr.wall_distance.resize(g.points());
  for (size_t p = 0; p < g.points(); ++p)
    fr.wall_distance[p] = float(0.3 + 0.7 * std::sin(1.7 * double(p)) + 0.01 * double(p));
  const FluidField f = FluidField::grid(g, {fr}, 1e-5, Drift::Stationary, TimeMode::Clamp);
  auto node = [&](int i, int j, int k) {
    return double(fr.wall_distance[size_t(i) + size_t(g.n[0]) * (size_t(j) + size_t(g.n[1]) * k)]);
  };
  for (const Vec3& x : {Vec3(-0.31, 0.37, 2.2), Vec3(0.55, 0.05, 3.61), Vec3(0.02, 0.61, 2.93)}) {
    double want = 0;
    int i0[3];
    double fr3[3];
    for (int a = 0; a < 3; ++a) {
      const double s = (x[a] - g.origin[a]) / g.spacing[a];
      i0[a] = int(s);
      fr3[a] = s - i0[a];
    }
    for (int c = 0; c < 8; ++c) {
      const int cx = c & 1, cy = (c >> 1) & 1, cz = c >> 2;
      want += (cx ? fr3[0] : 1 - fr3[0]) * (cy ? fr3[1] : 1 - fr3[1]) * (cz ? fr3[2] : 1 - fr3[2]) *
              node(i0[0] + cx, i0[1] + cy, i0[2] + cz);
    }
    double d;
    Vec3 grad;
    ASSERT_TRUE(f.wall_distance(x, 0, &d, &grad)) << x.transpose();
    EXPECT_NEAR(d, want, 1e-12) << x.transpose();
    for (int a = 0; a < 3; ++a) {
      const double h = 1e-6 * g.spacing[a];
      double dp, dm;
      Vec3 gp, gm;
      ASSERT_TRUE(f.wall_distance(x + h * Vec3::Unit(a), 0, &dp, &gp));
      ASSERT_TRUE(f.wall_distance(x - h * Vec3::Unit(a), 0, &dm, &gm));
      EXPECT_NEAR(grad[a], (dp - dm) / (2 * h), 1e-6 * (1 + std::abs(grad[a]))) << a;
    }
  }
}

// only_floor_near: true where every grid point of the cells about the body has the plane below
// as its nearest wall (its distance is its height above it), false next to another wall, off
// the box, for another floor height and without the array.
TEST(FluidField, OnlyFloorNearWhereEveryCornersNearestWallIsTheFloor) {
  const GridGeometry g = geometry();     // x -1..1 (0.5), y 0..0.75 (0.25), z 2..4 (1)
  RawGridFrame fr = walled_frame(g, 0);  // the floor z = 2.7: distances z - 2.7
  const FluidField f = FluidField::grid(g, {fr}, 1e-5, Drift::Stationary, TimeMode::Clamp);
  EXPECT_TRUE(f.only_floor_near(Vec3(-0.3, 0.37, 3.0), 0.05, 2.7, 0));
  EXPECT_TRUE(f.only_floor_near(Vec3(0.1, 0.3, 2.75), 0.2, 2.7, 0));
  EXPECT_FALSE(f.only_floor_near(Vec3(-0.3, 0.37, 3.0), 0.05, 2.0, 0)) << "another floor";
  EXPECT_FALSE(f.only_floor_near(Vec3(0.98, 0.37, 3.0), 0.05, 2.7, 0)) << "off the box";
  // a floor at the grid's bottom z = 2: a body lying on it reaches below the bottom
  RawGridFrame bottom = walled_frame(g, 0);
  for (size_t p = 0; p < g.points(); ++p) bottom.wall_distance[p] += 0.7f;  // z - 2
  const FluidField b = FluidField::grid(g, {bottom}, 1e-5, Drift::Stationary, TimeMode::Clamp);
  EXPECT_TRUE(b.only_floor_near(Vec3(-0.3, 0.37, 2.01), 0.05, 2.0, 0));
  EXPECT_FALSE(b.only_floor_near(Vec3(-0.3, 0.37, 1.9), 0.05, 2.0, 0)) << "all below the grid";
  // a wall nearer than the floor at the grid point (x, y, z) = (0.5, 0.5, 3): the cells
  // touching it are not floor-only, the others still are
  const size_t p = 3 + 2 * size_t(g.n[0]) + 1 * size_t(g.n[0]) * g.n[1];
  fr.wall_distance[p] = 0.1f;
  const FluidField w = FluidField::grid(g, {fr}, 1e-5, Drift::Stationary, TimeMode::Clamp);
  EXPECT_FALSE(w.only_floor_near(Vec3(0.4, 0.45, 2.8), 0.02, 2.7, 0));
  EXPECT_FALSE(w.only_floor_near(Vec3(0.6, 0.55, 3.5), 0.02, 2.7, 0));
  EXPECT_TRUE(w.only_floor_near(Vec3(-0.6, 0.1, 2.8), 0.02, 2.7, 0));
  const FluidField none =
      FluidField::grid(g, {linear_frame(g, 0, 1)}, 1e-5, Drift::Stationary, TimeMode::Clamp);
  EXPECT_FALSE(none.only_floor_near(Vec3(-0.3, 0.37, 3.0), 0.05, 2.7, 0));
  const FluidField u = FluidField::uniform(Vec3(1, 0, 0), 0.1, 0.01, 1e-5, Drift::Stationary);
  EXPECT_FALSE(u.only_floor_near(Vec3(0, 0, 0), 0.05, 0, 0));
}

TEST(FluidField, WithoutAWallDistanceEverySampleIsFarFromWalls) {
  const GridGeometry g = geometry();
  const FluidField f =
      FluidField::grid(g, {linear_frame(g, 0, 1)}, 1e-5, Drift::Stationary, TimeMode::Clamp);
  EXPECT_FALSE(f.has_wall_distance());
  FluidSample s;
  ASSERT_TRUE(f.sample(Vec3(0, 0.5, 3), 0, false, &s));
  EXPECT_EQ(s.wall_distance, HUGE_VAL);
  const FluidField u = FluidField::uniform(Vec3(1, 0, 0), 0.1, 0.01, 1e-5, Drift::Stationary);
  EXPECT_FALSE(u.has_wall_distance());
  ASSERT_TRUE(u.sample(Vec3(0, 0, 0), 0, false, &s));
  EXPECT_EQ(s.wall_distance, HUGE_VAL);
  // a streamed series learns it from its first frame, read on demand
  const FluidField st = FluidField::streamed(
      g, {0.0, 1.0, 2.0}, [&g](size_t i) { return walled_frame(g, double(i)); }, 1e-5,
      Drift::Stationary, TimeMode::Clamp);
  EXPECT_TRUE(st.has_wall_distance());
  st.prepare(0.5, 0.5);
  ASSERT_TRUE(st.sample(Vec3(0.1, 0.2, 3.2), 0.5, false, &s));
  EXPECT_NEAR(s.wall_distance, 0.5, 1e-6);
}

// The solids do not move, so a wall query may ask at any time: on a streamed series whose first
// frame has been released it reads a resident frame. Before, it read frame 0's records wherever
// the caller asked at t = 0 (the exit reason of a body that left the grid does), a released
// (empty) frame: lrigid run --stream-field on crashed on the tank series with colliding walls.
TEST(FluidField, WallQueriesOnAStreamedSeriesReadAResidentFrame) {
  const GridGeometry g = geometry();
  const FluidField st = FluidField::streamed(
      g, {0.0, 1.0, 2.0, 3.0}, [&g](size_t i) { return walled_frame(g, double(i)); }, 1e-5,
      Drift::Stationary, TimeMode::Clamp);
  st.prepare(2.5, 2.5);  // frames 2 and 3 only
  ASSERT_EQ(st.resident_frames(), 2u);
  for (const double t : {0.0, 0.5, 1.5, 2.5}) {
    double d;
    Vec3 grad;
    ASSERT_TRUE(st.wall_distance(Vec3(0.1, 0.2, 3.2), t, &d, &grad)) << t;
    EXPECT_NEAR(d, 0.5, 1e-6) << t;
    EXPECT_NEAR(grad.z(), 1.0, 1e-6) << t;
    EXPECT_TRUE(st.only_floor_near(Vec3(-0.3, 0.37, 3.0), 0.05, 2.7, t)) << t;
  }
}

}  // namespace
}  // namespace lrigid
