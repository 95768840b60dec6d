// foam2grid on bad input and its file format: every failure names what is wrong, exits with
// the documented code and leaves no file behind; the grid file holds the documented arrays.
#include <gtest/gtest.h>
#include <vtkFloatArray.h>
#include <vtkStringArray.h>
#include <vtkUnsignedCharArray.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "foam2grid/case_fixture.h"
#include "foam2grid/vti_util.h"

namespace fs = std::filesystem;
using namespace foam2grid_test;

namespace {

std::string f2g() { return quote(foam2grid_bin()); }

// a private copy of the run tiny case in the test's work directory
std::string tiny_copy(const std::string& w) {
  const std::string c = w + "/tiny";
  EXPECT_EQ(run("cp -r " + quote(prepared_case("tiny")) + " " + quote(c)), 0);
  return c;
}

// the latest time directory name of a case
std::string latest_time(const std::string& c) {
  double best = -1;
  std::string name;
  for (const auto& e : fs::directory_iterator(c)) {
    const std::string n = e.path().filename().string();
    char* end = nullptr;
    const double v = std::strtod(n.c_str(), &end);
    if (e.is_directory() && end != n.c_str() && *end == '\0' && v > best) {
      best = v;
      name = n;
    }
  }
  return name;
}

// files in dir (names), without the case copy
std::vector<std::string> files_in(const std::string& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string n = e.path().filename().string();
    if (n != "tiny" && n != "tinyTransient") out.push_back(n);
  }
  return out;
}

struct Result {
  int rc;
  std::string out;
};

Result f2g_run(const std::string& args) {
  Result r;
  r.rc = run(f2g() + " " + args, &r.out);
  return r;
}

}  // namespace

TEST(Foam2gridCli, HelpDocumentsEveryFlagWithUnits) {
  const Result r = f2g_run("--help");
  EXPECT_EQ(r.rc, 0);
  for (const char* flag : {"--output", "--spacing", "--resolution", "--bounds", "--time",
                           "--fields", "--interpolation", "--source", "--info", "--version"}) {
    EXPECT_NE(r.out.find(flag), std::string::npos) << flag;
  }
  for (const char* unit : {"m/s", "m^2/s^2", "m^2/s^3", "m^2/s", " m"}) {
    EXPECT_NE(r.out.find(unit), std::string::npos) << unit;
  }
  // usage errors exit 2 and name the flag
  const Result bogus = f2g_run("--bogus");
  EXPECT_EQ(bogus.rc, 2);
  EXPECT_NE(bogus.out.find("--bogus"), std::string::npos) << bogus.out;
  // a typo names the flag it was meant to be
  const Result typo = f2g_run("case -o x.vti --spacng 0.1 --interpolaton=linear");
  EXPECT_EQ(typo.rc, 2);
  EXPECT_NE(typo.out.find("unknown flag \"--spacng\" (did you mean \"--spacing\"?)"),
            std::string::npos)
      << typo.out;
  EXPECT_NE(typo.out.find("unknown flag \"--interpolaton\" (did you mean \"--interpolation\"?)"),
            std::string::npos)
      << typo.out;
  const Result nan = f2g_run("case -o x.vti --spacing abc");
  EXPECT_EQ(nan.rc, 2);
  EXPECT_NE(nan.out.find("--spacing"), std::string::npos) << nan.out;
  EXPECT_EQ(f2g_run("").rc, 2);
  EXPECT_EQ(f2g_run("case").rc, 2);  // no -o
}

TEST(Foam2gridCli, MissingCaseDirectory) {
  const std::string w = work_dir("cli_missing_case");
  const Result r = f2g_run(quote(w + "/nowhere") + " -o " + quote(w + "/out.vti") + " -q");
  EXPECT_EQ(r.rc, 3) << r.out;
  EXPECT_NE(r.out.find("nowhere"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("not found"), std::string::npos) << r.out;
  EXPECT_TRUE(files_in(w).empty());
}

TEST(Foam2gridCli, NoMesh) {
  const std::string w = work_dir("cli_no_mesh");
  fs::create_directories(w + "/bare/system");
  fs::create_directories(w + "/bare/0");
  const Result r = f2g_run(quote(w + "/bare") + " -o " + quote(w + "/out.vti") + " -q");
  EXPECT_EQ(r.rc, 3) << r.out;
  EXPECT_NE(r.out.find("no mesh"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("polyMesh/faces"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(w + "/out.vti"));
}

TEST(Foam2gridCli, FieldNotWrittenAsInALaminarCase) {
  const std::string w = work_dir("cli_missing_field");
  const std::string c = tiny_copy(w);
  const std::string t = latest_time(c);
  fs::remove(c + "/" + t + "/epsilon");  // a laminar run writes no epsilon
  const Result r = f2g_run(quote(c) + " -o " + quote(w + "/out.vti") + " -q");
  EXPECT_EQ(r.rc, 3) << r.out;
  EXPECT_NE(r.out.find("field 'epsilon' not found at time " + t), std::string::npos) << r.out;
  EXPECT_TRUE(files_in(w).empty());
  // without epsilon requested the same case converts
  const Result ok = f2g_run(quote(c) + " -o " + quote(w + "/out.vti") + " --fields U,nut -q");
  EXPECT_EQ(ok.rc, 0) << ok.out;
}

TEST(Foam2gridCli, TimeNotWritten) {
  const std::string w = work_dir("cli_time");
  const Result r =
      f2g_run(quote(prepared_case("tiny")) + " -o " + quote(w + "/out.vti") + " --time 7.5 -q");
  EXPECT_EQ(r.rc, 3) << r.out;
  EXPECT_NE(r.out.find("--time 7.5: time not written"), std::string::npos) << r.out;
  EXPECT_TRUE(files_in(w).empty());
  const Result bad =
      f2g_run(quote(prepared_case("tiny")) + " -o " + quote(w + "/out.vti") + " --time soon -q");
  EXPECT_EQ(bad.rc, 2) << bad.out;
  EXPECT_NE(bad.out.find("--time 'soon'"), std::string::npos) << bad.out;
}

TEST(Foam2gridCli, NanInAField) {
  const std::string w = work_dir("cli_nan");
  const std::string c = tiny_copy(w);
  const std::string k = c + "/" + latest_time(c) + "/k";
  std::ifstream in(k);
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  // the value of cell 4 (the 5th line after the list's '(') becomes nan
  const std::size_t open = text.find('(', text.find("internalField"));
  std::size_t pos = open + 1;
  for (int i = 0; i < 4; ++i) pos = text.find('\n', pos + 1);
  const std::size_t end = text.find('\n', pos + 1);
  text.replace(pos + 1, end - pos - 1, "nan");
  std::ofstream(k) << text;
  const Result r = f2g_run(quote(c) + " -o " + quote(w + "/out.vti") + " -q");
  EXPECT_EQ(r.rc, 3) << r.out;
  EXPECT_NE(r.out.find("non-finite value"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("'k'"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("in cell 4"), std::string::npos) << r.out;
  EXPECT_TRUE(files_in(w).empty());
}

TEST(Foam2gridCli, BoundsOutsideTheMesh) {
  const std::string w = work_dir("cli_bounds");
  const Result r = f2g_run(quote(prepared_case("tiny")) + " -o " + quote(w + "/out.vti") +
                           " --bounds -0.5 0.5 0 0.4 0 0.3 -q");
  EXPECT_EQ(r.rc, 3) << r.out;
  EXPECT_NE(r.out.find("--bounds: x range [-0.5, 0.5] m lies outside the mesh"), std::string::npos)
      << r.out;
  const Result inverted = f2g_run(quote(prepared_case("tiny")) + " -o " + quote(w + "/out.vti") +
                                  " --bounds 0 1 0.3 0.1 0 0.3 -q");
  EXPECT_EQ(inverted.rc, 2) << inverted.out;
  EXPECT_NE(inverted.out.find("ymin = 0.3"), std::string::npos) << inverted.out;
  EXPECT_TRUE(files_in(w).empty());
}

TEST(Foam2gridCli, ZeroOrNegativeSpacing) {
  const std::string w = work_dir("cli_spacing");
  for (const char* h : {"0", "-0.01"}) {
    const Result r = f2g_run(quote(prepared_case("tiny")) + " -o " + quote(w + "/out.vti") +
                             " --spacing " + h + " -q");
    EXPECT_EQ(r.rc, 2) << r.out;
    EXPECT_NE(r.out.find(std::string("--spacing ") + h), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("must be a positive length"), std::string::npos) << r.out;
  }
  const Result res = f2g_run(quote(prepared_case("tiny")) + " -o " + quote(w + "/out.vti") +
                             " --resolution 10 1 10 -q");
  EXPECT_EQ(res.rc, 2) << res.out;
  EXPECT_TRUE(files_in(w).empty());
}

TEST(Foam2gridCli, GridTooLargeForMemory) {
  const std::string w = work_dir("cli_too_large");
  const Result r =
      f2g_run(quote(prepared_case("tiny")) + " -o " + quote(w + "/out.vti") + " --spacing 1e-5 -q");
  EXPECT_EQ(r.rc, 5) << r.out;
  EXPECT_NE(r.out.find("120001 x 40001 x 30001"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("would need about"), std::string::npos) << r.out;
  EXPECT_TRUE(files_in(w).empty());
}

TEST(Foam2gridCli, OutputCannotBeWritten) {
  const std::string w = work_dir("cli_output");
  const Result r =
      f2g_run(quote(prepared_case("tiny")) + " -o " + quote(w + "/no/such/out.vti") + " -q");
  EXPECT_EQ(r.rc, 4) << r.out;
  EXPECT_NE(r.out.find("no/such"), std::string::npos) << r.out;
  const Result ext = f2g_run(quote(prepared_case("tiny")) + " -o " + quote(w + "/out.txt") + " -q");
  EXPECT_EQ(ext.rc, 2) << ext.out;
  EXPECT_TRUE(files_in(w).empty());
}

TEST(Foam2gridCli, FailureKeepsAnEarlierOutputIntact) {
  const std::string w = work_dir("cli_keep");
  const std::string c = tiny_copy(w);
  const std::string out = w + "/out.vti";
  ASSERT_EQ(f2g_run(quote(c) + " -o " + quote(out) + " --spacing 0.05 -q").rc, 0);
  const auto size = fs::file_size(out);
  fs::remove(c + "/" + latest_time(c) + "/nut");
  EXPECT_EQ(f2g_run(quote(c) + " -o " + quote(out) + " --spacing 0.02 -q").rc, 3);
  EXPECT_EQ(fs::file_size(out), size);
  EXPECT_EQ(files_in(w), std::vector<std::string>{"out.vti"});  // no temporary left
}

TEST(Foam2gridFormat, ArraysFieldDataAndInvalidPoints) {
  const std::string w = work_dir("format");
  const std::string out = w + "/tiny.vti";
  const Result r =
      f2g_run(quote(prepared_case("tiny")) + " -o " + quote(out) + " --spacing 0.0137 -q");
  ASSERT_EQ(r.rc, 0) << r.out;
  vtkSmartPointer<vtkImageData> im = read_vti(out);
  // grid: origin at the mesh's lower corner, floor(L/H)+1 points (upper bound rounded inward)
  int d[3];
  double o[3], h[3];
  im->GetDimensions(d);
  im->GetOrigin(o);
  im->GetSpacing(h);
  const double len[3] = {1.2, 0.4, 0.3};
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(o[k], 0.0, 1e-12);
    EXPECT_DOUBLE_EQ(h[k], 0.0137);
    EXPECT_EQ(d[k], static_cast<int>(std::floor(len[k] / 0.0137)) + 1);
    EXPECT_LE(o[k] + (d[k] - 1) * h[k], len[k]);
  }
  vtkPointData* pd = im->GetPointData();
  auto* u = vtkFloatArray::SafeDownCast(pd->GetArray("U"));
  ASSERT_NE(u, nullptr);
  EXPECT_EQ(u->GetNumberOfComponents(), 3);
  for (const char* s : {"k", "epsilon", "nut"}) {
    auto* a = vtkFloatArray::SafeDownCast(pd->GetArray(s));
    ASSERT_NE(a, nullptr) << s;
    EXPECT_EQ(a->GetNumberOfComponents(), 1) << s;
  }
  auto* valid = vtkUnsignedCharArray::SafeDownCast(pd->GetArray("valid"));
  ASSERT_NE(valid, nullptr);
  // invalid points: inside the cube (0.3..0.45, 0.1333..0.2667, 0..0.15) and exactly 0
  vtkIdType ninvalid = 0, ncube = 0;
  for (vtkIdType i = 0; i < im->GetNumberOfPoints(); ++i) {
    double x[3];
    im->GetPoint(i, x);
    const bool in_cube = x[0] > 0.3 + 1e-9 && x[0] < 0.45 - 1e-9 && x[1] > 0.4 / 3 + 1e-9 &&
                         x[1] < 0.8 / 3 - 1e-9 && x[2] < 0.15 - 1e-9;
    ncube += in_cube;
    if (valid->GetValue(i) == 0) {
      ++ninvalid;
      EXPECT_TRUE(in_cube) << "invalid point outside the cube at " << x[0] << " " << x[1] << " "
                           << x[2];
      for (int k = 0; k < 3; ++k) EXPECT_EQ(u->GetComponent(i, k), 0.0f);
      EXPECT_EQ(pd->GetArray("k")->GetTuple1(i), 0.0);
      EXPECT_EQ(pd->GetArray("epsilon")->GetTuple1(i), 0.0);
      EXPECT_EQ(pd->GetArray("nut")->GetTuple1(i), 0.0);
    } else {
      EXPECT_FALSE(in_cube);
      EXPECT_GT(pd->GetArray("k")->GetTuple1(i), 0.0);
    }
  }
  EXPECT_EQ(ninvalid, ncube);
  EXPECT_GT(ncube, 1000);
  // field data
  vtkFieldData* fd = im->GetFieldData();
  ASSERT_NE(fd->GetArray("kinematic_viscosity"), nullptr);
  EXPECT_EQ(fd->GetArray("kinematic_viscosity")->GetDataType(), VTK_DOUBLE);
  EXPECT_DOUBLE_EQ(fd->GetArray("kinematic_viscosity")->GetTuple1(0),
                   1.5e-5);  // constant/transportProperties
  ASSERT_NE(fd->GetArray("time"), nullptr);
  EXPECT_DOUBLE_EQ(fd->GetArray("time")->GetTuple1(0),
                   std::stod(latest_time(prepared_case("tiny"))));
  auto* name = vtkStringArray::SafeDownCast(fd->GetAbstractArray("case_name"));
  ASSERT_NE(name, nullptr);
  EXPECT_EQ(name->GetValue(0), "tiny");
  auto* version = vtkStringArray::SafeDownCast(fd->GetAbstractArray("converter_version"));
  ASSERT_NE(version, nullptr);
  EXPECT_FALSE(version->GetValue(0).empty());

  // --fields: only those, plus valid; --resolution gives the point counts
  const std::string out2 = w + "/u_only.vti";
  ASSERT_EQ(f2g_run(quote(prepared_case("tiny")) + " -o " + quote(out2) +
                    " --fields U --resolution 13 5 4 -q")
                .rc,
            0);
  vtkSmartPointer<vtkImageData> im2 = read_vti(out2);
  EXPECT_EQ(im2->GetPointData()->GetNumberOfArrays(), 3);
  EXPECT_NE(im2->GetPointData()->GetArray("U"), nullptr);
  EXPECT_NE(im2->GetPointData()->GetArray("valid"), nullptr);
  EXPECT_NE(im2->GetPointData()->GetArray("wall_distance"), nullptr);
  im2->GetDimensions(d);
  im2->GetSpacing(h);
  EXPECT_EQ(d[0], 13);
  EXPECT_EQ(d[1], 5);
  EXPECT_EQ(d[2], 4);
  EXPECT_NEAR(h[0], 0.1, 1e-12);

  // --info reads it back
  const Result info = f2g_run("--info " + quote(out));
  EXPECT_EQ(info.rc, 0) << info.out;
  EXPECT_NE(info.out.find("kinematic_viscosity"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("% of the points (valid = 0)"), std::string::npos) << info.out;
  EXPECT_EQ(f2g_run("--info " + quote(w + "/none.vti")).rc, 3);
}

TEST(Foam2gridFormat, BinaryAndCompressedCaseGiveTheSameGrid) {
  const std::string w = work_dir("format_binary");
  const std::string c = tiny_copy(w);
  ASSERT_EQ(f2g_run(quote(c) + " -o " + quote(w + "/ascii.vti") + " --spacing 0.0137 -q").rc, 0);
  // OpenFOAM rewrites mesh and fields in binary; then gzip them all (OpenFOAM reads name.gz)
  ASSERT_EQ(run("cd " + quote(c) +
                " && export WM_PROJECT_DIR=/usr/share/openfoam && "
                "foamDictionary -entry writeFormat -set binary system/controlDict >/dev/null && "
                "/usr/bin/foamFormatConvert > log.foamFormatConvert 2>&1 && "
                "grep -q 'format      binary' constant/polyMesh/faces && "
                "gzip constant/polyMesh/faces " +
                latest_time(c) + "/U " + latest_time(c) + "/k"),
            0);
  ASSERT_EQ(f2g_run(quote(c) + " -o " + quote(w + "/binary.vti") + " --spacing 0.0137 -q").rc, 0);
  vtkSmartPointer<vtkImageData> a = read_vti(w + "/ascii.vti");
  vtkSmartPointer<vtkImageData> b = read_vti(w + "/binary.vti");
  ASSERT_EQ(a->GetNumberOfPoints(), b->GetNumberOfPoints());
  for (const char* f : {"U", "k", "epsilon", "nut", "valid", "wall_distance"}) {
    vtkDataArray* x = a->GetPointData()->GetArray(f);
    vtkDataArray* y = b->GetPointData()->GetArray(f);
    ASSERT_TRUE(x && y) << f;
    ASSERT_NE(y, nullptr) << f;
    double worst = 0;
    for (vtkIdType i = 0; i < x->GetNumberOfTuples(); ++i) {
      for (int k = 0; k < x->GetNumberOfComponents(); ++k) {
        worst = std::max(worst, std::fabs(x->GetComponent(i, k) - y->GetComponent(i, k)));
      }
    }
    // binary holds the same doubles as the 8-digit ascii text: identical results
    EXPECT_EQ(worst, 0.0) << f;
  }
}

TEST(Foam2gridSeries, TransientCaseBecomesAPvdTimeSeries) {
  const std::string w = work_dir("series");
  const std::string c = prepared_case("tinyTransient");
  const std::string pvd = w + "/flow.pvd";
  const Result r = f2g_run(quote(c) + " -o " + quote(pvd) + " --time all --spacing 0.02 -q");
  ASSERT_EQ(r.rc, 0) << r.out;
  std::ifstream in(pvd);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  EXPECT_NE(text.find("<VTKFile type=\"Collection\""), std::string::npos);
  // every written time but 0, ascending, with files relative to the .pvd
  std::vector<double> case_times;
  for (const auto& e : fs::directory_iterator(c)) {
    const std::string n = e.path().filename().string();
    char* end = nullptr;
    const double v = std::strtod(n.c_str(), &end);
    if (e.is_directory() && end != n.c_str() && *end == '\0' && v > 0) case_times.push_back(v);
  }
  std::sort(case_times.begin(), case_times.end());
  ASSERT_GE(case_times.size(), 2u);
  const std::regex ds(R"re(<DataSet timestep="([^"]*)"[^>]*file="([^"]*)")re");
  std::vector<double> times;
  std::vector<double> k_means;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), ds); it != std::sregex_iterator();
       ++it) {
    const double t = std::stod((*it)[1]);
    const std::string file = (*it)[2];
    times.push_back(t);
    EXPECT_EQ(file.rfind("flow_vti/", 0), 0u) << file;
    ASSERT_TRUE(fs::exists(w + "/" + file)) << file;
    vtkSmartPointer<vtkImageData> im = read_vti(w + "/" + file);
    EXPECT_DOUBLE_EQ(im->GetFieldData()->GetArray("time")->GetTuple1(0), t);
    vtkDataArray* k = im->GetPointData()->GetArray("k");
    double sum = 0;
    for (vtkIdType i = 0; i < k->GetNumberOfTuples(); ++i) sum += k->GetTuple1(i);
    k_means.push_back(sum);
  }
  ASSERT_EQ(times.size(), case_times.size());
  for (std::size_t i = 0; i < times.size(); ++i) EXPECT_DOUBLE_EQ(times[i], case_times[i]);
  EXPECT_NE(k_means.front(), k_means.back());  // the fields change in time
  const Result info = f2g_run("--info " + quote(pvd));
  EXPECT_EQ(info.rc, 0) << info.out;
  EXPECT_NE(info.out.find("collection of " + std::to_string(times.size()) + " grids"),
            std::string::npos)
      << info.out;
  // a .vti output with --time all is a usage error
  EXPECT_EQ(f2g_run(quote(c) + " -o " + quote(w + "/x.vti") + " --time all -q").rc, 2);
}

TEST(Foam2gridDecomposed, ProcessorDirectoriesGiveTheReconstructedGrid) {
  const std::string w = work_dir("decomposed");
  const std::string c = prepared_case("tiny", "_decomposed", "/usr/bin/decomposePar -latestTime");
  ASSERT_TRUE(fs::exists(c + "/processor1"));
  const Result r1 = f2g_run(quote(c) + " -o " + quote(w + "/recon.vti") +
                            " --spacing 0.0137 --source reconstructed -q");
  ASSERT_EQ(r1.rc, 0) << r1.out;
  const Result r2 = f2g_run(quote(c) + " -o " + quote(w + "/decomp.vti") +
                            " --spacing 0.0137 --source decomposed");
  ASSERT_EQ(r2.rc, 0) << r2.out;
  EXPECT_NE(r2.out.find("decomposed, 2 processors"), std::string::npos) << r2.out;
  vtkSmartPointer<vtkImageData> a = read_vti(w + "/recon.vti");
  vtkSmartPointer<vtkImageData> b = read_vti(w + "/decomp.vti");
  for (const char* f : {"U", "k", "epsilon", "nut", "valid", "wall_distance"}) {
    vtkDataArray* x = a->GetPointData()->GetArray(f);
    vtkDataArray* y = b->GetPointData()->GetArray(f);
    ASSERT_TRUE(x && y) << f;
    double worst = 0, range = 0;
    for (vtkIdType i = 0; i < x->GetNumberOfTuples(); ++i) {
      for (int k = 0; k < x->GetNumberOfComponents(); ++k) {
        worst = std::max(worst, std::fabs(x->GetComponent(i, k) - y->GetComponent(i, k)));
        range = std::max(range, std::fabs(x->GetComponent(i, k)));
      }
    }
    // same values up to the summation order of the point interpolation and float32 rounding
    EXPECT_LE(worst, 1e-6 * range) << f;
  }
}
