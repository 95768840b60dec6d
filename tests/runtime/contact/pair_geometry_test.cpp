// The narrow phase between bodies (contact/pair_geometry.h): closed forms for each pair of kinds
// (spheres, boxes face on face, corner into face, edge across edge, ellipsoids, thin plates),
// the symmetry collide(A, B) = collide(B, A) with the normals negated, the margin, and random
// pairs of every kind against FCL (Debian libfcl-dev), an independent implementation (ODE's
// box-box, its own GJK/EPA).
#include "contact/pair_geometry.h"

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <vector>

namespace lrigid {
namespace {

using ShapePtr = std::shared_ptr<const PairShape>;

Mat3 rotation(const Vec3& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

PairPose at(const Vec3& x, const Mat3& R = Mat3::Identity()) { return {x, R}; }

ShapePtr box_shape(double lx, double ly, double lz, const Vec3& com = Vec3::Zero()) {
  return pair_shape(Shape::box(lx, ly, lz), com);
}

// n (B towards A), p and depth of every point match
void expect_point(const PairPoint& q, const Vec3& p, const Vec3& n, double depth, double tol) {
  EXPECT_LT((q.p - p).norm(), tol) << q.p.transpose() << " vs " << p.transpose();
  EXPECT_LT((q.n - n).norm(), tol) << q.n.transpose() << " vs " << n.transpose();
  EXPECT_NEAR(q.depth, depth, tol);
}

// each of `corners` is one of the manifold's points (any order), and there are no others
void expect_points_at(const PairManifold& m, const std::vector<Vec3>& corners, double tol) {
  ASSERT_EQ(m.count, int(corners.size()));
  for (const Vec3& c : corners) {
    double best = 1e300;
    for (int i = 0; i < m.count; ++i) best = std::min(best, (m.pts[i].p - c).norm());
    EXPECT_LT(best, tol) << "no point at " << c.transpose();
  }
}

TEST(PairGeometry, SphereSphereClosedForm) {
  const ShapePtr a = pair_shape(Shape::sphere(0.1), Vec3::Zero());
  const ShapePtr b = pair_shape(Shape::sphere(0.2), Vec3(0.01, 0, 0));  // centre off the COM
  const Vec3 u = Vec3(1, -2, 0.5).normalized();
  const Vec3 cb(0.3, 0.1, -0.2);
  const Mat3 Rb = rotation(Vec3(0, 0, 1), M_PI / 2);  // centre at com + Rb (-com)
  const PairPose pb = at(cb + Rb * Vec3(0.01, 0, 0), Rb);
  const PairPose pa = at(cb + u * 0.25);
  PairManifold m;
  ASSERT_EQ(collide(*a, pa, *b, pb, 0, &m), 1);
  // surfaces at cb + 0.15 u (A's) and cb + 0.2 u (B's): depth 0.05, midway at 0.175
  expect_point(m.pts[0], cb + 0.175 * u, u, 0.05, 1e-14);
}

TEST(PairGeometry, BoxRestingOnBoxGivesTheFourCornersOfTheOverlap) {
  const ShapePtr a = box_shape(1, 1, 0.2), b = box_shape(1, 1, 0.2);
  // A's bottom at z = 0.09, B's top at 0.1: 0.01 deep; overlap x in [-0.2, 0.5], y in [-0.3, 0.5]
  PairManifold m;
  collide(*a, at(Vec3(0.3, 0.2, 0.19)), *b, at(Vec3::Zero()), 0, &m);
  expect_points_at(m,
                   {Vec3(-0.2, -0.3, 0.095), Vec3(0.5, -0.3, 0.095), Vec3(0.5, 0.5, 0.095),
                    Vec3(-0.2, 0.5, 0.095)},
                   1e-12);
  for (int i = 0; i < m.count; ++i) {
    EXPECT_NEAR(m.pts[i].depth, 0.01, 1e-12);
    EXPECT_LT((m.pts[i].n - Vec3::UnitZ()).norm(), 1e-12);
  }
}

TEST(PairGeometry, SmallBoxOnBigBoxAndBigBoxOnSmallBox) {
  const ShapePtr small = box_shape(0.2, 0.2, 0.2), big = box_shape(2, 2, 0.2);
  const Mat3 R = rotation(Vec3(0, 0, 1), 0.3);  // the small box turned about the vertical
  // small on big: the small box's bottom corners, 2 mm deep
  PairManifold m;
  const Vec3 xs(0.4, -0.3, 0.198);
  collide(*small, at(xs, R), *big, at(Vec3::Zero()), 0, &m);
  std::vector<Vec3> corners;
  for (int c = 0; c < 4; ++c)
    corners.push_back(xs + R * Vec3(c & 1 ? 0.1 : -0.1, c & 2 ? 0.1 : -0.1, -0.1) +
                      Vec3(0, 0, 0.001));
  expect_points_at(m, corners, 1e-12);
  for (int i = 0; i < m.count; ++i) {
    EXPECT_NEAR(m.pts[i].depth, 0.002, 1e-12);
    EXPECT_LT((m.pts[i].n - Vec3::UnitZ()).norm(), 1e-12);
  }
  // big on small (upside down): the small box's top corners, the normal down from the small one
  const Vec3 xb(0, 0, 0.398), xt(0.4, -0.3, 0.2);
  collide(*big, at(xb), *small, at(xt, R), 0, &m);
  corners.clear();
  for (int c = 0; c < 4; ++c)
    corners.push_back(xt + R * Vec3(c & 1 ? 0.1 : -0.1, c & 2 ? 0.1 : -0.1, 0.1) -
                      Vec3(0, 0, 0.001));
  expect_points_at(m, corners, 1e-12);
  for (int i = 0; i < m.count; ++i) {
    EXPECT_NEAR(m.pts[i].depth, 0.002, 1e-12);
    EXPECT_LT((m.pts[i].n - Vec3::UnitZ()).norm(), 1e-12);
  }
}

TEST(PairGeometry, RotatedBoxCornerIntoAFace) {
  const ShapePtr cube = box_shape(0.2, 0.2, 0.2), floor = box_shape(2, 2, 0.2);
  // turn the diagonal (1, 1, 1) straight down: the corner (0.1, 0.1, 0.1) lowest, sqrt(3) 0.1 below
  const Mat3 R = Eigen::Quaterniond::FromTwoVectors(Vec3(1, 1, 1), Vec3(0, 0, -1)).toRotationMatrix();
  const Vec3 x(0.3, 0.2, 0.1 + std::sqrt(3.0) * 0.1 - 0.004);
  PairManifold m;
  ASSERT_EQ(collide(*cube, at(x, R), *floor, at(Vec3::Zero()), 0, &m), 1);
  expect_point(m.pts[0], Vec3(0.3, 0.2, 0.098), Vec3::UnitZ(), 0.004, 1e-12);
}

TEST(PairGeometry, EdgeAcrossEdge) {
  // A's lowest edge along x, B's highest along y (each cube turned 45 degrees), crossing 3 mm deep
  const ShapePtr a = box_shape(0.2, 0.2, 0.2), b = box_shape(0.4, 0.4, 0.4);
  const double ra = 0.1 * std::sqrt(2.0), rb = 0.2 * std::sqrt(2.0);
  const PairPose pa = at(Vec3(0.05, -0.02, ra + rb - 0.003), rotation(Vec3::UnitX(), M_PI / 4));
  const PairPose pb = at(Vec3::Zero(), rotation(Vec3::UnitY(), M_PI / 4));
  PairManifold m;
  ASSERT_EQ(collide(*a, pa, *b, pb, 0, &m), 1);
  // the crossing at x = 0 (B's edge), y = -0.02 (A's edge), midway between the edges' heights
  expect_point(m.pts[0], Vec3(0, -0.02, rb - 0.0015), Vec3::UnitZ(), 0.003, 1e-12);
}

TEST(PairGeometry, EllipsoidsAlongAnAxis) {
  const ShapePtr a = pair_shape(Shape::ellipsoid(0.3, 0.2, 0.1), Vec3::Zero());
  const ShapePtr b = pair_shape(Shape::ellipsoid(0.1, 0.2, 0.4), Vec3::Zero());
  PairManifold m;
  // along z: A's bottom at 0.48 - 0.1 = 0.38, B's top at 0.4: 0.02 deep
  ASSERT_EQ(collide(*a, at(Vec3(0, 0, 0.48)), *b, at(Vec3::Zero()), 0, &m), 1);
  expect_point(m.pts[0], Vec3(0, 0, 0.39), Vec3::UnitZ(), 0.02, 1e-6);
  // along x with A turned a quarter about z: A's semi-axis along x is 0.2, B's 0.1
  ASSERT_EQ(collide(*a, at(Vec3(-0.29, 0, 0), rotation(Vec3::UnitZ(), M_PI / 2)), *b,
                    at(Vec3::Zero()), 0, &m),
            1);
  expect_point(m.pts[0], Vec3(-0.095, 0, 0), -Vec3::UnitX(), 0.01, 1e-6);
  // ellipsoid on a box: its lowest point 1 mm into the box's top
  const ShapePtr floor = box_shape(2, 2, 0.2);
  ASSERT_EQ(collide(*a, at(Vec3(0.1, 0.2, 0.199)), *floor, at(Vec3::Zero()), 0, &m), 1);
  expect_point(m.pts[0], Vec3(0.1, 0.2, 0.0995), Vec3::UnitZ(), 0.001, 1e-6);
}

// Leaves: 6 x 4 cm x 0.4 mm; paper 0.1 mm
TEST(PairGeometry, ThinPlatesStackedGiveAFaceContact) {
  const ShapePtr leaf = box_shape(0.06, 0.04, 0.0004), paper = box_shape(0.06, 0.04, 0.0001);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 200; ++trial) {
    const ShapePtr& s = trial % 2 ? leaf : paper;
    const double h = s->semi_axes.z();
    const double depth = 0.2 * h * (1 + u(rng));  // up to 40 % of the thickness
    // the whole stack at a random orientation; the upper plate turned and shifted in its plane
    const Mat3 Q = Eigen::Quaterniond::UnitRandom().toRotationMatrix();
    const Mat3 turn = rotation(Vec3::UnitZ(), M_PI * u(rng));
    const Vec3 shift(0.03 * u(rng), 0.02 * u(rng), 2 * h - depth);
    const Vec3 base(u(rng), u(rng), u(rng));
    PairManifold m;
    ASSERT_GE(collide(*s, at(base + Q * shift, Q * turn), *s, at(base, Q), 0, &m), 3) << trial;
    for (int i = 0; i < m.count; ++i) {
      // the plates' normal, not an edge's; every point inside both plates' outlines
      EXPECT_LT((m.pts[i].n - Q.col(2)).norm(), 1e-9) << trial;
      EXPECT_NEAR(m.pts[i].depth, depth, 1e-12) << trial;
      const Vec3 lb = Q.transpose() * (m.pts[i].p - base);
      const Vec3 la = turn.transpose() * (lb - shift);
      EXPECT_NEAR(lb.z(), h - depth / 2, 1e-12);
      EXPECT_LE(std::abs(lb.x()), 0.03 + 1e-12);
      EXPECT_LE(std::abs(lb.y()), 0.02 + 1e-12);
      EXPECT_LE(std::abs(la.x()), 0.03 + 1e-12);
      EXPECT_LE(std::abs(la.y()), 0.02 + 1e-12);
    }
  }
  // slightly tilted paper (1 mrad) on paper: still its face's normal
  PairManifold m;
  const Mat3 tilt = rotation(Vec3(1, 1, 0), 1e-3);
  ASSERT_GE(collide(*paper, at(Vec3(0.01, 0, 0.0001 - 0.00002), tilt), *paper, at(Vec3::Zero()), 0,
                    &m),
            1);
  for (int i = 0; i < m.count; ++i)
    EXPECT_TRUE(m.pts[i].n.isApprox(Vec3::UnitZ(), 1e-12) || m.pts[i].n.isApprox(tilt.col(2), 1e-12))
        << m.pts[i].n.transpose();
}

TEST(PairGeometry, PlateAcrossAnotherPlatesEdge) {
  const ShapePtr leaf = box_shape(0.06, 0.04, 0.0004);
  // B stands on its long edge (its 6 cm x 0.4 mm face up, z up to 0.02); A lies across it,
  // turned a quarter (x within 2 cm), 0.05 mm deep
  const PairPose pb = at(Vec3::Zero(), rotation(Vec3::UnitX(), M_PI / 2));
  const PairPose pa = at(Vec3(0.005, 0, 0.02 + 0.0002 - 0.00005), rotation(Vec3::UnitZ(), M_PI / 2));
  PairManifold m;
  collide(*leaf, pa, *leaf, pb, 0, &m);
  const double z = 0.02 - 0.000025;
  expect_points_at(m,
                   {Vec3(-0.015, -0.0002, z), Vec3(0.025, -0.0002, z), Vec3(0.025, 0.0002, z),
                    Vec3(-0.015, 0.0002, z)},
                   1e-12);
  for (int i = 0; i < m.count; ++i) EXPECT_LT((m.pts[i].n - Vec3::UnitZ()).norm(), 1e-12);
  // B leaning 20 degrees: A touches its top edge only, along the 4 cm A spans
  const PairPose lean = at(Vec3::Zero(), rotation(Vec3::UnitX(), M_PI / 2 + 0.35));
  Vec3 lo, hi;
  pair_aabb(*leaf, lean, &lo, &hi);
  const PairPose pa2 = at(Vec3(0.005, 0, hi.z() + 0.0002 - 0.00005), rotation(Vec3::UnitZ(), M_PI / 2));
  ASSERT_EQ(collide(*leaf, pa2, *leaf, lean, 0, &m), 2);
  for (int i = 0; i < m.count; ++i) {
    EXPECT_LT((m.pts[i].n - Vec3::UnitZ()).norm(), 1e-12);
    EXPECT_NEAR(m.pts[i].depth, 0.00005, 1e-12);
    EXPECT_NEAR(std::abs(m.pts[i].p.x() - 0.005), 0.02, 1e-12);
  }
}

TEST(PairGeometry, SphereOnAPlate) {
  const ShapePtr leaf = box_shape(0.06, 0.04, 0.0004);
  const ShapePtr ball = pair_shape(Shape::sphere(0.005), Vec3::Zero());
  PairManifold m;
  ASSERT_EQ(collide(*ball, at(Vec3(0.01, 0.01, 0.0002 + 0.005 - 0.0001)), *leaf, at(Vec3::Zero()),
                    0, &m),
            1);
  expect_point(m.pts[0], Vec3(0.01, 0.01, 0.00015), Vec3::UnitZ(), 0.0001, 1e-15);
  // beyond the plate's corner: the normal from the corner to the centre
  const Vec3 corner(0.03, 0.02, 0.0002), dir = Vec3(1, 2, 2).normalized();
  ASSERT_EQ(collide(*leaf, at(Vec3::Zero()), *ball, at(corner + dir * 0.0049), 0, &m), 1);
  expect_point(m.pts[0], corner - dir * 0.00005, -dir, 0.0001, 1e-15);
}

// ---- random shapes and poses --------------------------------------------------------------

enum class Pick { Sphere, Ellipsoid, Box, Hull };

ShapePtr random_shape(Pick k, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> size(0.05, 0.5), u(-1, 1);
  const Vec3 com = 0.02 * Vec3(u(rng), u(rng), u(rng));
  switch (k) {
    case Pick::Sphere:
      return pair_shape(Shape::sphere(size(rng)), com);
    case Pick::Ellipsoid:
      return pair_shape(Shape::ellipsoid(size(rng), size(rng), size(rng)), com);
    case Pick::Box:
      return pair_shape(Shape::box(2 * size(rng), 2 * size(rng), 2 * size(rng)), com);
    case Pick::Hull: {
      // 30 points on an ellipsoid, some pulled inwards
      auto mesh = std::make_shared<TriangleMesh>();
      const Vec3 axes(size(rng), size(rng), size(rng));
      for (int i = 0; i < 30; ++i) {
        const Vec3 d = Vec3(u(rng), u(rng), u(rng)).normalized();
        mesh->vertices.push_back(axes.cwiseProduct(d) * (i % 3 ? 1.0 : 0.9));
      }
      Shape s;
      s.type = ShapeType::Mesh;
      s.mesh = mesh;
      return pair_shape(s, com);
    }
  }
  return nullptr;
}

// FCL's geometry of the shape and its centre in the body frame
std::shared_ptr<fcl::CollisionGeometryd> fcl_geometry(const PairShape& s, Vec3* centre) {
  *centre = s.centre;
  switch (s.kind) {
    case PairShape::Kind::Sphere:
      return std::make_shared<fcl::Sphered>(s.semi_axes.x());
    case PairShape::Kind::Ellipsoid:
      return std::make_shared<fcl::Ellipsoidd>(s.semi_axes);
    case PairShape::Kind::Polytope:
      break;
  }
  if (s.box) return std::make_shared<fcl::Boxd>(2 * s.semi_axes);
  *centre = Vec3::Zero();
  auto verts = std::make_shared<std::vector<Vec3>>(s.vertices);
  auto faces = std::make_shared<std::vector<int>>();
  for (const PairShape::Face& f : s.faces) {
    faces->push_back(f.count);
    for (int k = 0; k < f.count; ++k) faces->push_back(s.loops[size_t(f.first + k)]);
  }
  return std::make_shared<fcl::Convexd>(verts, int(s.faces.size()), faces);
}

struct FclBody {
  std::shared_ptr<fcl::CollisionGeometryd> g;
  Vec3 centre;
  explicit FclBody(const PairShape& s) { g = fcl_geometry(s, &centre); }
  fcl::CollisionObjectd at(const PairPose& p) const {
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    tf.linear() = p.R;
    tf.translation() = p.x + p.R * centre;
    return fcl::CollisionObjectd(g, tf);
  }
};

// FCL's deepest contact: true when the shapes intersect, with the depth and the normal from B
// towards A (FCL's normal points from o1 to o2)
bool fcl_contact(const FclBody& a, const PairPose& pa, const FclBody& b, const PairPose& pb,
                 double* depth, Vec3* n) {
  const fcl::CollisionObjectd oa = a.at(pa), ob = b.at(pb);
  fcl::CollisionRequestd req(8, true);
  req.gjk_solver_type = fcl::GST_LIBCCD;
  fcl::CollisionResultd res;
  if (fcl::collide(&oa, &ob, req, res) == 0) return false;
  *depth = -1;
  for (size_t i = 0; i < res.numContacts(); ++i)
    if (res.getContact(i).penetration_depth > *depth) {
      *depth = res.getContact(i).penetration_depth;
      *n = -res.getContact(i).normal;
    }
  return true;
}

// FCL's distance between A and B (0 when they intersect)
double fcl_distance(const FclBody& a, const PairPose& pa, const FclBody& b, const PairPose& pb) {
  const fcl::CollisionObjectd oa = a.at(pa), ob = b.at(pb);
  fcl::DistanceRequestd req;
  req.gjk_solver_type = fcl::GST_INDEP;
  fcl::DistanceResultd res;
  return std::max(0.0, fcl::distance(&oa, &ob, req, res));
}

// The distance along `dir` from B's centre of mass at which A (turned by Ra) just touches B,
// by bisection on FCL's answer; < 0 when A at B's centre of mass does not meet B.
double touching_distance(const FclBody& fa, const PairShape& a, const Mat3& Ra, const FclBody& fb,
                         const PairShape& b, const PairPose& pb, const Vec3& dir) {
  double in = 0, out = a.radius + b.radius + 1e-3, d;
  Vec3 n;
  if (!fcl_contact(fa, at(pb.x, Ra), fb, pb, &d, &n)) return -1;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (in + out);
    (fcl_contact(fa, at(pb.x + dir * mid, Ra), fb, pb, &d, &n) ? in : out) = mid;
  }
  return 0.5 * (in + out);
}

Mat3 random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  return Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
}

Vec3 random_direction(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  return Vec3(g(rng), g(rng), g(rng)).normalized();
}

const char* pick_name(Pick k) {
  switch (k) {
    case Pick::Sphere: return "sphere";
    case Pick::Ellipsoid: return "ellipsoid";
    case Pick::Box: return "box";
    case Pick::Hull: return "hull";
  }
  return "";
}

// Random intersecting pairs of each pair of kinds, up to 5 % of the smaller shape's size deep:
// the deepest point's depth and the normal against FCL's (ODE's box-box SAT, sphere-box and
// sphere-sphere in closed form, its own GJK/EPA for the rest). Tolerances relative to the
// smaller shape's bounding radius r.
struct Agreement {
  Pick a, b;
  double depth_tol;  // |depth - FCL's| <= depth_tol r
  double angle_tol;  // angle between the normals <= angle_tol, rad
  double agree;      // at least this fraction of the pairs within both
  // depth <= pair_overlap along FCL's normal + least_tol r (the overlap's least value found)
  double least_tol;
};

TEST(PairGeometry, RandomPairsAgreeWithFcl) {
  // FCL's EPA (GST_LIBCCD) stops on a polytope inside the curved Minkowski difference: on the
  // pairs it serves, ours is checked to be at least as shallow along FCL's own normal
  // (least_tol), and locally least (below), and agrees with FCL's depth to its error
  const Agreement cases[] = {
      {Pick::Sphere, Pick::Sphere, 1e-12, 1e-7, 1, 1e-12},
      {Pick::Sphere, Pick::Box, 1e-12, 1e-7, 1, 1e-12},
      {Pick::Sphere, Pick::Ellipsoid, 2e-2, M_PI, 1, 1e-12},
      {Pick::Sphere, Pick::Hull, 2e-2, M_PI, 1, 1e-12},
      {Pick::Ellipsoid, Pick::Ellipsoid, 3e-2, M_PI, 1, 1e-12},
      {Pick::Ellipsoid, Pick::Box, 2e-2, M_PI, 1, 1e-12},
      {Pick::Ellipsoid, Pick::Hull, 2e-2, M_PI, 1, 1e-12},
      // the face preference (kAxisRelTolerance, 2 % of the depth): up to 1e-3 r deeper
      {Pick::Box, Pick::Box, 1e-9, 1e-6, 0.97, 1.1e-3},
      {Pick::Box, Pick::Hull, 1e-4, 1e-2, 0.9, 1.1e-3},
      {Pick::Hull, Pick::Hull, 1e-4, 1e-2, 0.9, 1.1e-3},
  };

  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u01(0, 1);
  for (const Agreement& c : cases) {
    int pairs = 0, within = 0;
    double worst_depth = 0, worst_angle = 0, worst_least = 0;
    std::vector<double> depth_err, angle_err;
    while (pairs < 300) {
      const ShapePtr a = random_shape(c.a, rng), b = random_shape(c.b, rng);
      const FclBody fa(*a), fb(*b);
      const PairPose pb = at(Vec3(u01(rng), u01(rng), u01(rng)), random_rotation(rng));
      const Mat3 Ra = random_rotation(rng);
      const Vec3 dir = random_direction(rng);
      const double t0 = touching_distance(fa, *a, Ra, fb, *b, pb, dir);
      if (t0 < 0) continue;
      const double r = std::min(a->radius, b->radius);
      const PairPose pa = at(pb.x + dir * (t0 - 0.05 * r * u01(rng)), Ra);
      double ref;
      Vec3 ref_n;
      if (!fcl_contact(fa, pa, fb, pb, &ref, &ref_n)) continue;
      PairManifold m;
      ASSERT_GE(collide(*a, pa, *b, pb, 0, &m), 1)
          << pick_name(c.a) << "-" << pick_name(c.b) << " FCL depth " << ref << " n "
          << ref_n.transpose() << " r " << r << " dist " << fcl_distance(fa, pa, fb, pb);
      int deepest = 0;
      for (int i = 1; i < m.count; ++i)
        if (m.pts[i].depth > m.pts[deepest].depth) deepest = i;
      const double de = std::abs(m.pts[deepest].depth - ref) / r;
      const double ae = std::acos(std::clamp(m.pts[deepest].n.dot(ref_n), -1.0, 1.0));
      // no deeper than the overlap along FCL's normal: the depth is the least overlap
      const double better = pair_overlap(*a, pa, *b, pb, ref_n) - m.pts[deepest].depth;
      EXPECT_GE(better, -c.least_tol * r) << pick_name(c.a) << "-" << pick_name(c.b);
      worst_least = std::min(worst_least, better / r);
      // a smooth pair's normal is a local least of the overlap (a polytope's may lie on a kink)
      if (c.a != Pick::Box && c.a != Pick::Hull && c.b != Pick::Box && c.b != Pick::Hull) {
        const Vec3 t1 = m.pts[deepest].n.unitOrthogonal(), t2 = m.pts[deepest].n.cross(t1);
        for (int k = 0; k < 8; ++k) {
          const Vec3 nk = (m.pts[deepest].n + 1e-3 * (std::cos(k * M_PI / 4) * t1 +
                                                      std::sin(k * M_PI / 4) * t2)).normalized();
          EXPECT_GE(pair_overlap(*a, pa, *b, pb, nk), m.pts[deepest].depth - 1e-12 * r);
        }
      }
      depth_err.push_back(de);
      angle_err.push_back(ae);
      worst_depth = std::max(worst_depth, de);
      worst_angle = std::max(worst_angle, ae);
      within += de <= c.depth_tol && ae <= c.angle_tol;
      ++pairs;
    }
    std::sort(depth_err.begin(), depth_err.end());
    std::sort(angle_err.begin(), angle_err.end());
    std::printf("%-9s-%-9s %d pairs: within %.3g r, %.3g rad: %.1f %%; depth error / r median "
                "%.2g, 99 %% %.2g, max %.2g; normal angle median %.2g, 99 %% %.2g, max %.2g\n",
                pick_name(c.a), pick_name(c.b), pairs, c.depth_tol, c.angle_tol,
                100.0 * within / pairs, depth_err[depth_err.size() / 2],
                depth_err[depth_err.size() * 99 / 100], worst_depth, angle_err[angle_err.size() / 2],
                angle_err[angle_err.size() * 99 / 100], worst_angle);
    std::printf("  deepest point against the overlap along FCL's normal: at worst %.2g r deeper\n",
                -worst_least);
    EXPECT_GE(within, c.agree * pairs) << pick_name(c.a) << "-" << pick_name(c.b);
  }
}

// collide(B, A) repeats collide(A, B): the same points bit for bit, the normals negated
TEST(PairGeometry, SymmetricInItsArguments) {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u01(0, 1);
  const Pick kinds[] = {Pick::Sphere, Pick::Ellipsoid, Pick::Box, Pick::Hull};
  int compared = 0;
  for (Pick ka : kinds)
    for (Pick kb : kinds)
      for (int trial = 0; trial < 40; ++trial) {
        const ShapePtr a = random_shape(ka, rng), b = random_shape(kb, rng);
        const FclBody fa(*a), fb(*b);
        const PairPose pb = at(Vec3(u01(rng), u01(rng), u01(rng)), random_rotation(rng));
        const Mat3 Ra = random_rotation(rng);
        const Vec3 dir = random_direction(rng);
        const double t0 = touching_distance(fa, *a, Ra, fb, *b, pb, dir);
        if (t0 < 0) continue;
        const double r = std::min(a->radius, b->radius);
        const PairPose pa = at(pb.x + dir * (t0 + 0.05 * r * (u01(rng) - 0.5)), Ra);
        PairManifold ab, ba;
        collide(*a, pa, *b, pb, 0.02 * r, &ab);
        collide(*b, pb, *a, pa, 0.02 * r, &ba);
        ASSERT_EQ(ab.count, ba.count);
        for (int i = 0; i < ab.count; ++i) {
          EXPECT_EQ(ab.pts[i].p, ba.pts[i].p);
          EXPECT_EQ(ab.pts[i].n, -ba.pts[i].n);
          EXPECT_EQ(ab.pts[i].depth, ba.pts[i].depth);
        }
        compared += ab.count > 0;
      }
  EXPECT_GT(compared, 400);
}

// Two boxes take the closed form of box-box separating axes (box_separation); the same boxes given
// as meshes of their eight corners take the general polytope test (faces, and the edge pairs
// whose Gauss-map arcs cross): the same contact points, normals and depths, at random poses
// around touching, apart by less than the margin, and in
TEST(PairGeometry, BoxPairsInClosedFormAgreeWithTheGeneralPolytopeTest) {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> size(0.02, 0.5), u(-1, 1), u01(0, 1);
  auto box_and_mesh = [&](ShapePtr* box, ShapePtr* mesh) {
    const Vec3 l(size(rng), size(rng), size(rng) * (u01(rng) < 0.2 ? 0.01 : 1.0));  // plates too
    const Vec3 com = 0.02 * Vec3(u(rng), u(rng), u(rng));
    *box = pair_shape(Shape::box(l.x(), l.y(), l.z()), com);
    auto m = std::make_shared<TriangleMesh>();
    for (int c = 0; c < 8; ++c)
      m->vertices.emplace_back(0.5 * (c & 1 ? l.x() : -l.x()), 0.5 * (c & 2 ? l.y() : -l.y()),
                               0.5 * (c & 4 ? l.z() : -l.z()));
    Shape s;
    s.type = ShapeType::Mesh;
    s.mesh = m;
    *mesh = pair_shape(s, com);
    ASSERT_TRUE((*box)->box);
    ASSERT_FALSE((*mesh)->box);
  };
  int compared = 0, manifolds = 0;
  for (int trial = 0; trial < 300; ++trial) {
    ShapePtr a, ma, b, mb;
    box_and_mesh(&a, &ma);
    box_and_mesh(&b, &mb);
    const FclBody fa(*a), fb(*b);
    const PairPose pb = at(Vec3(u01(rng), u01(rng), u01(rng)), random_rotation(rng));
    // every other pair nearly face on face: A turned from B's axes by up to 0.01 rad, along one
    // of B's axes
    const bool faces = trial % 2 == 0;
    const Mat3 Ra = faces ? Mat3(pb.R * rotation(random_direction(rng), 0.01 * u01(rng)))
                          : random_rotation(rng);
    const Vec3 dir = faces ? Vec3(pb.R.col(trial / 2 % 3) * (u01(rng) < 0.5 ? -1.0 : 1.0))
                           : random_direction(rng);
    const double t0 = touching_distance(fa, *a, Ra, fb, *b, pb, dir);
    if (t0 < 0) continue;
    const double r = std::min(a->radius, b->radius);
    const PairPose pa = at(pb.x + dir * (t0 + 0.05 * r * (u01(rng) - 0.5)), Ra);
    PairManifold closed, general;
    collide(*a, pa, *b, pb, 0.02 * r, &closed);
    collide(*ma, pa, *mb, pb, 0.02 * r, &general);
    ASSERT_EQ(closed.count, general.count) << "trial " << trial;
    for (int i = 0; i < closed.count; ++i) {
      const PairPoint& c = closed.pts[i];
      int near = 0;
      for (int k = 1; k < general.count; ++k)
        if ((general.pts[k].p - c.p).norm() < (general.pts[near].p - c.p).norm()) near = k;
      const PairPoint& g = general.pts[near];
      EXPECT_LT((g.p - c.p).norm(), 1e-9 * r) << "trial " << trial << " point " << i;
      EXPECT_LT((g.n - c.n).norm(), 1e-9) << "trial " << trial << " point " << i;
      EXPECT_NEAR(g.depth, c.depth, 1e-9 * r) << "trial " << trial << " point " << i;
    }
    compared += closed.count > 0;
    manifolds += closed.count >= 3;
  }
  EXPECT_GT(compared, 150);
  EXPECT_GT(manifolds, 50);  // faces on faces among them, not only single points
}

// Points apart by less than the margin come with depth minus the gap; farther, none
TEST(PairGeometry, MarginGivesSpeculativePointsAndNoFarther) {
  const double margin = 0.004;
  const ShapePtr ball = pair_shape(Shape::sphere(0.1), Vec3::Zero());
  const ShapePtr egg = pair_shape(Shape::ellipsoid(0.3, 0.2, 0.1), Vec3::Zero());
  const ShapePtr slab = box_shape(1, 1, 0.2);
  auto cube_mesh = std::make_shared<TriangleMesh>();
  for (int c = 0; c < 8; ++c)
    cube_mesh->vertices.emplace_back(c & 1 ? 0.1 : -0.1, c & 2 ? 0.1 : -0.1, c & 4 ? 0.1 : -0.1);
  Shape cube;
  cube.type = ShapeType::Mesh;
  cube.mesh = cube_mesh;
  const ShapePtr hull = pair_shape(cube, Vec3::Zero());
  // A above B, each reaching `reach` above / below its centre: the gap between them
  struct Stack {
    const PairShape* a;
    double reach_a;
    const PairShape* b;
    double reach_b;
    int points;
    bool shifted;  // A shifted sideways (a flat face below or above: the gap stays vertical)
  };
  const Stack stacks[] = {
      {ball.get(), 0.1, ball.get(), 0.1, 1, false}, {ball.get(), 0.1, slab.get(), 0.1, 1, true},
      {egg.get(), 0.1, egg.get(), 0.1, 1, false},   {egg.get(), 0.1, slab.get(), 0.1, 1, true},
      {egg.get(), 0.1, ball.get(), 0.1, 1, false},  {slab.get(), 0.1, slab.get(), 0.1, 4, true},
      {hull.get(), 0.1, slab.get(), 0.1, 4, true},  {hull.get(), 0.1, hull.get(), 0.1, 4, true},
      {ball.get(), 0.1, hull.get(), 0.1, 1, true},  {egg.get(), 0.1, hull.get(), 0.1, 1, true}};
  for (const Stack& s : stacks)
    for (double gap : {0.0, 0.25 * margin, 0.75 * margin, 1.01 * margin, 2 * margin}) {
      const double side = s.shifted ? 0.01 : 0;
      const PairPose pa = at(Vec3(side, 2 * side, s.reach_a + s.reach_b + gap));
      PairManifold m;
      const int n = collide(*s.a, pa, *s.b, at(Vec3::Zero()), margin, &m);
      if (gap >= margin) {
        EXPECT_EQ(n, 0) << gap;
        continue;
      }
      ASSERT_EQ(n, s.points) << gap << " stack " << (&s - stacks);
      for (int i = 0; i < n; ++i) {
        EXPECT_NEAR(m.pts[i].depth, -gap, 1e-8) << gap;
        EXPECT_LT((m.pts[i].n - Vec3::UnitZ()).norm(), 1e-6);
        EXPECT_NEAR(m.pts[i].p.z(), s.reach_b + gap / 2, 1e-6);
      }
    }
}

// Smooth pairs apart by a random gap: one point whose depth is minus FCL's distance while the gap
// is below the margin, none beyond
TEST(PairGeometry, MarginAgreesWithFclDistance) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u01(0, 1);
  const Pick kinds[] = {Pick::Sphere, Pick::Ellipsoid};
  int near = 0, far = 0;
  for (Pick ka : kinds)
    for (int trial = 0; trial < 200; ++trial) {
      const ShapePtr a = random_shape(ka, rng), b = random_shape(Pick::Ellipsoid, rng);
      const FclBody fa(*a), fb(*b);
      const PairPose pb = at(Vec3::Zero(), random_rotation(rng));
      const Mat3 Ra = random_rotation(rng);
      const Vec3 dir = random_direction(rng);
      const double t0 = touching_distance(fa, *a, Ra, fb, *b, pb, dir);
      if (t0 < 0) continue;
      const double r = std::min(a->radius, b->radius), margin = 0.02 * r;
      const PairPose pa = at(dir * (t0 + 2 * margin * u01(rng)), Ra);
      const double d = fcl_distance(fa, pa, fb, pb);
      if (std::abs(d - margin) < 1e-4 * r) continue;  // too close to call
      PairManifold m;
      const int n = collide(*a, pa, *b, pb, margin, &m);
      if (d > margin) {
        EXPECT_EQ(n, 0) << d << " " << margin;
        ++far;
      } else {
        ASSERT_EQ(n, 1) << d << " " << margin;
        EXPECT_NEAR(m.pts[0].depth, -d, 1e-4 * r);
        ++near;
      }
    }
  EXPECT_GT(near, 100);
  EXPECT_GT(far, 100);
}

}  // namespace
}  // namespace lrigid
