// Building the model from a scene (runtime/src/compile/compile_model.cpp): failures of the
// added-mass solver are the input's fault and name the body type's key and its mesh file.
#include "compile/compile_model.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "integrate/simulation.h"
#include "support/fixture.h"
#include "util/error.h"

namespace lrigid {
namespace {

// The added-mass provider's runtime failure, as the boundary elements throw it.
AddedMass no_solution(const Shape&, double, int) {
  throw Error(ExitCode::Runtime, "boundary element method: no finite solution (degenerate mesh?)");
}

TEST(CompileModel, AddedMassFailureOnAMeshIsBadInputNamingTheFile) {
  Scene s = test::sphere_scene(0.01, 500, 1000, 1e-6);
  s.file = "scene.json";
  s.bodies[0].shape = Shape::from_mesh(
      std::make_shared<const TriangleMesh>(test::polygon_prism(8, 0.01, 0.002)), "leaf.obj");
  FluidField f = FluidField::uniform(Vec3::Zero(), 0, 0, s.kinematic_viscosity, s.drift);
  try {
    compile_model(s, std::move(f), no_solution);
    FAIL() << "compiled";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::BadInput) << e.what();
    const std::string m = e.what();
    EXPECT_NE(m.find("scene.json"), std::string::npos) << m;
    EXPECT_NE(m.find("bodies[0].shape.file"), std::string::npos) << m;
    EXPECT_NE(m.find("leaf.obj"), std::string::npos) << m;
    EXPECT_NE(m.find("no finite solution"), std::string::npos) << m;
  }
}

TEST(CompileModel, OtherErrorsOfTheProviderKeepTheirCodeAndNameTheKey) {
  Scene s = test::sphere_scene(0.01, 500, 1000, 1e-6);
  s.file = "scene.json";
  FluidField f = FluidField::uniform(Vec3::Zero(), 0, 0, s.kinematic_viscosity, s.drift);
  try {
    compile_model(s, std::move(f), [](const Shape&, double, int) -> AddedMass {
      throw Error(ExitCode::Resource, "out of memory");
    });
    FAIL() << "compiled";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::Resource) << e.what();
    EXPECT_NE(std::string(e.what()).find("scene.json: bodies[0].shape: out of memory"),
              std::string::npos) << e.what();
  }
}

// Body entries that differ only in where and how many bodies start (name, count, position,
// orientation, velocity) step alike (BodyType::steps_as: the batched step takes them in the same
// blocks); another density or friction, or an entry of several variants, does not. A body then
// ends bitwise where it ends stepped alone.
TEST(CompileModel, EntriesThatDifferOnlyInPlacementStepAlike) {
  Scene s = test::sphere_scene(0.01, 500, 1.2, 1.5e-5);
  s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::Drag, Effect::AddedMass});
  s.duration = 0.2;
  s.dt = 1e-3;
  BodySpec a = s.bodies[0];
  a.name = "pebble";
  a.shape = Shape::ellipsoid(0.02, 0.015, 0.01);
  a.density = 800;
  a.position = Vec3(0, 0, 1);
  a.angular_velocity = Vec3(0, 0, 2);
  BodySpec b = a;
  b.name = "another pebble";
  b.count = 2;
  b.position = Vec3(1, 0, 2);
  b.orientation = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
  b.velocity = Vec3(0.5, 0, 0);
  BodySpec denser = a, rougher = a, varied = a;
  denser.density = 900;
  rougher.contact.friction = 0.9;
  rougher.friction_given = true;
  varied.variants = 3;
  varied.count = 3;
  varied.size_min = 0.9;
  varied.size_max = 1.1;
  s.bodies = {a, b, denser, rougher, varied};
  const Model m = test::compile(s);
  ASSERT_EQ(m.types.size(), 7u);
  const std::vector<int> expected = {0, 0, 2, 3, 4, 5, 6};
  for (size_t t = 0; t < m.types.size(); ++t)
    EXPECT_EQ(m.types[t].steps_as, expected[t]) << "type " << t << " (" << m.types[t].name << ")";
  ASSERT_EQ(step_kind(m, m.types[1], nullptr), StepKind::Batched);

  // the two pebbles of the second entry: stepped in a block with the first entry's, and alone
  Scene shared = s, alone = s;
  shared.bodies = {a, b};
  alone.bodies = {b};
  const Model ms = test::compile(shared), ma = test::compile(alone);
  State with = initial_state(ms, shared), without = initial_state(ma, alone);
  RunOptions o;
  o.threads = 1;
  simulate(ms, &with, o);
  simulate(ma, &without, o);
  for (size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(with.x[1 + k], without.x[k]) << k;
    EXPECT_EQ(with.q[1 + k].coeffs(), without.q[k].coeffs()) << k;
    EXPECT_EQ(with.v[1 + k], without.v[k]) << k;
    EXPECT_EQ(with.w[1 + k], without.w[k]) << k;
  }
  EXPECT_LT(with.x[1].z(), 2 - 0.1) << "it fell";
}

// "spawn": {"surface": "solids", "box": ..., "offset": m}: every body starts in the fluid, within
// offset + one grid spacing of a solid point, inside the box widened by the same; the places
// follow from the seed; a box without solids and a uniform flow are refused naming the key.
TEST(CompileModel, ASpawnOnTheSolidsSurfacePlacesBodiesNextToThemInTheFluid) {
  const GridGeometry g = test::grid_geometry(12, 10, 8, Vec3::Zero(), Vec3::Constant(0.5));
  auto solid = [](const Vec3& x) {
    return x.x() >= 2 && x.x() <= 3.5 && x.y() >= 1.5 && x.y() <= 3 && x.z() <= 1.5;
  };
  const RawGridFrame f = test::grid_frame(g, [&](const Vec3& x, Vec3* U, double* k, double* e) {
    *U = Vec3(1, 0, 0);
    *k = 0.1;
    *e = 0.05;
    return !solid(x);
  });
  const FluidField field = FluidField::grid(g, {f}, 1.5e-5, Drift::Stationary, TimeMode::Clamp);
  std::vector<Vec3> solid_points;
  for (size_t p = 0; p < g.points(); ++p)
    if (!f.valid[p]) {
      int c[3];
      grid_point_indices(g, p, c);
      solid_points.push_back(Vec3(c[0], c[1], c[2]) * 0.5);
    }
  Scene s = test::sphere_scene(0.01, 500, 1.2, 1.5e-5, 300);
  s.uniform_field = false;
  s.bodies[0].spawn_on_solids = true;
  s.bodies[0].spawn_surface_box = true;
  s.bodies[0].box_lo = Vec3(0, 0, 0);
  s.bodies[0].box_hi = Vec3(6, 2.2, 5);  // the block's sides facing -x, -y, +x and its top
  for (const double offset : {0.0, 0.1, 0.4}) {
    s.bodies[0].spawn_offset = offset;
    const Model m = test::compile(s, field);
    const State st = initial_state(m, s);
    size_t top = 0;
    for (size_t i = 0; i < st.size(); ++i) {
      const Vec3& x = st.x[i];
      FluidSample fs;
      EXPECT_TRUE(m.field.sample(x, 0.0, false, &fs)) << "in the fluid: " << x.transpose();
      double nearest = 1e30;
      for (const Vec3& p : solid_points) nearest = std::min(nearest, (x - p).norm());
      EXPECT_LE(nearest, offset + 0.5) << "offset " << offset << ": " << x.transpose();
      EXPECT_LE(x.y(), 2.2 + 0.25 + 1e-12) << "within the box and half a spacing";
      top += x.z() > 1.5;
    }
    EXPECT_GT(top, 0u) << "some on the top face";
    EXPECT_LT(top, st.size()) << "some on the sides";
    // the same seed, the same places; another, others
    EXPECT_EQ(initial_state(m, s).x, st.x);
    Scene other = s;
    other.seed = s.seed + 1;
    EXPECT_NE(initial_state(test::compile(other, field), other).x, st.x);
  }
  Scene empty = s;
  empty.bodies[0].box_lo = Vec3(4.5, 4, 0);
  empty.bodies[0].box_hi = Vec3(5.5, 4.5, 3);
  try {
    test::compile(empty, field);
    ADD_FAILURE() << "a box without solids was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bodies[0].spawn.box: no surface of the grid's solids"),
              std::string::npos)
        << e.what();
    EXPECT_EQ(e.code(), ExitCode::BadInput);
  }
  Scene uniform = s;
  uniform.uniform_field = true;
  EXPECT_THROW(test::compile(uniform), Error) << "a uniform flow has no solids";
}

}  // namespace
}  // namespace lrigid
