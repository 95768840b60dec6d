// Disk cache of BEM tensors (runtime/src/io/added_mass_cache.cpp).
#include "io/added_mass_cache.h"

#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>

#include "body/tessellate.h"

namespace lrigid {
namespace {

namespace fs = std::filesystem;

class CacheTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("lrigid_cache_test_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    ::setenv("LRIGID_CACHE_DIR", dir_.c_str(), 1);
  }
  void TearDown() override {
    ::unsetenv("LRIGID_CACHE_DIR");
    fs::remove_all(dir_);
  }
  fs::path dir_;
};

TEST_F(CacheTest, DirectoryFromEnvironment) {
  EXPECT_EQ(added_mass_cache_dir(), dir_.string());
  ::unsetenv("LRIGID_CACHE_DIR");
  ::setenv("XDG_CACHE_HOME", "/x/y", 1);
  EXPECT_EQ(added_mass_cache_dir(), "/x/y/lrigid");
  ::unsetenv("XDG_CACHE_HOME");
  ::setenv("HOME", "/home/z", 1);
  EXPECT_EQ(added_mass_cache_dir(), "/home/z/.cache/lrigid");
}

TEST_F(CacheTest, StoresReadsAndRewritesCorruptEntries) {
  const Shape box = Shape::box(0.3, 0.2, 0.1);
  const AddedMass direct = added_mass(box, 1000.0, 200);
  const AddedMass first = cached_added_mass(box, 1000.0, 200);
  EXPECT_LT((first.tensor - direct.tensor).norm(), 1e-12 * direct.tensor.norm());
  EXPECT_EQ(first.panels, direct.panels);
  const std::string file = added_mass_cache_file(box, 200);
  ASSERT_TRUE(fs::exists(file));
  EXPECT_EQ(fs::path(file).parent_path(), dir_);

  // the entry is really read: doctor it (still valid) and see the doctored value come back,
  // scaled by the fluid density
  nlohmann::json j;
  {
    std::ifstream in(file);
    j = nlohmann::json::parse(in);
  }
  j["tensor_per_unit_density"][0][0] = 0.125;
  {
    std::ofstream out(file);
    out << j.dump();
  }
  EXPECT_DOUBLE_EQ(cached_added_mass(box, 2.0, 200).tensor(0, 0), 0.25);

  // corrupt: ignored, recomputed and rewritten
  {
    std::ofstream out(file);
    out << "{\"format\": 1, \"key\": tru";
  }
  const AddedMass again = cached_added_mass(box, 1000.0, 200);
  EXPECT_LT((again.tensor - direct.tensor).norm(), 1e-12 * direct.tensor.norm());
  std::ifstream in(file);
  EXPECT_NO_THROW(nlohmann::json::parse(in));
  int tmp_files = 0;
  for (const auto& e : fs::directory_iterator(dir_))
    tmp_files += e.path().filename().string().find(".tmp") != std::string::npos;
  EXPECT_EQ(tmp_files, 0);
}

TEST_F(CacheTest, KeyDependsOnGeometryAndPanels) {
  const Shape a = Shape::box(0.3, 0.2, 0.1), b = Shape::box(0.3, 0.2, 0.11);
  EXPECT_NE(added_mass_cache_file(a, 200), added_mass_cache_file(b, 200));
  EXPECT_NE(added_mass_cache_file(a, 200), added_mass_cache_file(a, 300));
  EXPECT_EQ(added_mass_cache_file(a, 0), added_mass_cache_file(a, kDefaultPanels));
  // meshes: every vertex bit counts
  auto m1 = std::make_shared<TriangleMesh>(tessellate(Shape::box(1, 1, 1), 100));
  auto m2 = std::make_shared<TriangleMesh>(*m1);
  m2->vertices[3].x() = std::nextafter(m2->vertices[3].x(), 10.0);
  const Shape s1 = Shape::from_mesh(m1, "a.obj"), s2 = Shape::from_mesh(m2, "a.obj");
  EXPECT_NE(added_mass_cache_file(s1, 200), added_mass_cache_file(s2, 200));
  EXPECT_EQ(added_mass_cache_file(s1, 200),
            added_mass_cache_file(Shape::from_mesh(m1, "other/name.stl"), 200));
  // analytic shapes bypass the cache
  const AddedMass s = cached_added_mass(Shape::sphere(1), 1.0);
  EXPECT_EQ(s.method, "analytic");
  EXPECT_FALSE(fs::exists(dir_));
}

TEST_F(CacheTest, UnwritableCacheStillComputes) {
  ::setenv("LRIGID_CACHE_DIR", "/proc/lrigid-not-writable", 1);
  const AddedMass am = cached_added_mass(Shape::box(0.3, 0.2, 0.1), 1.0, 100);
  EXPECT_EQ(am.method, "bem");
  EXPECT_GT(am.tensor(0, 0), 0);
}

}  // namespace
}  // namespace lrigid
