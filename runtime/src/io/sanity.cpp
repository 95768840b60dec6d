#include "io/sanity.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "model/release.h"
#include "util/error.h"

namespace lrigid {

namespace {

// thresholds (docs/scene-format.md, "Sanity warnings")
constexpr double kMaxSizeOfGrid = 0.1;     // a body wider than 10 % of the grid's smallest extent
constexpr double kMaxSizeUniform = 5.0;    // m: without a grid, a body wider than this
constexpr double kMaxMass = 100.0;         // kg per body
constexpr double kMaxDensity = 25000.0;    // kg/m^3: osmium, the densest element, is 22 590
constexpr double kMinDensity = 0.05;       // kg/m^3: aerogels are about 1
// docs/stability.md section 2: the explicit schemes' measured limits, rate x dt_max, and the
// largest step at which the splitting scheme was measured stable (100 / rate)
constexpr double kEulerLimit = 2.0, kRk4Limit = 2.78, kSplittingMeasured = 100.0;

std::string fmt(const char* f, double a) {
  char b[64];
  std::snprintf(b, sizeof b, f, a);
  return b;
}
std::string g3(double a) { return fmt("%.3g", a); }
std::string vec(const Vec3& v) { return "[" + g3(v.x()) + ", " + g3(v.y()) + ", " + g3(v.z()) + "]"; }
std::string box(const Vec3& lo, const Vec3& hi) { return "[" + vec(lo) + ", " + vec(hi) + "]"; }

// fraction of the box [lo, hi] inside [glo, ghi] (by volume; a flat box by its area or length)
double inside_fraction(const Vec3& lo, const Vec3& hi, const Vec3& glo, const Vec3& ghi) {
  double f = 1;
  for (int a = 0; a < 3; ++a) {
    const double w = hi[a] - lo[a];
    const double in = std::min(hi[a], ghi[a]) - std::max(lo[a], glo[a]);
    if (w <= 0) f *= (lo[a] >= glo[a] && lo[a] <= ghi[a]) ? 1 : 0;
    else f *= std::clamp(in / w, 0.0, 1.0);
  }
  return f;
}

const char* axis_name(int a) { return a == 0 ? "x" : a == 1 ? "y" : "z"; }

}  // namespace

std::vector<SanityFinding> check_scene(const Scene& scene, const Model& model) {
  std::vector<SanityFinding> out;
  auto add = [&](const char* check, const std::string& key, const std::string& msg,
                 bool error = false) { out.push_back({check, key, msg, error}); };
  const bool grid = !model.field.is_uniform();
  const GridGeometry& g = model.field.geometry();
  const Vec3 glo = g.origin, ghi = grid ? g.upper() : Vec3::Zero();
  const FlowScales flow = flow_scales(scene, model.field);

  if (grid)
    for (int a = 0; a < 3; ++a)
      if (g.n[a] < 4)
        add("grid_coarse", "fluid.field",
            "the grid has " + std::to_string(g.n[a]) + " points along " + axis_name(a) +
                " (spacing " + g3(g.spacing[a]) +
                " m): the flow between them is a straight interpolation, too coarse to move "
                "bodies by anything but a uniform drift; check the grid's resolution "
                "(foam2grid --spacing, docs/converter.md)");

  std::vector<bool> seen(scene.bodies.size(), false);
  size_t outside_bodies = 0, solid_bodies = 0, all_bodies = 0;
  for (const BodyType& t : model.types) {
    if (t.spec >= scene.bodies.size() || seen[t.spec]) continue;
    seen[t.spec] = true;
    const BodySpec& spec = scene.bodies[t.spec];
    const std::string key = "bodies[" + std::to_string(t.spec) + "]";
    const std::string who = "body type \"" + spec.name + "\"";
    const EffectAnalysis a = analyze_effects(scene, t, flow, spec);
    const double width = 2 * t.shape.half_extents.maxCoeff();  // m

    // size and mass: a unit mistake (centimetres or millimetres written as metres)
    if (grid) {
      int amin = 0;
      for (int k = 1; k < 3; ++k)
        if (ghi[k] - glo[k] < ghi[amin] - glo[amin]) amin = k;
      const double extent = ghi[amin] - glo[amin];
      if (extent > 0 && width > kMaxSizeOfGrid * extent)
        add("body_size", key + ".shape",
            who + " is " + g3(width) + " m wide, " + fmt("%.0f", 100 * width / extent) +
                " % of the grid's extent along " + axis_name(amin) + " (" + g3(extent) +
                " m): sizes are in metres; a size in centimetres written as metres is 100 times "
                "too large (check " + key + ".shape and its mesh's units)");
    } else if (width > kMaxSizeUniform) {
      add("body_size", key + ".shape",
          who + " is " + g3(width) + " m wide: sizes are in metres; a size in centimetres "
                "written as metres is 100 times too large (check " + key + ".shape)");
    }
    if (t.mass > kMaxMass)
      add("body_mass", key + ".density",
          who + " weighs " + g3(t.mass) + " kg per body (" + g3(t.volume) + " m^3 at " +
              g3(t.density) + " kg/m^3): check the units of " + key + ".shape (metres) and " +
              key + ".density (kg/m^3)");
    if (spec.density > kMaxDensity || spec.density < kMinDensity)
      add("density", key + ".density",
          who + " has density " + g3(spec.density) + " kg/m^3, " +
              (spec.density > kMaxDensity ? "denser than any material (osmium: 22 590)"
                                          : "lighter than any solid (aerogels: about 1)") +
              ": densities are in kg/m^3 (water 1000, g/cm^3 x 1000)");

    // where the bodies start
    Vec3 lo = spec.position, hi = spec.position;
    std::string where_key = key + ".position", what = "position " + vec(spec.position);
    if (spec.spawn_in_box) {
      lo = spec.box_lo, hi = spec.box_hi;
      where_key = key + ".spawn_box";
      what = "spawn_box " + box(lo, hi);
    } else if (spec.spawn_on_solids) {
      // the sites' fluid points lie in the grid and the box (compile_model refuses none)
      lo = spec.spawn_surface_box ? Vec3(spec.box_lo.cwiseMax(glo)) : glo;
      hi = spec.spawn_surface_box ? Vec3(spec.box_hi.cwiseMin(ghi)) : ghi;
      where_key = key + ".spawn";
      what = "spawn on the solids' surface in " + box(lo, hi);
    }
    all_bodies += size_t(spec.count);
    if (grid) {
      const double in = inside_fraction(lo, hi, glo, ghi);
      if (in <= 0) {
        outside_bodies += size_t(spec.count);
        add("spawn_outside_grid", where_key,
            what + " lies entirely outside the grid " + box(glo, ghi) + " (fluid.field): its " +
                std::to_string(spec.count) +
                " bodies would stop (\"exited\") at t = 0; positions are in metres in the grid's "
                "frame: check the units and the box against the grid's bounds");
      } else if (in < 0.999) {
        add("spawn_partly_outside_grid", where_key,
            what + ": " + fmt("%.0f", 100 * (1 - in)) + " % of it lies outside the grid " +
                box(glo, ghi) +
                " (fluid.field), and bodies placed there stop (\"exited\") at t = 0; shrink it "
                "to the grid's bounds");
      }
      // inside the grid but where it has no flow (the walls and buildings of the flow's
      // solids): those bodies stop ("exited") at t = 0 as well
      size_t in_solid = 0;
      if (in > 0)
        for (const BodyType& same : model.types) {
          if (same.spec != t.spec) continue;
          for (size_t i = same.first_body; i < same.first_body + same.count; ++i) {
            const Vec3 x = initial_position(model, spec, t.spec, static_cast<uint32_t>(i));
            FluidSample fs;
            if ((x.array() >= glo.array()).all() && (x.array() <= ghi.array()).all() &&
                !model.field.sample(x, 0.0, false, &fs))
              ++in_solid;
          }
        }
      const size_t entry = size_t(spec.count);
      if (in_solid > 0 && in_solid == entry) {
        solid_bodies += in_solid;
        add("spawn_inside_solid", where_key,
            what + " lies inside the flow's solids (fluid.field has no flow there: a building, "
                   "a wall): all its " + std::to_string(entry) +
                " bodies would stop (\"exited\") at t = 0; move it into the fluid");
      } else if (in_solid > 0) {
        solid_bodies += in_solid;
        add("spawn_partly_inside_solid", where_key,
            what + ": " + std::to_string(in_solid) + " of its " + std::to_string(entry) +
                " bodies start inside the flow's solids (fluid.field has no flow there: a "
                "building, a wall) and stop (\"exited\") at t = 0; move the box off them");
      }
      // the whole spawn region within one cell: every body sees the same interpolated flow
      bool within_cell = spec.count > 1;
      for (int k = 0; k < 3 && within_cell; ++k)
        within_cell = hi[k] - lo[k] < g.spacing[k];
      if (within_cell && in > 0)
        add("grid_coarse", where_key,
            what + " fits within one grid cell (spacing " + vec(g.spacing) + " m): its " +
                std::to_string(spec.count) +
                " bodies start in nearly the same flow; use a finer grid (docs/converter.md) or "
                "a larger box");
    }
    if (model.has_ground && hi.z() < model.ground_z)
      add("spawn_below_ground", where_key,
          what + " lies below the ground (ground.z = " + g3(model.ground_z) +
              " m): its bodies land at t = 0; check ground.z and the box's z");

    // bodies released after the run ends never move (model/release.h)
    if (spec.released_over_time()) {
      int late = 0;
      for (int k = 0; k < spec.count; ++k) late += release_time(spec, k) > scene.duration;
      if (late > 0)
        add("release_after_end", key + ".release",
            who + ": " + std::to_string(late) + " of its " + std::to_string(spec.count) +
                " bodies are released after the run ends (duration = " + g3(scene.duration) +
                " s, the last at " + g3(release_time(spec, spec.count - 1)) +
                " s): they never appear; check the release times or the duration");
    }

    // the time step against the scheme's measured limit (docs/stability.md section 2)
    if (a.tau_p > 0 && std::isfinite(a.tau_p)) {
      const double dt = scene.dt;
      // strang takes the same implicit parts as splitting (and an L-stable force step)
      const bool splitting =
          scene.integrator == Integrator::Splitting || scene.integrator == Integrator::Strang;
      const double limit = (scene.integrator == Integrator::Euler ? kEulerLimit
                            : scene.integrator == Integrator::RK4 ? kRk4Limit
                                                                  : kSplittingMeasured) *
                           a.tau_p;
      const std::string name = integrator_name(scene.integrator);
      if (dt > limit)
        add("dt_stability", "integrator.dt",
            "dt = " + g3(dt) + " s is " + g3(dt / limit) + " times " +
                (splitting ? "the largest step the " + name + " scheme was measured stable at"
                           : "the measured stability limit of " + name) +
                " for " + who + " (response time tau_p = " + g3(a.tau_p) + " s: dt <= " +
                g3(limit) + " s, docs/stability.md section 2); " +
                (splitting ? "use a smaller dt"
                           : "use \"scheme\": \"" + std::string(integrator_name(kDefaultIntegrator)) +
                                 "\" or dt <= " + g3(limit) + " s"));
    }
  }
  if (grid && all_bodies > 0 && outside_bodies == all_bodies)
    add("all_outside_grid", "bodies",
        "every body starts outside the grid " + box(glo, ghi) +
            " (fluid.field): the run would end at t = 0 with all of them \"exited\"; positions "
            "and spawn boxes are in metres in the grid's frame",
        true);
  else if (grid && all_bodies > 0 && solid_bodies > 0 && outside_bodies + solid_bodies >= all_bodies)
    add("all_outside_fluid", "bodies",
        "every body starts inside the flow's solids or outside the grid " + box(glo, ghi) +
            " (fluid.field): the run would end at t = 0 with all of them \"exited\"",
        true);
  return out;
}

nlohmann::json findings_json(const std::vector<SanityFinding>& findings) {
  nlohmann::json j = nlohmann::json::array();
  for (const SanityFinding& f : findings)
    j.push_back({{"check", f.check}, {"key", f.key}, {"message", f.message}, {"error", f.error}});
  return j;
}

void report_findings(const std::vector<SanityFinding>& findings, const std::string& scene_file,
                     bool strict, bool quiet) {
  const SanityFinding* thrown = nullptr;
  for (const SanityFinding& f : findings)
    if (f.error || strict) {
      thrown = &f;
      break;
    }
  // the one thrown is printed by whoever catches it
  for (const SanityFinding& f : findings) {
    const bool error = f.error || strict;
    if (&f != thrown && (!quiet || error))
      std::fprintf(stderr, "lrigid: %s: %s\n", error ? "error" : "warning",
                   where(scene_file, f.key, f.message).c_str());
  }
  if (thrown)
    throw Error(ExitCode::BadInput,
                where(scene_file, thrown->key,
                      thrown->message + (thrown->error ? "" : " (a warning: --strict)")));
}

}  // namespace lrigid
