// lrigid run --stream-field: a .pvd series streamed from disk gives byte for byte the
// trajectories of the same series held in memory. The streamed run takes frame 0 from the read
// that opened the series (it is not read twice), so this also checks that hand-over.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support/vti_writer.h"

namespace {

namespace fs = std::filesystem;
const std::string kLrigid = std::string(LRIGID_BINARY_DIR) + "/bin/lrigid";

// a 5 x 4 x 3 grid on [0, 2] x [0, 1.5] x [0, 1] m whose U, k and epsilon change with time
void write_frame(const std::string& path, double t) {
  lrigid::test::VtiGrid g;
  g.dims = {5, 4, 3};
  g.spacing = {0.5, 0.5, 0.5};
  g.time = t;
  ASSERT_TRUE(lrigid::test::write_vti(
      path, g, [t](int, const std::array<double, 3>& x, float U[3], float* k, float* eps) {
        U[0] = float(0.3 * (1 + t) * x[1]);
        U[1] = float(0.2 * std::sin(3 * t + x[0]));
        U[2] = float(0.05 * x[2]);
        *k = float(0.02 + 0.01 * std::sin(x[0] + 5 * t));
        *eps = float(0.01 + 0.003 * std::cos(x[2] + 2 * t));
      }));
}

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

int run(const std::string& scene, const fs::path& out, const char* mode) {
  const std::string cmd = kLrigid + " run " + scene + " -o " + out.string() +
                          " --quiet --threads 2 --stream-field " + mode + " > /dev/null 2>&1";
  const int rc = std::system(cmd.c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

TEST(CliStreamField, StreamedSeriesGivesTheInMemoryTrajectories) {
  const fs::path d = fs::temp_directory_path() / ("lrigid_stream_cli_" + std::to_string(getpid()));
  fs::remove_all(d);
  fs::create_directories(d / "s_vti");
  std::ofstream pvd(d / "s.pvd");
  pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\">\n<Collection>\n";
  for (int i = 0; i < 5; ++i) {
    write_frame((d / "s_vti" / ("f" + std::to_string(i) + ".vti")).string(), 0.1 * i);
    pvd << "<DataSet timestep=\"" << 0.1 * i << "\" file=\"s_vti/f" << i << ".vti\"/>\n";
  }
  pvd << "</Collection></VTKFile>\n";
  pvd.close();
  const std::string scene = (d / "scene.json").string();
  std::ofstream(scene) << R"({"version": 1,
    "fluid": {"density": 1.204, "kinematic_viscosity": 1.5e-5, "time": "clamp", "field": ")"
                       << (d / "s.pvd").string() << R"("},
    "gravity": [0, 0, -9.81],
    "effects": ["gravity", "buoyancy", "added_mass", "drag", "mean_flow", "turbulence"],
    "integrator": {"scheme": "splitting", "dt": 0.002}, "duration": 0.4, "seed": 3,
    "bodies": [{"name": "bead", "shape": {"type": "sphere", "radius": 0.002}, "density": 50,
                "count": 16, "spawn_box": [[0.8, 0.6, 0.4], [1.2, 0.9, 0.6]]}],
    "output": {"every": 0.02, "formats": ["csv"]}})";
  ASSERT_EQ(run(scene, d / "mem", "off"), 0);
  ASSERT_EQ(run(scene, d / "str", "on"), 0);
  const std::string a = slurp(d / "mem" / "trajectories.csv");
  ASSERT_GT(a.size(), 1000u);
  EXPECT_EQ(a, slurp(d / "str" / "trajectories.csv"));
  EXPECT_EQ(slurp(d / "mem" / "summary.json").find("field_stream"), std::string::npos);
  // frames 1-4 are read while stepping; frame 0 comes from the read that opened the series
  const std::string summary = slurp(d / "str" / "summary.json");
  EXPECT_NE(summary.find("\"frames_read\": 4"), std::string::npos) << summary;

  // a streamed run stopped mid-way (a file-size limit of 30 KiB on its trajectories,
  // exit 4) resumes from its last checkpoint, the stream picking up at the checkpoint's time,
  // and ends with the same trajectories
  const std::string cut = "(ulimit -f 30; exec " + kLrigid + " run " + scene + " -o " +
                          (d / "res").string() +
                          " --quiet --threads 2 --stream-field on --checkpoint-every 1e-9)"
                          " > /dev/null 2>&1";
  const int rc = std::system(("/bin/bash -c '" + cut + "'").c_str());
  ASSERT_TRUE(WIFEXITED(rc)) << rc;
  ASSERT_EQ(WEXITSTATUS(rc), 4);
  ASSERT_TRUE(fs::exists(d / "res" / "checkpoint" / "latest.json"));
  EXPECT_FALSE(fs::exists(d / "res" / "summary.json"));
  const std::string resume = kLrigid + " run " + scene + " --resume " + (d / "res").string() +
                             " --quiet --threads 1 --stream-field on > /dev/null 2>&1";
  ASSERT_EQ(std::system(resume.c_str()), 0);
  EXPECT_EQ(a, slurp(d / "res" / "trajectories.csv"));
  fs::remove_all(d);
}

}  // namespace
