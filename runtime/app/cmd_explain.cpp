// lrigid explain SCENE.json: per body type, the dimensionless numbers that decide which effects
// matter, the effects chosen (by "auto" or by the scene's list), each skipped effect with its
// reason, and the estimated cost per body-step (docs/effects.md).
#include <cstdio>
#include <iostream>
#include <string>

#include "commands.h"
#include "effects/basset.h"
#include "integrate/simulation.h"
#include "integrate/sphere_batch.h"
#include "io/added_mass_cache.h"
#include "io/field_loader.h"
#include "io/scene_json.h"
#include "model/model.h"

namespace lrigid::app {

namespace {

std::string list(EffectSet s) {
  std::string r;
  for (const std::string& n : effect_names(s)) r += (r.empty() ? "" : ", ") + n;
  return r.empty() ? "(none)" : r;
}

void explain(const std::string& path) {
  const Scene scene = read_scene(path);
  FluidField field = load_field(scene);
  const FlowScales flow = flow_scales(scene, field);
  const Model model = compile_model(scene, std::move(field), cached_added_mass);
  const double nu = scene.kinematic_viscosity;
  std::printf("scene: %s\n", path.c_str());
  std::printf("fluid: rho_f = %g kg/m^3, nu = %g m^2/s, gravity = %g m/s^2\n",
              scene.fluid_density, nu, scene.gravity.norm());
  std::printf("flow (%s): |U| = %.3g m/s, k = %.3g m^2/s^2, eps = %.3g m^2/s^3",
              flow.source.c_str(), flow.U, flow.k, flow.eps);
  if (flow.k > 0 && flow.eps > 0)
    std::printf(", k/eps = %.3g s, tau_eta = sqrt(nu/eps) = %.3g s", flow.k / flow.eps,
                std::sqrt(nu / flow.eps));
  std::printf("\n");
  if (scene.mean_flow_scale != 1 || scene.turbulence_scale != 1)
    std::printf("art: mean_flow_scale = %g, turbulence_scale = %g (included above)\n",
                scene.mean_flow_scale, scene.turbulence_scale);
  std::printf("integrator: %s, dt = %g s; effects: %s\n", integrator_name(scene.integrator),
              scene.dt, scene.effects_auto ? "auto" : "listed by the scene");
  double total_ns = 0;
  for (size_t ti = 0; ti < model.types.size(); ++ti) {
    const BodyType& t = model.types[ti];
    const BodySpec& spec = scene.bodies[t.spec];
    const EffectAnalysis a = analyze_effects(scene, t, flow, spec);
    std::printf("\nbody type %zu \"%s\" (%s, %zu bodies): mass %.3g kg, volume %.3g m^3, "
                "density %.4g kg/m^3\n",
                ti, t.name.c_str(), shape_type_name(t.shape.type), t.count, t.mass, t.volume,
                t.density);
    std::printf("  rho_f/rho_b = %.3g   aspect ratio (min/max semi-axis) = %.3g   flat: %s\n",
                a.density_ratio, a.aspect_ratio,
                t.flat ? ("yes, normal = body axis " + std::to_string(t.normal_axis)).c_str()
                       : "no");
    std::printf("  size d = %.3g m   settling speed = %.3g m/s   relative speed = %.3g m/s   "
                "Re = %.3g\n",
                a.size, a.terminal_speed, a.speed, a.reynolds);
    std::printf("  tau_p = %.3g s   St(k/eps) = %.3g   St(Kolmogorov) = %.3g   spin ratio = %.3g\n",
                a.tau_p, a.stokes_k_eps, a.stokes_kolmogorov, a.spin_ratio);
    std::printf("  %-11s %-10s %s\n", "effect", "size", "auto");
    for (const auto& [e, size] : a.size_rel) {
      std::string status = "keep";
      for (const auto& [se, why] : a.skipped)
        if (se == e) status = "skip: " + why;
      const char* name = "?";
      for (const auto& info : all_effects())
        if (info.effect == e) name = info.name;
      std::printf("  %-11s %-10.3g %s\n", name, size, status.c_str());
    }
    std::printf("  auto chooses: %s\n", list(a.chosen).c_str());
    if (!scene.effects_auto) std::printf("  the scene lists: %s\n", list(t.effects).c_str());
    std::string why;
    const StepKind kind = step_kind(model, t, &why);
    const bool sphere = kind == StepKind::SphereBlock, rigid = kind == StepKind::RigidBlock;
    const double ns = sphere || rigid
                          ? estimated_batched_cost_ns(t.effects, model.precision, rigid)
                          : estimated_cost_ns(t.effects, scene.integrator, !scene.uniform_field,
                                              t.M_isotropic);
    total_ns += ns * double(t.count);
    std::printf("  simulated: %s\n", list(t.effects).c_str());
    if (sphere || rigid)
      std::printf("  step: batched (%s), %d bodies per block, %s loops, %s (docs/batched-step.md)\n",
                  sphere ? "spheres" : "plates and ellipsoids", kBatch, sphere_batch_isa(),
                  model.precision == Precision::Float ? "float" : "double");
    else
      std::printf("  step: scalar (not batched: %s)\n", why.c_str());
    std::printf("  estimated cost: %.0f ns per body-step\n", ns);
  }
  const double steps = std::round(scene.duration / scene.dt);
  std::printf("\nestimated total: %.3g body-steps, %.3g s on one core\n",
              steps * double(model.body_count), total_ns * steps * 1e-9);
}

}  // namespace

void add_explain_command(CLI::App& app) {
  auto scene = std::make_shared<std::string>();
  auto* cmd = app.add_subcommand(
      "explain", "Per body type: the dimensionless numbers, the effects chosen and skipped (with "
                 "the reason) and the estimated cost per body-step (docs/effects.md)");
  cmd->add_option("scene", *scene, "Scene file (JSON, schema v1)")->required();
  cmd->callback([scene] { explain(*scene); });
}

}  // namespace lrigid::app
