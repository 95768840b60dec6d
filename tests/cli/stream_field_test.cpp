// lrigid run --stream-field (issue 11): a .pvd series streamed from disk gives byte for byte the
// trajectories of the same series held in memory. The streamed run takes frame 0 from the read
// that opened the series (it is not read twice), so this also checks that hand-over.
#include <gtest/gtest.h>
#include <unistd.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkFieldData.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLImageDataWriter.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;
const std::string kLrigid = std::string(LRIGID_BINARY_DIR) + "/bin/lrigid";

// a 5 x 4 x 3 grid on [0, 2] x [0, 1.5] x [0, 1] m whose U, k and epsilon change with time
void write_frame(const std::string& path, double t) {
  vtkNew<vtkImageData> img;
  img->SetDimensions(5, 4, 3);
  img->SetOrigin(0, 0, 0);
  img->SetSpacing(0.5, 0.5, 0.5);
  const int n = 60;
  vtkNew<vtkFloatArray> U, k, eps;
  vtkNew<vtkUnsignedCharArray> valid;
  U->SetName("U");
  U->SetNumberOfComponents(3);
  U->SetNumberOfTuples(n);
  k->SetName("k");
  k->SetNumberOfTuples(n);
  eps->SetName("epsilon");
  eps->SetNumberOfTuples(n);
  valid->SetName("valid");
  valid->SetNumberOfTuples(n);
  for (int p = 0; p < n; ++p) {
    const double x = 0.5 * (p % 5), y = 0.5 * ((p / 5) % 4), z = 0.5 * (p / 20);
    U->SetTuple3(p, 0.3 * (1 + t) * y, 0.2 * std::sin(3 * t + x), 0.05 * z);
    k->SetValue(p, float(0.02 + 0.01 * std::sin(x + 5 * t)));
    eps->SetValue(p, float(0.01 + 0.003 * std::cos(z + 2 * t)));
    valid->SetValue(p, 1);
  }
  img->GetPointData()->AddArray(U);
  img->GetPointData()->AddArray(k);
  img->GetPointData()->AddArray(eps);
  img->GetPointData()->AddArray(valid);
  vtkNew<vtkDoubleArray> nu, time;
  nu->SetName("kinematic_viscosity");
  nu->InsertNextValue(1.5e-5);
  time->SetName("time");
  time->InsertNextValue(t);
  img->GetFieldData()->AddArray(nu);
  img->GetFieldData()->AddArray(time);
  vtkNew<vtkXMLImageDataWriter> w;
  w->SetFileName(path.c_str());
  w->SetInputData(img);
  ASSERT_EQ(w->Write(), 1);
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
    "fluid": {"density": 1.204, "kinematic_viscosity": 1.5e-5, "field": ")"
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
  EXPECT_NE(slurp(d / "str" / "summary.json").find("field_stream"), std::string::npos);
  fs::remove_all(d);
}

}  // namespace
