// foam2grid: resamples the fields of an OpenFOAM case onto a regular grid (.vti, or a .pvd
// series), with OpenFOAM's own cellPoint interpolation. See docs/converter.md and
// docs/grid-format.md.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "error.h"
#include "foam_case.h"
#include "grid_io.h"
#include "interpolate.h"
#include "io/progress.h"
#include "wall_distance.h"
#include "util/cli_suggest.h"

#ifndef FOAM2GRID_VERSION
#define FOAM2GRID_VERSION "unknown"
#endif

namespace fs = std::filesystem;
using namespace foam2grid;

namespace {

struct Options {
  std::string case_dir;
  std::string output;
  double spacing = 0;
  bool spacing_given = false;
  std::vector<long> resolution;
  std::vector<double> bounds;
  std::string time = "latest";
  std::string fields = "U,k,epsilon,nut";
  std::string interpolation = "cellPoint";
  std::string source = "auto";
  std::string info;
  bool quiet = false;
};

class Clock {
 public:
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
  }

 private:
  std::chrono::steady_clock::time_point t0_ = std::chrono::steady_clock::now();
};

std::string fmt(double v) {
  std::ostringstream s;
  s << std::setprecision(6) << v;
  return s.str();
}

std::string human_bytes(double b) {
  const char* units[] = {"B", "KB", "MB", "GB", "TB", "PB"};
  int u = 0;
  while (b >= 1024 && u < 5) {
    b /= 1024;
    ++u;
  }
  std::ostringstream s;
  s << std::setprecision(3) << b << " " << units[u];
  return s.str();
}

// MemAvailable from /proc/meminfo, bytes (0 if unknown)
double available_memory() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kb;
  std::string unit;
  while (in >> key >> kb) {
    std::getline(in, unit);
    if (key == "MemAvailable:") return kb * 1024.0;
  }
  return 0;
}

std::vector<FieldSpec> parse_fields(const std::string& list) {
  std::vector<FieldSpec> specs;
  std::stringstream ss(list);
  std::string name;
  int offset = 0;
  while (std::getline(ss, name, ',')) {
    if (name.empty()) fail_usage("--fields '" + list + "': empty field name");
    for (const FieldSpec& s : specs) {
      if (s.name == name) fail_usage("--fields '" + list + "': '" + name + "' given twice");
    }
    if (name == "valid" || name == "wall_distance")
      fail_usage("--fields: '" + name + "' is always written, do not request it");
    FieldSpec s;
    s.name = name;
    s.ncomp = name == "U" ? 3 : 1;
    s.offset = offset;
    offset += s.ncomp;
    specs.push_back(s);
  }
  if (specs.empty()) fail_usage("--fields '" + list + "': no field named");
  return specs;
}

// indices of the times to convert
std::vector<std::size_t> select_times(const FoamCase& fc, const std::string& spec) {
  const std::size_t n = fc.time_names.size();
  // written times: the initial 0 only counts when nothing else was written (as ParaView)
  std::vector<std::size_t> written;
  for (std::size_t i = 0; i < n; ++i) {
    if (fc.time_values[i] != 0.0 || n == 1) written.push_back(i);
  }
  if (spec == "latest") return {written.back()};
  if (spec == "all") return written;
  char* end = nullptr;
  const double t = std::strtod(spec.c_str(), &end);
  if (end == spec.c_str() || *end != '\0' || !std::isfinite(t)) {
    fail_usage("--time '" + spec + "': expected latest, all or a time in s");
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (std::fabs(fc.time_values[i] - t) <= 1e-9 * std::max(1.0, std::fabs(t))) return {i};
  }
  std::string avail;
  for (const std::string& s : fc.time_names) avail += " " + s;
  fail_input("--time " + spec + ": time not written in " + fc.part_dirs[0] + " (written:" + avail +
             ")");
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

GridSpec make_grid(const Options& opt, const std::array<double, 6>& mb, double default_spacing) {
  std::array<double, 6> b = mb;
  if (!opt.bounds.empty()) {
    b = {opt.bounds[0], opt.bounds[1], opt.bounds[2], opt.bounds[3], opt.bounds[4], opt.bounds[5]};
    const char* axis = "xyz";
    const double extent = std::max({mb[1] - mb[0], mb[3] - mb[2], mb[5] - mb[4]});
    const double tol = 1e-9 * extent;
    for (int k = 0; k < 3; ++k) {
      if (!(b[2 * k] < b[2 * k + 1])) {
        fail_usage("--bounds: " + std::string(1, axis[k]) + "min = " + fmt(b[2 * k]) +
                   " must be below " + std::string(1, axis[k]) + "max = " + fmt(b[2 * k + 1]));
      }
      if (b[2 * k] < mb[2 * k] - tol || b[2 * k + 1] > mb[2 * k + 1] + tol) {
        fail_input("--bounds: " + std::string(1, axis[k]) + " range [" + fmt(b[2 * k]) + ", " +
                   fmt(b[2 * k + 1]) + "] m lies outside the mesh, which spans [" + fmt(mb[2 * k]) +
                   ", " + fmt(mb[2 * k + 1]) + "] m");
      }
    }
  }
  GridSpec g;
  for (int k = 0; k < 3; ++k) {
    const double len = b[2 * k + 1] - b[2 * k];
    g.origin[k] = b[2 * k];
    if (opt.resolution.empty()) {
      // cubic spacing; the upper bound is rounded inward to a whole number of steps
      const double h = opt.spacing > 0 ? opt.spacing : default_spacing;
      const double n = std::floor(len / h + 1e-9) + 1;
      if (n > 1e9) {
        throw Error(Exit::kTooLarge, "--spacing " + fmt(opt.spacing) + " m gives " + fmt(n) +
                                         " points along one axis: far too many");
      }
      g.dims[k] = static_cast<long>(n);
      g.spacing[k] = h;
    } else {
      g.dims[k] = opt.resolution[static_cast<std::size_t>(k)];
      g.spacing[k] = len > 0 ? len / static_cast<double>(g.dims[k] - 1) : 1.0;
    }
  }
  return g;
}

int run(const Options& opt) {
  Clock clock;
  // the runtime's progress display: a bar on a terminal, a line per 10 % otherwise
  using lrigid::Progress;
  Progress progress("foam2grid", opt.quiet ? Progress::Mode::Quiet : Progress::Mode::Auto);
  auto log = [&](const std::string& msg) {
    // wall time and process CPU time (all threads) since the start
    std::ostringstream line;
    line << "foam2grid [" << std::fixed << std::setprecision(2) << clock.seconds() << " s, cpu "
         << static_cast<double>(std::clock()) / CLOCKS_PER_SEC << " s] " << msg;
    progress.message(line.str());
  };
  // flags first: nothing is read before they are known to be sane
  if (opt.spacing_given && !(opt.spacing > 0)) {
    fail_usage("--spacing " + fmt(opt.spacing) + ": must be a positive length in m");
  }
  if (!std::isfinite(opt.spacing)) fail_usage("--spacing: must be a finite length in m");
  if (opt.spacing > 0 && !opt.resolution.empty()) {
    fail_usage("give only one of --spacing H (m) and --resolution NX NY NZ");
  }
  for (long n : opt.resolution) {
    if (n < 2)
      fail_usage("--resolution: " + std::to_string(n) + " points: need at least 2 per axis");
  }
  for (double v : opt.bounds) {
    if (!std::isfinite(v)) fail_usage("--bounds: values must be finite numbers (m)");
  }
  const std::vector<FieldSpec> specs = parse_fields(opt.fields);
  Scheme scheme = Scheme::kCellPoint;
  if (opt.interpolation == "cell") {
    scheme = Scheme::kCell;
  } else if (opt.interpolation != "cellPoint") {
    fail_usage("--interpolation '" + opt.interpolation + "': expected cellPoint or cell");
  }
  CaseSource source = CaseSource::kAuto;
  if (opt.source == "reconstructed") {
    source = CaseSource::kReconstructed;
  } else if (opt.source == "decomposed") {
    source = CaseSource::kDecomposed;
  } else if (opt.source != "auto") {
    fail_usage("--source '" + opt.source + "': expected auto, reconstructed or decomposed");
  }
  const bool series = opt.time == "all";
  if (series && !ends_with(opt.output, ".pvd")) {
    fail_usage("-o " + opt.output + ": with --time all the output is a .pvd collection");
  }
  if (!series && !ends_with(opt.output, ".vti")) {
    fail_usage("-o " + opt.output + ": the output must be a .vti file (or .pvd with --time all)");
  }
  {
    const fs::path parent = fs::absolute(opt.output).parent_path();
    std::error_code ec;
    if (!fs::is_directory(parent, ec)) {
      throw Error(Exit::kOutput,
                  "-o " + opt.output + ": directory " + parent.string() + " does not exist");
    }
    if (access(parent.c_str(), W_OK) != 0) {
      throw Error(Exit::kOutput,
                  "-o " + opt.output + ": directory " + parent.string() + " is not writable");
    }
  }

  // case, times, viscosity
  const FoamCase fc = open_case(opt.case_dir, source);
  const std::vector<std::size_t> times = select_times(fc, opt.time);
  const double nu = read_viscosity(fc.dir);
  log("case " + fc.dir +
      (fc.decomposed ? " (decomposed, " + std::to_string(fc.part_dirs.size()) + " processors)"
                     : "") +
      ", " + std::to_string(times.size()) + " time(s), nu = " + fmt(nu) + " m^2/s");

  // points, bounds, grid, memory
  std::vector<MeshPart> parts;
  read_points(fc, &parts);
  const std::array<double, 6> mb = mesh_bounds(parts);
  // default spacing: (bounding-box volume / number of mesh points)^(1/3), about the mean cell
  // size of a hexahedral mesh
  double mesh_points = 0;
  for (const MeshPart& m : parts) mesh_points += static_cast<double>(m.n_points());
  const double box_volume =
      std::max(mb[1] - mb[0], 0.0) * std::max(mb[3] - mb[2], 0.0) * std::max(mb[5] - mb[4], 0.0);
  const double default_spacing = std::cbrt(box_volume / std::max(mesh_points, 1.0));
  if (!(default_spacing > 0) && opt.spacing <= 0 && opt.resolution.empty()) {
    fail_input("the mesh of '" + fc.dir + "' is flat or empty: give --spacing or --resolution");
  }
  const GridSpec grid = make_grid(opt, mb, default_spacing);
  {
    double per_point = 10;  // valid + claim flag, wall distance (unsigned and signed)
    for (const FieldSpec& s : specs) per_point += 4.0 * s.ncomp;
    const double npts = static_cast<double>(grid.dims[0]) * static_cast<double>(grid.dims[1]) *
                        static_cast<double>(grid.dims[2]);
    const double need = npts * per_point + mesh_points * 600.0;
    const double avail = available_memory();
    std::ostringstream dims;
    dims << grid.dims[0] << " x " << grid.dims[1] << " x " << grid.dims[2];
    if (npts > 2147483647.0 || (avail > 0 && need > 0.9 * avail)) {
      throw Error(Exit::kTooLarge,
                  "grid " + dims.str() + " = " + fmt(npts) + " points (" + opt.fields +
                      ", valid) would need about " + human_bytes(need) + " of memory" +
                      (avail > 0 ? "; " + human_bytes(avail) + " is available" : "") +
                      (npts > 2147483647.0 ? "; at most 2^31 - 1 points are supported" : "") +
                      ": use a coarser --spacing/--resolution or smaller --bounds");
    }
    log("grid " + dims.str() + " points, spacing " + fmt(grid.spacing[0]) + " " +
        fmt(grid.spacing[1]) + " " + fmt(grid.spacing[2]) + " m, about " + human_bytes(need));
  }

  read_topology(fc, &parts);
  Label ncells = 0;
  for (const MeshPart& m : parts) ncells += m.n_cells;
  log("mesh: " + std::to_string(ncells) + " cells, " + std::to_string(count_global_points(parts)) +
      " points");

  // the distance to the walls: the mesh does not move, so once for every time (signed below
  // with each time's valid mask)
  std::size_t wall_faces = 0;
  const std::vector<float> wall_d = unsigned_wall_distance(parts, grid, &wall_faces);
  log(wall_faces == 0 ? std::string("no wall patch: wall_distance not written")
                      : "wall distance: " + std::to_string(wall_faces) + " wall faces");

  // output locations
  const fs::path out_path = fs::absolute(opt.output);
  const std::string stem = out_path.stem().string();
  const fs::path series_dir = out_path.parent_path() / (stem + "_vti");
  const fs::path series_tmp =
      out_path.parent_path() / ("." + stem + "_vti.tmp" + std::to_string(getpid()));
  if (series) {
    std::error_code ec;
    fs::remove_all(series_tmp, ec);
    if (!fs::create_directory(series_tmp, ec)) {
      throw Error(Exit::kOutput, "-o " + opt.output + ": cannot create " + series_tmp.string());
    }
  }
  std::vector<double> pvd_times;
  std::vector<std::string> pvd_files;
  try {
    for (std::size_t n = 0; n < times.size(); ++n) {
      const std::size_t ti = times[n];
      const std::string& tname = fc.time_names[ti];
      // progress over all times: time n of N, then the fraction of its cells resampled
      const std::string which = "time " + std::to_string(n + 1) + "/" +
                                std::to_string(times.size()) + " (" + tname + " s)";
      const double per_time = 1.0 / static_cast<double>(times.size());
      progress.update(static_cast<double>(n) * per_time, which + ": reading fields");
      std::vector<PartFields> fields(parts.size());
      for (std::size_t p = 0; p < parts.size(); ++p) {
        read_fields(parts[p], tname, specs, &fields[p]);
      }
      log("time " + tname + ": fields read");
      progress.update(static_cast<double>(n) * per_time, which + ": point values");
      std::vector<double> pv;
      if (scheme == Scheme::kCellPoint) pv = point_values(parts, fields, specs);
      GridFields data;
      const std::string of_points = " of " + std::to_string(grid.n_points()) + " points resampled";
      resample(parts, fields, pv, specs, grid, scheme, &data, [&](double f, std::size_t points) {
        progress.update((static_cast<double>(n) + f) * per_time,
                        which + ": " + std::to_string(points) + of_points);
      });
      data.wall_distance = signed_wall_distance(wall_d, data.valid);
      std::size_t nvalid = 0;
      for (std::uint8_t v : data.valid) nvalid += v;
      log("time " + tname + ": resampled, " + std::to_string(nvalid) + " of " +
          std::to_string(grid.n_points()) + " points in the fluid");
      if (nvalid == 0) {
        fail_input("no grid point lies inside the mesh cells (check --bounds and the spacing)");
      }
      GridMeta meta;
      meta.kinematic_viscosity = nu;
      meta.case_name = fc.name;
      meta.time = fc.time_values[ti];
      meta.converter_version = FOAM2GRID_VERSION;
      if (series) {
        const std::string file = stem + "_" + tname + ".vti";
        write_vti((series_tmp / file).string(), grid, specs, &data, meta);
        pvd_times.push_back(fc.time_values[ti]);
        pvd_files.push_back(stem + "_vti/" + file);
      } else {
        write_vti(out_path.string(), grid, specs, &data, meta);
      }
      log("time " + tname + ": written");
    }
    if (series) {
      // replace an older series directory, then write the collection
      std::error_code ec;
      const fs::path old =
          out_path.parent_path() / ("." + stem + "_vti.old" + std::to_string(getpid()));
      if (fs::exists(series_dir, ec)) fs::rename(series_dir, old, ec);
      if (ec) throw Error(Exit::kOutput, "cannot move the old " + series_dir.string() + " aside");
      fs::rename(series_tmp, series_dir, ec);
      if (ec)
        throw Error(Exit::kOutput, "cannot rename " + series_tmp.string() + ": " + ec.message());
      fs::remove_all(old, ec);
      write_pvd(out_path.string(), pvd_times, pvd_files);
    }
  } catch (...) {
    if (series) {
      std::error_code ec;
      fs::remove_all(series_tmp, ec);
    }
    throw;
  }
  progress.finish();
  log("done: " + out_path.string());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  CLI::App app{
      "foam2grid " FOAM2GRID_VERSION
      ": resample the fields of an OpenFOAM case (U, k, epsilon, nut)\n"
      "onto a regular grid, a VTK ImageData file (.vti) or a .pvd series of them, with OpenFOAM's\n"
      "cellPoint interpolation. All values in SI units (m, s, m/s, m^2/s^2, m^2/s^3, m^2/s).\n"
      "Exit codes: 0 ok, 2 usage, 3 bad input, 4 output cannot be written, 5 grid too large.",
      "foam2grid"};
  app.add_option("case", opt.case_dir, "OpenFOAM case directory (serial or decomposed)");
  app.add_option("-o,--output", opt.output,
                 "output file: OUT.vti, or OUT.pvd with --time all (the .vti files then go to "
                 "OUT_vti/ beside it)");
  CLI::Option* spacing = app.add_option(
      "--spacing", opt.spacing,
      "grid spacing H in m, the same along x, y and z; the number of points per axis "
      "is floor(L/H)+1, so the upper bounds are rounded inward (default: "
      "(bounding-box volume / mesh points)^(1/3), about the mean cell size)");
  app.add_option("--resolution", opt.resolution,
                 "grid points NX NY NZ along x, y, z (each >= 2); spacing = extent/(N-1)")
      ->expected(3);
  app.add_option("--bounds", opt.bounds,
                 "grid box XMIN XMAX YMIN YMAX ZMIN ZMAX in m (default: the mesh bounding box); "
                 "must lie inside the mesh bounding box")
      ->expected(6);
  app.add_option("--time", opt.time,
                 "latest (default), all (every written time but 0; needs a .pvd output), or a "
                 "written time in s")
      ->capture_default_str();
  app.add_option("--fields", opt.fields,
                 "comma-separated fields: U (m/s), k (m^2/s^2), epsilon (m^2/s^3), nut (m^2/s); "
                 "'valid' and 'wall_distance' (m, signed distance to the nearest wall patch face) "
                 "are always written")
      ->capture_default_str();
  app.add_option("--interpolation", opt.interpolation,
                 "cellPoint (OpenFOAM's cellPoint: linear over each cell's tetrahedra, from cell "
                 "and point values) or cell (the value of the cell holding the point)")
      ->capture_default_str();
  app.add_option("--source", opt.source,
                 "auto, reconstructed (case/constant, case/<time>) or decomposed "
                 "(processor*/ without reconstructPar); auto takes the processors when they hold "
                 "later times")
      ->capture_default_str();
  app.add_option("--info", opt.info,
                 "summarize a grid file FILE.vti or FILE.pvd (dimensions, spacing, bounds, "
                 "per-field min/max/mean, invalid fraction, times) and exit");
  app.add_flag("-q,--quiet", opt.quiet, "no progress messages on stderr");
  app.set_version_flag("--version", FOAM2GRID_VERSION);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    if (dynamic_cast<const CLI::ExtrasError*>(&e)) {
      std::istringstream hints(lrigid::unknown_flag_hints(app, app.remaining(true)));
      for (std::string line; std::getline(hints, line);) std::cerr << "foam2grid: " << line << "\n";
    }
    return rc == 0 ? 0 : static_cast<int>(Exit::kUsage);
  }
  opt.spacing_given = spacing->count() > 0;
  try {
    if (!opt.info.empty()) {
      if (!opt.case_dir.empty() || !opt.output.empty()) {
        fail_usage("--info takes only the grid file; no case or -o");
      }
      print_info(opt.info, std::cout);
      return 0;
    }
    if (opt.case_dir.empty()) fail_usage("no case directory given (see --help)");
    if (opt.output.empty()) fail_usage("no output given: -o OUT.vti (see --help)");
    return run(opt);
  } catch (const Error& e) {
    std::cerr << "foam2grid: error: " << e.what() << std::endl;
    return static_cast<int>(e.code());
  } catch (const std::bad_alloc&) {
    std::cerr << "foam2grid: error: out of memory" << std::endl;
    return static_cast<int>(Exit::kTooLarge);
  } catch (const std::exception& e) {
    std::cerr << "foam2grid: error: " << e.what() << std::endl;
    return 1;
  }
}
