// Cost of the narrow phase between bodies (contact/pair_geometry.h), per pair of kinds: collide
// against FCL's collide (Debian libfcl-dev, GJK solver libccd, contacts on) on the same 256
// intersecting pairs, up to 5 % of the smaller shape's size deep. "ns_per_pair": wall time per
// pair, single thread.
//   build/bin/pair_geometry_bench --benchmark_min_time=0.3
#include <benchmark/benchmark.h>

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>

#include <memory>
#include <random>
#include <vector>

#include "contact/pair_geometry.h"

namespace lrigid {
namespace {

enum Pick { kSphere, kEllipsoid, kBox, kPlate, kHull };

std::shared_ptr<const PairShape> make_shape(int k, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> size(0.05, 0.5), u(-1, 1);
  switch (k) {
    case kSphere: return pair_shape(Shape::sphere(size(rng)), Vec3::Zero());
    case kEllipsoid: return pair_shape(Shape::ellipsoid(size(rng), size(rng), size(rng)), Vec3::Zero());
    case kBox: return pair_shape(Shape::box(2 * size(rng), 2 * size(rng), 2 * size(rng)), Vec3::Zero());
    case kPlate: return pair_shape(Shape::box(0.06, 0.04, 0.0004), Vec3::Zero());
    default: {
      auto mesh = std::make_shared<TriangleMesh>();
      const Vec3 axes(size(rng), size(rng), size(rng));
      for (int i = 0; i < 30; ++i) mesh->vertices.push_back(axes.cwiseProduct(Vec3(u(rng), u(rng), u(rng)).normalized()));
      Shape s;
      s.type = ShapeType::Mesh;
      s.mesh = mesh;
      return pair_shape(s, Vec3::Zero());
    }
  }
}

std::shared_ptr<fcl::CollisionGeometryd> fcl_shape(const PairShape& s) {
  if (s.kind == PairShape::Kind::Sphere) return std::make_shared<fcl::Sphered>(s.semi_axes.x());
  if (s.kind == PairShape::Kind::Ellipsoid) return std::make_shared<fcl::Ellipsoidd>(s.semi_axes);
  if (s.box) return std::make_shared<fcl::Boxd>(2 * s.semi_axes);
  auto faces = std::make_shared<std::vector<int>>();
  for (const PairShape::Face& f : s.faces) {
    faces->push_back(f.count);
    for (int k = 0; k < f.count; ++k) faces->push_back(s.loops[size_t(f.first + k)]);
  }
  return std::make_shared<fcl::Convexd>(std::make_shared<std::vector<Vec3>>(s.vertices),
                                        int(s.faces.size()), faces);
}

struct Pair {
  std::shared_ptr<const PairShape> a, b;
  PairPose pa, pb;
  std::unique_ptr<fcl::CollisionObjectd> fa, fb;
};

std::vector<Pair> make_pairs(int ka, int kb) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u01(0, 1);
  std::vector<Pair> pairs;
  while (pairs.size() < 256) {
    Pair p;
    p.a = make_shape(ka, rng), p.b = make_shape(kb, rng);
    const auto rot = [&] { return Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix(); };
    p.pb = {Vec3::Zero(), rot()};
    const Mat3 Ra = ka == kPlate && kb == kPlate ? Mat3(p.pb.R * Eigen::AngleAxisd(u01(rng), Vec3::UnitZ())) : rot();
    const Vec3 dir = ka == kPlate && kb == kPlate ? Vec3(p.pb.R.col(2)) : Vec3(g(rng), g(rng), g(rng)).normalized();
    // touching by bisection on collide, then deeper
    double in = 0, out = p.a->radius + p.b->radius + 1e-3;
    PairManifold m;
    for (int it = 0; it < 50; ++it) {
      const double mid = 0.5 * (in + out);
      (collide(*p.a, {dir * mid, Ra}, *p.b, p.pb, 0, &m) ? in : out) = mid;
    }
    const double r = std::min(p.a->radius, p.b->radius);
    const double deep = ka == kPlate && kb == kPlate ? 0.0002 * u01(rng) : 0.05 * r * u01(rng);
    p.pa = {dir * (in - deep), Ra};
    const auto tf = [](const PairShape& s, const PairPose& q) {
      fcl::Transform3d t = fcl::Transform3d::Identity();
      t.linear() = q.R;
      t.translation() = q.x + q.R * (s.kind == PairShape::Kind::Polytope && !s.box ? Vec3::Zero() : s.centre);
      return t;
    };
    p.fa = std::make_unique<fcl::CollisionObjectd>(fcl_shape(*p.a), tf(*p.a, p.pa));
    p.fb = std::make_unique<fcl::CollisionObjectd>(fcl_shape(*p.b), tf(*p.b, p.pb));
    pairs.push_back(std::move(p));
  }
  return pairs;
}

void BM_Ours(benchmark::State& state) {
  const std::vector<Pair> pairs = make_pairs(int(state.range(0)), int(state.range(1)));
  PairManifold m;
  size_t i = 0;
  for (auto _ : state) {
    const Pair& p = pairs[i++ & 255];
    benchmark::DoNotOptimize(collide(*p.a, p.pa, *p.b, p.pb, 0, &m));
  }
  state.counters["ns_per_pair"] = benchmark::Counter(double(state.iterations()),
                                                     benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_Fcl(benchmark::State& state) {
  const std::vector<Pair> pairs = make_pairs(int(state.range(0)), int(state.range(1)));
  fcl::CollisionRequestd req(8, true);
  size_t i = 0;
  for (auto _ : state) {
    const Pair& p = pairs[i++ & 255];
    fcl::CollisionResultd res;
    benchmark::DoNotOptimize(fcl::collide(p.fa.get(), p.fb.get(), req, res));
  }
  state.counters["ns_per_pair"] = benchmark::Counter(double(state.iterations()),
                                                     benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

#define PAIRS(B)                                                                               \
  BENCHMARK(B)->ArgNames({"a", "b"})->Args({kSphere, kSphere})->Args({kSphere, kBox})          \
      ->Args({kSphere, kEllipsoid})->Args({kEllipsoid, kEllipsoid})->Args({kEllipsoid, kBox})  \
      ->Args({kBox, kBox})->Args({kPlate, kPlate})->Args({kBox, kHull})->Args({kHull, kHull})
PAIRS(BM_Ours);
PAIRS(BM_Fcl);

}  // namespace
}  // namespace lrigid

BENCHMARK_MAIN();
