// lrigid explain SCENE.json: per body type, the dimensionless numbers that decide which effects
// matter, the effects chosen (by "auto" or by the scene's list), each skipped effect with its
// reason, and the estimated cost per body-step (docs/effects.md). The data come from
// io/explain.h (also the Python module's lrigid.explain); this file only prints them.
#include <cstdio>
#include <string>

#include "commands.h"
#include "io/explain.h"
#include "io/scene_json.h"

namespace lrigid::app {

namespace {

using nlohmann::json;

std::string list(const json& names) {
  std::string r;
  for (const auto& n : names) r += (r.empty() ? "" : ", ") + n.get<std::string>();
  return r.empty() ? "(none)" : r;
}

double num(const json& j, const char* key) { return j.at(key).get<double>(); }

void print_type(const json& t) {
  std::printf("\nbody type %zu \"%s\" (%s, %zu bodies): mass %.3g kg, volume %.3g m^3, "
              "density %.4g kg/m^3\n",
              t["index"].get<size_t>(), t["name"].get<std::string>().c_str(),
              t["shape"].get<std::string>().c_str(), t["count"].get<size_t>(), num(t, "mass"),
              num(t, "volume"), num(t, "density"));
  std::printf("  In plain words: %s\n", t["plain_words"].get<std::string>().c_str());
  const std::string flat =
      t["flat"].get<bool>() ? "yes, normal = body axis " + std::to_string(t["normal_axis"].get<int>())
                            : "no";
  std::printf("  rho_f/rho_b = %.3g   aspect ratio (min/max semi-axis) = %.3g   flat: %s\n",
              num(t, "density_ratio"), num(t, "aspect_ratio"), flat.c_str());
  std::printf("  size d = %.3g m   settling speed = %.3g m/s   relative speed = %.3g m/s   "
              "Re = %.3g\n",
              num(t, "size"), num(t, "terminal_speed"), num(t, "relative_speed"),
              num(t, "reynolds"));
  std::printf("  tau_p = %.3g s   St(k/eps) = %.3g   St(Kolmogorov) = %.3g   spin ratio = %.3g\n",
              num(t, "tau_p"), num(t, "stokes_k_eps"), num(t, "stokes_kolmogorov"),
              num(t, "spin_ratio"));
  const json& sf = t["start_flow"];
  if (sf.is_object() && sf["in_fluid"].get<size_t>() > 0)
    std::printf("  flow where it starts (%zu of %zu positions in the fluid): |U| = %.3g m/s "
                "(10-90 %%: %.3g-%.3g), k = %.3g m^2/s^2, u' = %.3g m/s\n",
                sf["in_fluid"].get<size_t>(), sf["positions"].get<size_t>(), num(sf, "U_median"),
                num(sf, "U_p10"), num(sf, "U_p90"), num(sf, "k_median"), num(sf, "u_turb_median"));
  else if (sf.is_object())
    std::printf("  flow where it starts: none of its %zu positions is in the fluid\n",
                sf["positions"].get<size_t>());
  std::printf("  released: %s\n", t["release"]["text"].get<std::string>().c_str());
  const json& ct = t["crossing_trajectories"];
  if (ct["on"].get<bool>())
    std::printf("  crossing trajectories: drift %.3g m/s = %.3g u'; time scale of the velocity "
                "it sees / %.3g along the drift, / %.3g across it\n",
                num(ct, "drift_speed"), num(ct, "drift_over_u_turb"), num(ct, "factor_along"),
                num(ct, "factor_across"));
  else
    std::printf("  crossing trajectories: off (%s)\n", ct["reason"].get<std::string>().c_str());
  std::printf("  %-11s %-10s %s\n", "effect", "size", "auto");
  for (const json& e : t["effects"]) {
    const std::string status =
        e["keep"].get<bool>() ? "keep" : "skip: " + e["reason"].get<std::string>();
    std::printf("  %-11s %-10.3g %s\n", e["name"].get<std::string>().c_str(), num(e, "size"),
                status.c_str());
  }
  std::printf("  auto chooses: %s\n", list(t["auto_chooses"]).c_str());
  if (!t["scene_lists"].is_null())
    std::printf("  the scene lists: %s\n", list(t["scene_lists"]).c_str());
  std::printf("  simulated: %s\n", list(t["simulated"]).c_str());
  const json& s = t["step"];
  if (s["batched"].get<bool>())
    std::printf("  step: batched (%s), %d bodies per block, %s loops, %s (docs/batched-step.md)\n",
                s["kind"].get<std::string>().c_str(), s["block"].get<int>(),
                s["isa"].get<std::string>().c_str(), s["precision"].get<std::string>().c_str());
  else
    std::printf("  step: scalar (not batched: %s)\n", s["reason"].get<std::string>().c_str());
  std::printf("  estimated cost: %.0f ns per body-step\n", num(t, "cost_ns"));
}

void explain(const std::string& path) {
  const json j = explain_scene(read_scene(path));
  // what looks like a mistake first (io/sanity.h), on stderr as lrigid run prints it
  for (const json& w : j["warnings"])
    std::fprintf(stderr, "lrigid: %s: %s: %s: %s\n", w["error"].get<bool>() ? "error" : "warning",
                 path.c_str(), w["key"].get<std::string>().c_str(),
                 w["message"].get<std::string>().c_str());
  const json &fluid = j["fluid"], &flow = j["flow"], &art = j["art"];
  std::printf("scene: %s\n", path.c_str());
  std::printf("fluid: rho_f = %g kg/m^3, nu = %g m^2/s, gravity = %g m/s^2\n",
              num(fluid, "density"), num(fluid, "kinematic_viscosity"), num(fluid, "gravity"));
  std::printf("flow (%s): |U| = %.3g m/s, k = %.3g m^2/s^2, eps = %.3g m^2/s^3",
              flow["source"].get<std::string>().c_str(), num(flow, "U"), num(flow, "k"),
              num(flow, "epsilon"));
  if (flow.contains("k_over_epsilon"))
    std::printf(", k/eps = %.3g s, tau_eta = sqrt(nu/eps) = %.3g s", num(flow, "k_over_epsilon"),
                num(flow, "tau_eta"));
  std::printf("\n");
  if (num(art, "mean_flow_scale") != 1 || num(art, "turbulence_scale") != 1)
    std::printf("art: mean_flow_scale = %g, turbulence_scale = %g (included above)\n",
                num(art, "mean_flow_scale"), num(art, "turbulence_scale"));
  std::printf("integrator: %s, dt = %g s; effects: %s\n",
              j["integrator"].get<std::string>().c_str(), num(j, "dt"),
              j["effects_auto"].get<bool>() ? "auto" : "listed by the scene");
  for (const json& t : j["body_types"]) print_type(t);
  std::printf("\nThe numbers (tau_p, St, Re, ...) and the reasons are explained in "
              "docs/effects.md, \"Glossary\".\n");
  std::printf("\nbodies against each other: %s\n",
              j["body_contact"]["words"].get<std::string>().c_str());
  std::printf("\nestimated total: %.3g body-steps, %.3g s on one core%s\n",
              num(j["total"], "body_steps"), num(j["total"], "seconds_one_core"),
              j["body_contact"]["mode"] == "collide"
                  ? " without the contacts between bodies (docs/contacts.md)"
                  : "");
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
