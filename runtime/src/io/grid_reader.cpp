#include "io/grid_reader.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkXMLImageDataReader.h>

#include <algorithm>
#include <cmath>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>
#include <cstdlib>
#include <unistd.h>

#include "util/error.h"

namespace lrigid {

namespace fs = std::filesystem;

namespace {

std::string fmt(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// VTK reports a broken file through its error events; printed, they come before lrigid's own
// message and name no key. The first one is kept (the text after "(0x...): ", one line) for
// lrigid's error, and none is printed.
void keep_first_vtk_error(vtkObject*, unsigned long event, void* client, void* call) {
  auto* first = static_cast<std::string*>(client);
  if (event != vtkCommand::ErrorEvent || !first->empty() || !call) return;
  std::string m = static_cast<const char*>(call);
  if (const size_t p = m.find("): "); p != std::string::npos) m = m.substr(p + 3);
  while (!m.empty() && (m.back() == '\n' || m.back() == ' ')) m.pop_back();
  for (char& c : m)
    if (c == '\n') c = ' ';
  *first = m.empty() ? "unspecified error" : m;
}

// The numbers of one header attribute, each read whole: "0.1 0.x 0.1" is refused where VTK
// would read 0 for the letter and shear the grid.
std::vector<double> header_numbers(const std::string& path, const std::string& tag,
                                   const std::string& key, size_t count) {
  const std::regex attr("\\b" + key + "=\"([^\"]*)\"");
  std::smatch m;
  if (!std::regex_search(tag, m, attr))
    fail_input(path, key, "missing from the header's <" + tag.substr(1, tag.find(' ') - 1) + ">");
  std::istringstream in(m[1].str());
  std::vector<double> v;
  std::string word;
  while (in >> word) {
    char* end = nullptr;
    const double x = std::strtod(word.c_str(), &end);
    if (end == word.c_str() || *end != '\0' || !std::isfinite(x))
      fail_input(path, key, "expected " + std::to_string(count) + " finite numbers, got \"" +
                                m[1].str() + "\"");
    v.push_back(x);
  }
  if (v.size() != count)
    fail_input(path, key, "expected " + std::to_string(count) + " numbers, got \"" + m[1].str() +
                              "\"");
  return v;
}

// Checks the XML header before VTK reads the file: numbers well formed, the piece's extent the
// whole extent, and a point count that fits in memory (a typo in the extent could ask for 1e15).
void check_vti_header(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(1 << 16, '\0');
  in.read(&head[0], static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  const size_t i = head.find("<ImageData");
  const size_t j = head.find("<Piece");
  if (i == std::string::npos || j == std::string::npos) return;  // VTK's reader will say
  const std::string image = head.substr(i, head.find('>', i) - i);
  const std::string piece = head.substr(j, head.find('>', j) - j);
  const auto whole = header_numbers(path, image, "WholeExtent", 6);
  header_numbers(path, image, "Origin", 3);
  const auto spacing = header_numbers(path, image, "Spacing", 3);
  const auto extent = header_numbers(path, piece, "Extent", 6);
  for (int a = 0; a < 3; ++a)
    if (!(spacing[a] > 0)) fail_input(path, "Spacing", "must be > 0 on every axis");
  if (extent != whole)
    fail_input(path, "Extent", "the piece's extent differs from WholeExtent (one piece expected)");
  long double points = 1;
  for (int a = 0; a < 3; ++a) {
    if (whole[2 * a] != std::floor(whole[2 * a]) || whole[2 * a + 1] != std::floor(whole[2 * a + 1]))
      fail_input(path, "WholeExtent", "must be integers");
    points *= static_cast<long double>(whole[2 * a + 1] - whole[2 * a] + 1);
  }
  // U, k, epsilon, valid, wall distance as doubles here, and VTK's copy as floats
  const long double bytes = points * (7 * 8 + 7 * 4);
  const long double ram = static_cast<long double>(sysconf(_SC_PHYS_PAGES)) *
                          static_cast<long double>(sysconf(_SC_PAGESIZE));
  if (ram > 0 && bytes > ram) {
    std::ostringstream m;
    m << "WholeExtent needs " << static_cast<double>(points) << " points, about "
      << static_cast<double>(bytes / 1e9) << " GB, more than this machine's "
      << static_cast<double>(ram / 1e9) << " GB";
    throw Error(ExitCode::Resource, path + ": " + m.str());
  }
}

void read_vti(const std::string& path, GridGeometry* geom, RawGridFrame* frame, double* nu) {
  std::error_code ec;  // the non-throwing overload: an over-long or odd name is a bad input too
  if (!fs::is_regular_file(path, ec)) fail_input(path, "", "grid file not found");
  // VTK's reader cannot tell an unreadable file from one of another kind
  if (!std::ifstream(path, std::ios::binary))
    fail_input(path, "", std::string("cannot be read: ") + std::strerror(errno));
  vtkNew<vtkXMLImageDataReader> reader;
  if (!reader->CanReadFile(path.c_str()))
    fail_input(path, "", "not a VTK XML ImageData (.vti) file");
  check_vti_header(path);
  reader->SetFileName(path.c_str());
  std::string vtk_error;
  vtkNew<vtkCallbackCommand> on_message;
  on_message->SetCallback(keep_first_vtk_error);
  on_message->SetClientData(&vtk_error);
  reader->AddObserver(vtkCommand::ErrorEvent, on_message);
  reader->AddObserver(vtkCommand::WarningEvent, on_message);
  reader->Update();
  if (!vtk_error.empty()) fail_input(path, "", "VTK's .vti reader failed: " + vtk_error);
  vtkImageData* img = reader->GetOutput();
  if (!img || reader->GetErrorCode() != 0) fail_input(path, "", "cannot be read as .vti");
  int dims[3];
  img->GetDimensions(dims);
  for (int a = 0; a < 3; ++a)
    if (dims[a] < 2)
      fail_input(path, "dimensions", "need at least 2 points per axis, got " +
                                         std::to_string(dims[0]) + " x " + std::to_string(dims[1]) +
                                         " x " + std::to_string(dims[2]));
  double origin[3], spacing[3];
  img->GetOrigin(origin);
  img->GetSpacing(spacing);
  for (int a = 0; a < 3; ++a) {
    geom->n[a] = dims[a];
    geom->origin[a] = origin[a];
    geom->spacing[a] = spacing[a];
    if (!(spacing[a] > 0) || !std::isfinite(origin[a]))
      fail_input(path, "spacing", "must be positive and finite");
  }
  const size_t np = geom->points();
  vtkPointData* pd = img->GetPointData();
  auto array = [&](const char* name, int comps, bool required) -> vtkDataArray* {
    vtkDataArray* a = pd->GetArray(name);
    if (!a) {
      if (required) fail_input(path, name, "point array missing");
      return nullptr;
    }
    if (a->GetNumberOfComponents() != comps || size_t(a->GetNumberOfTuples()) != np)
      fail_input(path, name, "expected " + std::to_string(np) + " tuples of " +
                                 std::to_string(comps) + " components, got " +
                                 std::to_string(a->GetNumberOfTuples()) + " of " +
                                 std::to_string(a->GetNumberOfComponents()));
    return a;
  };
  vtkDataArray* U = array("U", 3, true);
  vtkDataArray* k = array("k", 1, true);
  vtkDataArray* eps = array("epsilon", 1, true);
  vtkDataArray* valid = array("valid", 1, false);
  vtkDataArray* wall = array("wall_distance", 1, false);  // older grids have none
  frame->U.resize(3 * np);
  frame->k.resize(np);
  frame->epsilon.resize(np);
  frame->valid.assign(np, 1);
  size_t nvalid = 0;
  for (size_t p = 0; p < np; ++p) {
    const bool ok = !valid || valid->GetComponent(p, 0) != 0;
    frame->valid[p] = ok ? 1 : 0;
    nvalid += ok;
    double u[3];
    U->GetTuple(p, u);
    const double kk = k->GetComponent(p, 0), ee = eps->GetComponent(p, 0);
    if (!std::isfinite(u[0]) || !std::isfinite(u[1]) || !std::isfinite(u[2]))
      fail_input(path, "U", "non-finite value at point " + std::to_string(p));
    if (!std::isfinite(kk)) fail_input(path, "k", "non-finite value at point " + std::to_string(p));
    if (!std::isfinite(ee))
      fail_input(path, "epsilon", "non-finite value at point " + std::to_string(p));
    if (ok && kk < 0)
      fail_input(path, "k", "negative value " + fmt(kk) + " at point " + std::to_string(p));
    if (ok && ee < 0)
      fail_input(path, "epsilon", "negative value " + fmt(ee) + " at point " + std::to_string(p));
    // the ranges of a scene's uniform flow (docs/scene-format.md): beyond them the bodies'
    // forces overflow and they leave the grid or fail in the first step
    if (ok && !(std::max({std::abs(u[0]), std::abs(u[1]), std::abs(u[2])}) <= 1e5))
      fail_input(path, "U", "value (" + fmt(u[0]) + ", " + fmt(u[1]) + ", " + fmt(u[2]) +
                                ") at point " + std::to_string(p) +
                                ": components must be in [-1e5, 1e5] m/s");
    if (ok && kk > 1e8)
      fail_input(path, "k", "value " + fmt(kk) + " at point " + std::to_string(p) +
                                ": must be in [0, 1e8] m^2/s^2");
    if (ok && ee > 1e12)
      fail_input(path, "epsilon", "value " + fmt(ee) + " at point " + std::to_string(p) +
                                      ": must be in [0, 1e12] m^2/s^3");
    for (int a = 0; a < 3; ++a) frame->U[3 * p + a] = float(u[a]);
    frame->k[p] = float(kk);
    frame->epsilon[p] = float(ee);
  }
  if (nvalid == 0) fail_input(path, "valid", "no valid point: the grid is empty");
  frame->wall_distance.clear();
  if (wall) {
    frame->wall_distance.resize(np);
    for (size_t p = 0; p < np; ++p) {
      const double d = wall->GetComponent(p, 0);
      if (!std::isfinite(d))
        fail_input(path, "wall_distance", "non-finite value at point " + std::to_string(p));
      frame->wall_distance[p] = float(d);
    }
  }
  *nu = 0;
  if (vtkFieldData* fd = img->GetFieldData())
    if (vtkDataArray* a = fd->GetArray("kinematic_viscosity"); a && a->GetNumberOfTuples() > 0)
      *nu = a->GetComponent(0, 0);
  frame->time = 0;
  if (vtkFieldData* fd = img->GetFieldData())
    if (vtkDataArray* a = fd->GetArray("time"); a && a->GetNumberOfTuples() > 0)
      frame->time = a->GetComponent(0, 0);
}

}  // namespace

namespace {

// the .pvd's entries (time, file path), sorted by time and checked for distinct times; a .vti is
// one entry at the time it records
std::vector<std::pair<double, std::string>> series_entries(const std::string& path) {
  const std::string ext = fs::path(path).extension().string();
  if (ext == ".vti") return {{0.0, path}};
  if (ext != ".pvd") fail_input(path, "", "grid must be a .vti or .pvd file");
  std::ifstream in(path);
  if (!in) fail_input(path, "", "cannot be read");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  // <DataSet timestep="0.5" ... file="x_0001.vti"/>, attributes in any order
  const std::regex dataset("<DataSet\\b([^>]*)>");
  const std::regex ts("timestep\\s*=\\s*\"([^\"]*)\"");
  const std::regex file("file\\s*=\\s*\"([^\"]*)\"");
  std::vector<std::pair<double, std::string>> entries;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), dataset);
       it != std::sregex_iterator(); ++it) {
    const std::string attrs = (*it)[1];
    std::smatch mt, mf;
    if (!std::regex_search(attrs, mf, file)) fail_input(path, "DataSet", "entry without file=");
    double t = 0;
    if (std::regex_search(attrs, mt, ts)) {
      try {
        t = std::stod(mt[1]);
      } catch (...) {
        fail_input(path, "DataSet.timestep", "not a number: \"" + std::string(mt[1]) + "\"");
      }
      // "nan" and "inf" read as numbers; a NaN time would then be named as a repeated one
      if (!std::isfinite(t))
        fail_input(path, "DataSet.timestep", "must be a finite time in s, got \"" +
                                                 std::string(mt[1]) + "\"");
    }
    entries.emplace_back(t, (fs::path(path).parent_path() / std::string(mf[1])).string());
  }
  if (entries.empty()) fail_input(path, "", "no <DataSet> entries: the series is empty");
  std::stable_sort(entries.begin(), entries.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (size_t i = 1; i < entries.size(); ++i)
    if (!(entries[i].first > entries[i - 1].first))
      fail_input(path, "DataSet.timestep",
                 "times must be distinct, " + fmt(entries[i].first) + " repeats");
  return entries;
}

// entry i of a series with its geometry and the viscosity it records
RawGridFrame read_entry(const GridSeries& s, size_t i, GridGeometry* geom, double* nu) {
  RawGridFrame f;
  if (!s.is_series) {
    read_vti(s.files[i], geom, &f, nu);
    return f;
  }
  try {
    read_vti(s.files[i], geom, &f, nu);
  } catch (const Error& e) {
    // name the series and the entry as well as the frame file
    fail_input(s.path, "DataSet[" + std::to_string(i) + "]", e.what());
  }
  f.time = s.times[i];
  return f;
}

}  // namespace

RawGridFrame GridSeries::load(size_t i) const {
  GridGeometry geom;
  double nu = 0;
  RawGridFrame f = read_entry(*this, i, &geom, &nu);
  if (geom.n[0] != geometry.n[0] || geom.n[1] != geometry.n[1] || geom.n[2] != geometry.n[2] ||
      (geom.origin - geometry.origin).norm() > 1e-9 ||
      (geom.spacing - geometry.spacing).norm() > 1e-9)
    fail_input(files[i], "", "grid differs from the series' first grid " + files[0]);
  if (f.wall_distance.empty() != !has_wall_distance)
    fail_input(files[i], "wall_distance",
               std::string(has_wall_distance ? "point array missing; the series' first grid "
                                             : "present, but the series' first grid ") +
                   files[0] + (has_wall_distance ? " has it" : " has none"));
  return f;
}

GridSeries open_grid_series(const std::string& path, RawGridFrame* first) {
  GridSeries s;
  s.path = path;
  s.is_series = fs::path(path).extension().string() == ".pvd";
  for (auto& [t, file] : series_entries(path)) {
    s.times.push_back(t);
    s.files.push_back(std::move(file));
  }
  // the first frame gives the geometry the others must match
  RawGridFrame f0 = read_entry(s, 0, &s.geometry, &s.kinematic_viscosity);
  s.has_wall_distance = !f0.wall_distance.empty();
  if (!s.is_series) s.times[0] = f0.time;
  if (first) *first = std::move(f0);
  return s;
}

GridFile read_grid(const std::string& path) {
  GridFile g;
  RawGridFrame f0;
  const GridSeries s = open_grid_series(path, &f0);
  g.geometry = s.geometry;
  g.kinematic_viscosity = s.kinematic_viscosity;
  g.frames.push_back(std::move(f0));
  for (size_t i = 1; i < s.times.size(); ++i) g.frames.push_back(s.load(i));
  return g;
}

}  // namespace lrigid
