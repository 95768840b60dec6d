#include "io/explain.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "compile/compile_model.h"
#include "effects/registry.h"
#include "effects/turbulence.h"
#include "integrate/simulation.h"
#include "integrate/rigid_batch.h"
#include "io/added_mass_cache.h"
#include "io/explain_words.h"
#include "io/field_loader.h"
#include "io/sanity.h"
#include "model/model.h"
#include "model/release.h"
#include "util/quantile.h"

namespace lrigid {

namespace {

nlohmann::json names(EffectSet s) { return effect_names(s); }

const char* effect_name(Effect e) {
  for (const auto& info : all_effects())
    if (info.effect == e) return info.name;
  return "?";
}

// The flow where a body type's bodies start (their positions as initial_state draws them, at
// most 4096 of them, evenly picked): the grid's medians describe the whole domain, which can be
// far from the corner a scene releases its bodies in. Null on a uniform field.
nlohmann::json start_flow(const Scene& scene, const Model& model, const BodyType& t) {
  if (model.field.is_uniform() || t.count == 0) return nullptr;
  const BodySpec& spec = scene.bodies[t.spec];
  const size_t picks = std::min<size_t>(t.count, 4096);
  std::vector<double> speed, u_turb;
  for (size_t k = 0; k < picks; ++k) {
    const size_t i = t.first_body + k * t.count / picks;
    FluidSample fs;
    if (!model.field.sample(initial_position(model, spec, t.spec, static_cast<uint32_t>(i)), 0.0,
                            false, &fs))
      continue;
    speed.push_back(fs.U.norm());
    u_turb.push_back(std::sqrt(fs.sigma2));
  }
  nlohmann::json j = {{"positions", picks}, {"in_fluid", speed.size()}};
  if (speed.empty()) return j;
  j["U_median"] = quantile(speed, 0.5);
  j["U_p10"] = quantile(speed, 0.1);
  j["U_p90"] = quantile(speed, 0.9);
  j["u_turb_median"] = quantile(u_turb, 0.5);
  // k from the Langevin variance sigma2 = 2k/3, as the grid's line above takes it
  j["k_median"] = 1.5 * j["u_turb_median"].get<double>() * j["u_turb_median"].get<double>();
  return j;
}

// When the entry's bodies are released (model/release.h): its rate or times, the first and last
// body's time, and the same in words.
nlohmann::json release(const BodySpec& spec) {
  char buf[200];
  nlohmann::json j;
  const double first = release_time(spec, 0), last = release_time(spec, spec.count - 1);
  j["first"] = first;
  j["last"] = last;
  if (spec.release_rate > 0) {
    j["rate"] = spec.release_rate;
    j["start"] = spec.release_start;
    std::snprintf(buf, sizeof buf,
                  "%.6g bodies per second from t = %.6g s: body k of the entry at %.6g + k / "
                  "%.6g s, the last (k = %d) at %.6g s",
                  spec.release_rate, spec.release_start, spec.release_start, spec.release_rate,
                  spec.count - 1, last);
  } else if (!spec.release_times.empty()) {
    j["times"] = spec.release_times;
    const size_t n = spec.release_times.size();
    const int q = spec.count / int(n), r = spec.count % int(n);
    std::snprintf(buf, sizeof buf, "in %zu bursts from t = %.6g s to %.6g s: %d bodies each",
                  n, spec.release_times.front(), spec.release_times.back(), q);
    std::string text = buf;
    if (r > 0)
      text += ", " + std::to_string(q + 1) + " in the first " + std::to_string(r) + " of them";
    j["text"] = text;
    return j;
  } else {
    std::snprintf(buf, sizeof buf, "all at t = 0");
  }
  j["text"] = buf;
  return j;
}

nlohmann::json body_type(const Scene& scene, const Model& model, const FlowScales& flow,
                         size_t ti) {
  const BodyType& t = model.types[ti];
  const EffectAnalysis a = analyze_effects(scene, t, flow, scene.bodies[t.spec]);
  nlohmann::json j;
  j["index"] = ti;
  j["name"] = t.name;
  j["shape"] = shape_type_name(t.shape.type);
  j["count"] = t.count;
  j["mass"] = t.mass;
  j["volume"] = t.volume;
  j["density"] = t.density;
  j["density_ratio"] = a.density_ratio;
  j["aspect_ratio"] = a.aspect_ratio;
  j["flat"] = t.flat;
  j["normal_axis"] = t.normal_axis;
  j["size"] = a.size;
  j["terminal_speed"] = a.terminal_speed;
  j["relative_speed"] = a.speed;
  j["reynolds"] = a.reynolds;
  j["tau_p"] = a.tau_p;
  j["stokes_k_eps"] = a.stokes_k_eps;
  j["stokes_kolmogorov"] = a.stokes_kolmogorov;
  j["spin_ratio"] = a.spin_ratio;
  j["start_flow"] = start_flow(scene, model, t);
  j["release"] = release(scene.bodies[t.spec]);
  // crossing trajectories at the representative flow (effects/turbulence.h): the drift against
  // the turbulent velocity u' = sqrt(2k/3), and the factors by which it shortens the time scale of
  // the velocity the body sees along and across the drift
  {
    const double u_turb = std::sqrt(2.0 * flow.k / 3.0), vd = t.drift_speed;
    double along = 1, across = 1;
    crossing_factors(vd * vd, u_turb * u_turb, &along, &across);
    std::string off;
    if (!t.effects.has(Effect::Turbulence)) off = "no turbulence simulated";
    else if (model.turbulence_model != TurbulenceModel::Seen) off = "the body turbulence model";
    else if (!model.crossing_trajectories) off = "turbulence.crossing_trajectories is false";
    else if (!(vd > 0)) off = "no drift (neither weight nor buoyancy simulated, or they balance)";
    j["crossing_trajectories"] = {{"on", off.empty()},
                                  {"reason", off},
                                  {"drift_speed", vd},
                                  {"drift_over_u_turb", u_turb > 0 ? vd / u_turb : 0.0},
                                  {"factor_along", along},
                                  {"factor_across", across}};
  }
  j["effects"] = nlohmann::json::array();
  for (const auto& [e, size] : a.size_rel) {
    nlohmann::json r = {{"name", effect_name(e)}, {"size", size}, {"keep", true},
                        {"reason", ""}};
    for (const auto& [se, why] : a.skipped)
      if (se == e) r["keep"] = false, r["reason"] = why;
    j["effects"].push_back(r);
  }
  j["auto_chooses"] = names(a.chosen);
  j["scene_lists"] = scene.effects_auto ? nlohmann::json() : names(t.effects);
  j["simulated"] = names(t.effects);
  // which step it takes (integrate/simulation.h step_kind), and why not batched
  std::string why;
  const StepKind kind = step_kind(model, t, &why);
  // (batched: the kind of M its loops are compiled for, rigid_batch.h)
  const bool batched = kind == StepKind::Batched;
  const BatchMass mass = batch_mass(t);
  j["step"] = {{"batched", batched},
               {"kind", batched ? batch_mass_name(mass) : "scalar"},
               {"block", kBatch},
               {"isa", batch_isa()},
               {"precision", model.precision == Precision::Float ? "float" : "double"},
               {"reason", batched ? "" : why}};
  j["cost_ns"] = batched ? estimated_batched_cost_ns(t.effects, model.precision,
                                                     mass != BatchMass::Isotropic,
                                                     scene.integrator)
                         : estimated_cost_ns(t.effects, scene.integrator, !scene.uniform_field,
                                             t.M_isotropic);
  return j;
}

// Whether contacts between bodies matter for the scene (docs/contacts.md "Bodies against each
// other"): in flight, the bodies' mean spacing in their spawn boxes against their size; on a
// colliding ground, the share of the ground under the spawn boxes their largest projected areas
// would cover spread evenly (wind gathers them into corners: more). Either says they meet: then body_contact "collide" keeps them apart.
nlohmann::json body_contact_need(const Scene& scene, const Model& model) {
  double volume = 0, footprint = 0, cover = 0, size = 0;
  size_t n = 0;
  for (const BodyType& t : model.types) {
    const double count = double(t.count);
    size += count * 2 * t.reach;
    cover += count * t.area_max;
    n += t.count;
  }
  // the box around the spawn boxes (entries often share one)
  Vec3 lo = Vec3::Constant(HUGE_VAL), hi = Vec3::Constant(-HUGE_VAL);
  for (const BodySpec& b : scene.bodies) {
    if (!b.spawn_in_box) continue;
    lo = lo.cwiseMin(b.box_lo);
    hi = hi.cwiseMax(b.box_hi);
  }
  if (lo.x() <= hi.x()) {
    const Vec3 d = hi - lo;
    volume = d.x() * d.y() * d.z();
    footprint = d.x() * d.y();
  }
  nlohmann::json j;
  j["mode"] = scene.body_contact ? "collide" : "off";
  j["bodies"] = n;
  size = n > 0 ? size / double(n) : 0.0;
  j["size"] = size;
  const double spacing = volume > 0 && n > 0 ? std::cbrt(volume / double(n)) : 0.0;
  j["spacing"] = spacing;
  const double ground_cover = footprint > 0 ? cover / footprint : 0.0;
  j["ground_cover"] = model.ground_collides() ? ground_cover : 0.0;
  const bool in_flight = n > 1 && spacing > 0 && spacing < 5 * size;
  const bool on_ground = model.ground_collides() && n > 1 && ground_cover > 0.05;
  j["matters"] = in_flight || on_ground;
  char buf[400];
  std::string words;
  if (spacing > 0) {
    std::snprintf(buf, sizeof buf,
                  "%zu bodies in their spawn boxes: mean spacing %.3g m, %.3g times their size "
                  "(%.3g m): they %s in flight",
                  n, spacing, spacing / size, size, in_flight ? "meet" : "rarely meet");
    words = buf;
  }
  if (model.ground_collides() && footprint > 0) {
    std::snprintf(buf, sizeof buf,
                  "%son the ground, spread evenly under their spawn boxes, they would cover %.2g of "
                  "it: %s",
                  words.empty() ? "" : "; ", ground_cover,
                  on_ground ? "those that come to rest together pile up" : "few touch");
    words += buf;
  }
  if (words.empty()) words = "no spawn box to judge the bodies' spacing by";
  words += scene.body_contact
               ? "; body_contact is \"collide\": they collide"
               : (in_flight || on_ground ? "; body_contact is \"off\": they pass through each "
                                           "other (\"collide\" keeps them apart)"
                                         : "; body_contact is \"off\"");
  j["words"] = words;
  return j;
}

}  // namespace

nlohmann::json explain_scene(const Scene& scene) {
  FluidField field = load_field(scene, StreamMode::Off, true);
  const FlowScales flow = flow_scales(scene, field);
  const Model model = compile_model(scene, std::move(field), cached_added_mass);
  const double nu = scene.kinematic_viscosity;
  nlohmann::json j;
  j["scene"] = scene.file;
  j["fluid"] = {{"density", scene.fluid_density},
                {"kinematic_viscosity", nu},
                {"gravity", scene.gravity.norm()}};
  j["flow"] = {{"source", flow.source}, {"U", flow.U}, {"k", flow.k}, {"epsilon", flow.eps}};
  if (flow.k > 0 && flow.eps > 0) {
    j["flow"]["k_over_epsilon"] = flow.k / flow.eps;
    j["flow"]["tau_eta"] = std::sqrt(nu / flow.eps);
  }
  j["art"] = {{"mean_flow_scale", scene.mean_flow_scale},
              {"turbulence_scale", scene.turbulence_scale}};
  j["integrator"] = integrator_name(scene.integrator);
  j["dt"] = scene.dt;
  j["effects_auto"] = scene.effects_auto;
  j["warnings"] = findings_json(check_scene(scene, model));  // io/sanity.h
  j["body_types"] = nlohmann::json::array();
  double total_ns = 0;
  for (size_t ti = 0; ti < model.types.size(); ++ti) {
    j["body_types"].push_back(body_type(scene, model, flow, ti));
    j["body_types"].back()["plain_words"] = plain_words(j["body_types"].back(), j);
    total_ns += j["body_types"].back()["cost_ns"].get<double>() * double(model.types[ti].count);
  }
  const double steps = std::round(scene.duration / scene.dt);
  j["body_contact"] = body_contact_need(scene, model);
  j["total"] = {{"body_steps", steps * double(model.body_count)},
                {"seconds_one_core", total_ns * steps * 1e-9}};
  return j;
}

}  // namespace lrigid
