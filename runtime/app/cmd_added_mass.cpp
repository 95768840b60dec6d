// lrigid added-mass: volume, mass properties per unit density and the fluid Kirchhoff tensor
// of one body shape, the one a run takes for a body type of that shape (type_added_mass,
// compile/compile_model.h): a flat body whose surfaces are planes its planform's, any other body
// its own. BEM results come from / go to the disk cache.
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "body/added_mass.h"
#include "body/bem.h"
#include "body/mass_properties.h"
#include "commands.h"
#include "compile/compile_model.h"
#include "io/added_mass_cache.h"
#include "io/mesh_io.h"
#include "util/error.h"

namespace lrigid::app {

namespace {

struct Options {
  double sphere = 0;
  std::vector<double> ellipsoid, box;
  std::string mesh;
  double fluid_density = 1000.0;
  int panels = 0;
  bool json = false;
};

Shape make_shape(const Options& o, CLI::App* cmd) {
  int given = 0;
  for (const char* name : {"--sphere", "--ellipsoid", "--box", "--mesh"})
    given += cmd->count(name) > 0 ? 1 : 0;
  if (given != 1)
    throw Error(ExitCode::Usage,
                "added-mass: give exactly one of --sphere R, --ellipsoid A B C, --box LX LY LZ, "
                "--mesh FILE");
  // a length out of range: the shape's message, with the flag that gave it
  const auto flag = [](const char* name, auto make) {
    try {
      return make();
    } catch (const Error& e) {
      throw Error(e.code(), std::string("added-mass: ") + name + ": " + e.what());
    }
  };
  if (cmd->count("--sphere")) return flag("--sphere", [&] { return Shape::sphere(o.sphere); });
  if (cmd->count("--ellipsoid"))
    return flag("--ellipsoid", [&] {
      return Shape::ellipsoid(o.ellipsoid[0], o.ellipsoid[1], o.ellipsoid[2]);
    });
  if (cmd->count("--box"))
    return flag("--box", [&] { return Shape::box(o.box[0], o.box[1], o.box[2]); });
  auto mesh = std::make_shared<const TriangleMesh>(read_mesh(o.mesh));
  return Shape::from_mesh(mesh, o.mesh);
}

nlohmann::json to_json(const Eigen::MatrixXd& m) {
  nlohmann::json a = nlohmann::json::array();
  for (int r = 0; r < m.rows(); ++r) {
    nlohmann::json row = nlohmann::json::array();
    for (int c = 0; c < m.cols(); ++c) row.push_back(m(r, c));
    a.push_back(row);
  }
  return a;
}

const char* const kAxis[3] = {"x", "y", "z"};

nlohmann::json vec_json(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

void print_json(const Shape& s, const MassProperties& mp, const TypeAddedMass& t, double rho) {
  const AddedMass& am = t.added_mass;
  nlohmann::json j;
  j["shape"] = {{"type", shape_type_name(s.type)},
                {"half_extents", {s.half_extents.x(), s.half_extents.y(), s.half_extents.z()}}};
  if (s.type == ShapeType::Mesh) {
    j["shape"]["source"] = s.source;
    j["shape"]["vertices"] = s.mesh->vertices.size();
    j["shape"]["faces"] = s.mesh->faces.size();
  }
  j["fluid_density"] = rho;
  j["volume"] = mp.volume;
  j["centroid"] = {mp.centroid.x(), mp.centroid.y(), mp.centroid.z()};
  j["inertia_per_unit_density"] = to_json(mp.inertia);
  j["added_mass"] = to_json(am.tensor);
  j["method"] = am.method;
  j["panels"] = am.panels;
  j["flat"] = t.flat;
  j["added_mass_of"] = t.from_planform ? "planform" : "shape";
  if (t.flat) {
    const Planform& p = t.planform;
    j["planform"] = {{"normal_axis", kAxis[t.normal_axis]},
                     {"area", p.area},
                     {"half_sides", {p.h1, p.h2}},
                     {"e1", vec_json(p.e1)},
                     {"e2", vec_json(p.e2)},
                     {"angle", p.angle},
                     {"rectangularity", p.rectangularity},
                     {"rectangle_weight", p.w},
                     {"rectangle_half_sides", {p.c1, p.c2}},
                     {"ellipse_semi_axes", {p.a1, p.a2}}};
  }
  std::cout << j.dump(2) << "\n";
}

void print_report(const Shape& s, const MassProperties& mp, const TypeAddedMass& t, double rho) {
  const AddedMass& am = t.added_mass;
  std::ostringstream o;
  o << std::setprecision(6);
  o << "shape: " << shape_type_name(s.type);
  if (s.type == ShapeType::Mesh)
    o << " " << s.source << " (" << s.mesh->vertices.size() << " vertices, " << s.mesh->faces.size()
      << " faces)";
  o << ", half extents " << s.half_extents.transpose() << " m\n";
  o << "volume: " << mp.volume << " m^3\n";
  o << "centroid (centre of buoyancy): " << mp.centroid.transpose() << " m\n";
  o << "inertia about the centroid per unit density [m^5]:\n" << mp.inertia << "\n";
  o << "fluid density: " << rho << " kg/m^3\n";
  if (t.flat) {
    const Planform& p = t.planform;
    const int na = t.normal_axis;
    o << "flat, normal along " << kAxis[na] << "; planform: area " << p.area
      << " m^2, tightest rectangle " << 2 * p.h1 << " x " << 2 * p.h2 << " m, its sides turned by "
      << p.angle * 180.0 / M_PI << " deg about " << kAxis[na] << " from the "
      << kAxis[(na + 1) % 3] << " and " << kAxis[(na + 2) % 3]
      << " axes; rectangularity R = " << p.rectangularity << ", rectangle weight w = " << p.w
      << "\n";
  }
  if (t.from_planform)
    o << "added mass (Kirchhoff tensor, fluid part) of the planform, as a run takes it for this "
         "flat body: w x the rectangle's (a box) + (1 - w) x the ellipse's (an ellipsoid), by ";
  else if (t.flat)
    o << "added mass (Kirchhoff tensor, fluid part) of the shape itself (flat but not planar: its "
         "own surface), by ";
  else
    o << "added mass (Kirchhoff tensor, fluid part) by ";
  o << am.method;
  if (am.panels > 0) o << " with " << am.panels << " panels";
  o << ", about the centroid, order (vx vy vz wx wy wz),\nunits kg | kg m | kg m^2:\n";
  Eigen::IOFormat fmt(6, 0, "  ", "\n", "  ", "");
  o << am.tensor.format(fmt) << "\n";
  if (rho > 0) {
    o << "translational coefficients K_ii / (rho V): "
      << (am.tensor.diagonal().head<3>() / (rho * mp.volume)).transpose() << "\n";
  }
  std::cout << o.str();
}

}  // namespace

void add_added_mass_command(CLI::App& app) {
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand(
      "added-mass",
      "Mass properties and fluid Kirchhoff (added-mass) tensor of a body shape (SI units)");
  cmd->add_option("--sphere", opt->sphere, "sphere of radius R [m]");
  cmd->add_option("--ellipsoid", opt->ellipsoid, "ellipsoid with semi-axes A B C [m]")->expected(3);
  cmd->add_option("--box", opt->box, "box with edge lengths LX LY LZ [m]")->expected(3);
  cmd->add_option("--mesh", opt->mesh, "closed triangle mesh (.obj or .stl; coordinates in m)");
  cmd->add_option("--fluid-density", opt->fluid_density, "fluid density RHO [kg/m^3]")
      ->capture_default_str();
  cmd->add_option("--panels", opt->panels,
                  "boundary element panels for boxes and meshes, about this many (0 = aim at " +
                      std::to_string(kDefaultPanels) +
                      "): a box is tessellated to the nearest count its construction allows "
                      "(a cube 1536, a thin plate 1792); a mesh's triangles are split in 4 "
                      "until nearest the aim, never coarsened (12 triangles give 768, 16 give "
                      "1024); the count used is printed")
      ->capture_default_str();
  cmd->add_flag("--json", opt->json, "print JSON (keys volume, added_mass, method, panels, ...)");
  cmd->callback([opt, cmd] {
    // the flags' ranges before any shape is read or built
    if (!(opt->fluid_density >= 0 && opt->fluid_density <= 1e6))
      throw Error(ExitCode::Usage, "added-mass: --fluid-density must be in [0, 1e6] kg/m^3, got " +
                                       std::to_string(opt->fluid_density));
    if (opt->panels < 0 || opt->panels > kMaxBemPanels)
      throw Error(ExitCode::Usage, "added-mass: --panels must be in [0, " +
                                       std::to_string(kMaxBemPanels) + "] (0 = default), got " +
                                       std::to_string(opt->panels));
    const Shape shape = make_shape(*opt, cmd);
    const MassProperties mp = mass_properties(shape);
    TypeAddedMass t;
    try {
      t = type_added_mass(shape, opt->fluid_density, opt->panels, cached_added_mass);
    } catch (const Error& e) {
      // the boundary elements fail only on a surface they cannot solve: the mesh's fault
      if (e.code() != ExitCode::Runtime || shape.type != ShapeType::Mesh) throw;
      throw Error(ExitCode::BadInput, shape.source + ": " + e.what());
    }
    if (opt->json)
      print_json(shape, mp, t, opt->fluid_density);
    else
      print_report(shape, mp, t, opt->fluid_density);
  });
}

}  // namespace lrigid::app
