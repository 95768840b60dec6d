// Building the model from a scene (runtime/src/compile/compile_model.cpp): failures of the
// added-mass solver are the input's fault and name the body type's key and its mesh file.
#include "compile/compile_model.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>

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

}  // namespace
}  // namespace lrigid
