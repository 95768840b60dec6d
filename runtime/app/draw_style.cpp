#include "draw_style.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "checks.h"
#include "model/state.h"
#include "util/error.h"
#include "vtk_draw.h"

namespace lrigid::app {

namespace {

std::string numbers(const std::vector<double>& v) {
  std::string s;
  for (double x : v) {
    char b[32];
    std::snprintf(b, sizeof b, "%s%g", s.empty() ? "" : " ", x);
    s += b;
  }
  return s;
}

// the 6 numbers of --frame x0 x1 y0 y1 z0 z1; false when it is one name
bool frame_box(const std::vector<std::string>& frame, Bounds* box) {
  if (frame.size() != 6) return false;
  double v[6];
  for (int i = 0; i < 6; ++i) {
    char* end = nullptr;
    v[i] = std::strtod(frame[size_t(i)].c_str(), &end);
    if (end == frame[size_t(i)].c_str() || *end != '\0' || !std::isfinite(v[i]))
      throw Error(ExitCode::Usage, "--frame: \"" + frame[size_t(i)] +
                                       "\" is not a number: give x0 x1 y0 y1 z0 z1 in m, or "
                                       "the name of a body entry");
  }
  box->add(Vec3(v[0], v[2], v[4]));
  box->add(Vec3(v[1], v[3], v[5]));
  if (!(v[0] < v[1] && v[2] < v[3] && v[4] < v[5])) {
    std::string s;
    for (const auto& f : frame) s += (s.empty() ? "" : " ") + f;
    throw Error(ExitCode::Usage,
                "--frame " + s + ": the box is empty; give x0 < x1, y0 < y1, z0 < z1 (m)");
  }
  return true;
}

}  // namespace

ColourBy PictureOptions::colouring() const {
  return colour_by == "state"   ? ColourBy::State
         : colour_by == "speed" ? ColourBy::Speed
                                : ColourBy::Type;
}

void add_picture_options(CLI::App* cmd, PictureOptions* o) {
  cmd->add_option("--camera-position", o->camera_position,
                  "Camera position X Y Z, m (default: in front, left and above the framed box)")
      ->expected(3);
  cmd->add_option("--camera-target", o->camera_target,
                  "Point the camera looks at (the picture's centre) X Y Z, m (default: the "
                  "framed box's centre)")
      ->expected(3);
  cmd->add_option("--fov", o->fov_deg, "Vertical field of view, degrees, in (0, 180) (default 30)");
  cmd->add_option("--frame", o->frame,
                  "Fit the view to a body entry's bodies (its name in the scene) or to a box "
                  "x0 x1 y0 y1 z0 z1, m")
      ->expected(1, 6);
  cmd->add_option("--color-by,--colour", o->colour_by,
                  "Colour bodies by type (body entry), state (flying, resting, ...) or speed "
                  "(|v|, m/s)")
      ->check(CLI::IsMember({"type", "state", "speed"}));
  cmd->add_option("--body-scale,--enlarge", o->body_scale,
                  "Draw every body this many times larger (default: true size, unless an "
                  "entry's median body would span under 4 pixels)")
      ->check(positive("a factor > 0"));
}

void check_picture_options(const PictureOptions& o) {
  if (!(o.fov_deg > 0 && o.fov_deg < 180)) {
    char b[64];
    std::snprintf(b, sizeof b, "%g", o.fov_deg);
    throw Error(ExitCode::Usage, std::string("--fov ") + b +
                                     ": the vertical field of view must be in (0, 180) degrees");
  }
  if (o.camera_position.size() == 3 && o.camera_target.size() == 3 &&
      Vec3(o.camera_position[0], o.camera_position[1], o.camera_position[2]) ==
          Vec3(o.camera_target[0], o.camera_target[1], o.camera_target[2]))
    throw Error(ExitCode::Usage, "--camera-target " + numbers(o.camera_target) +
                                     ": the same point as --camera-position; the camera must "
                                     "look at a point away from itself");
  if (!o.frame.empty() && o.frame.size() != 1 && o.frame.size() != 6) {
    std::string s;
    for (const auto& f : o.frame) s += (s.empty() ? "" : " ") + f;
    throw Error(ExitCode::Usage, "--frame " + s +
                                     ": give the name of a body entry or 6 numbers x0 x1 y0 y1 "
                                     "z0 z1 (m)");
  }
  Bounds box;
  frame_box(o.frame, &box);
}

CameraPose choose_camera(const PictureOptions& o, const Bounds& whole, const EntryBoxes& entries,
                         double aspect) {
  check_picture_options(o);
  Bounds box = whole;
  if (o.frame.size() == 6) {
    box = Bounds();
    frame_box(o.frame, &box);
  } else if (o.frame.size() == 1) {
    size_t e = 0;
    while (e < entries.names.size() && entries.names[e] != o.frame[0]) ++e;
    if (e == entries.names.size()) {
      std::string names;
      for (const auto& n : entries.names) names += (names.empty() ? "" : ", ") + n;
      throw Error(ExitCode::Usage, "--frame " + o.frame[0] +
                                       ": no body entry of that name; "
                                       "the entries are: " +
                                       names);
    }
    if (entries.boxes[e].empty())
      throw Error(ExitCode::Usage,
                  "--frame " + o.frame[0] + ": none of its bodies is visible in the frames drawn");
    box = entries.boxes[e];
  }
  CameraPose c = fit_box(box, default_view_direction(), o.fov_deg, aspect);
  const Vec3 offset = c.position - c.target;
  if (o.camera_target.size() == 3) {
    c.target = Vec3(o.camera_target[0], o.camera_target[1], o.camera_target[2]);
    c.position = c.target + offset;
  }
  if (o.camera_position.size() == 3)
    c.position = Vec3(o.camera_position[0], o.camera_position[1], o.camera_position[2]);
  if ((c.position - c.target).norm() <= 0)
    throw Error(ExitCode::Usage, "--camera-position " + numbers(o.camera_position) +
                                     ": the point the camera looks at; give another "
                                     "--camera-target");
  c.up = view_up(c.position, c.target);
  return c;
}

double largest_extent(const TriangleMesh& surface) {
  Bounds b;
  for (const Vec3& v : surface.vertices) b.add(v);
  return b.empty() ? 0.0 : (b.hi - b.lo).maxCoeff();
}

EntryTally::EntryTally(const std::vector<size_t>& type_entry,
                       const std::vector<std::string>& type_name,
                       const std::vector<double>& type_size)
    : type_entry_(type_entry), type_size_(type_size) {
  size_t ne = 0;
  for (size_t e : type_entry) ne = std::max(ne, e + 1);
  names_.assign(ne, "");
  reach_.assign(ne, 0.0);
  sizes_.resize(ne);
  seen_.resize(ne);
  boxes_.resize(ne);
  for (size_t t = 0; t < type_entry.size(); ++t) {
    const size_t e = type_entry[t];
    if (names_[e].empty()) names_[e] = type_name[t];
    reach_[e] = std::max(reach_[e], 0.5 * type_size[t]);
  }
}

void EntryTally::add_body(size_t type) { sizes_[type_entry_[type]].push_back(type_size_[type]); }

void EntryTally::add_seen(size_t type, const Vec3& x) {
  seen_[type_entry_[type]].push_back(x);
  boxes_[type_entry_[type]].add(x);
}

EntryBoxes EntryTally::boxes() const {
  EntryBoxes out;
  out.names = names_;
  out.boxes = boxes_;
  for (size_t e = 0; e < out.boxes.size(); ++e) {
    if (out.boxes[e].empty()) continue;
    out.boxes[e].lo -= Vec3::Constant(reach_[e]);
    out.boxes[e].hi += Vec3::Constant(reach_[e]);
  }
  return out;
}

double EntryTally::widest() const {
  double w = 0;
  for (double r : reach_) w = std::max(w, r);
  return w;
}

std::vector<double> EntryTally::factors(const PictureOptions& o, const CameraPose& c,
                                        int height) const {
  std::vector<double> f(names_.size(), o.body_scale);
  if (o.body_scale > 0) return f;
  for (size_t e = 0; e < f.size(); ++e) f[e] = true_scale_factor(c, height, sizes_[e], seen_[e]);
  return f;
}

std::string enlargement_note(const std::vector<std::string>& names,
                             const std::vector<double>& factors) {
  std::string s;
  for (size_t e = 0; e < names.size() && e < factors.size(); ++e) {
    if (factors[e] <= 1.05) continue;
    char b[32];
    std::snprintf(b, sizeof b, " x%.2g", factors[e]);
    s += (s.empty() ? "drawn enlarged: " : ", ") + names[e] + b;
  }
  return s;
}

void state_colour(int code, unsigned char rgb[3]) {
  // flying orange, sliding yellow, resting red, sleeping magenta, exited grey, landed green,
  // failed black: none blue (the slices), none pale (the ground, the background)
  static const unsigned char kState[kStateCount][3] = {
      {235, 130, 30},  {240, 215, 40}, {215, 25, 35}, {200, 50, 200},
      {110, 110, 110}, {40, 160, 60},  {15, 15, 15}};
  const int c = code >= 0 && code < kStateCount ? code : kStateCount - 1;
  for (int k = 0; k < 3; ++k) rgb[k] = kState[c][k];
}

std::vector<LegendEntry> legend_entries(ColourBy by, const std::vector<std::string>& entry_names,
                                        const std::vector<double>& factors,
                                        const std::vector<bool>& states_shown) {
  std::vector<LegendEntry> out;
  auto factor_text = [&](size_t e) {
    char b[48] = "";
    if (e < factors.size() && factors[e] > 1.05)
      std::snprintf(b, sizeof b, " (drawn %.2gx)", factors[e]);
    return std::string(b);
  };
  if (by == ColourBy::Type) {
    for (size_t e = 0; e < entry_names.size(); ++e) {
      LegendEntry l;
      l.label = entry_names[e] + factor_text(e);
      type_colour(e, l.rgb);
      out.push_back(l);
    }
    return out;
  }
  if (by == ColourBy::State)
    for (int s = 0; s < kStateCount; ++s) {
      if (size_t(s) >= states_shown.size() || !states_shown[size_t(s)]) continue;
      LegendEntry l;
      l.label = kStateNames[s];
      state_colour(s, l.rgb);
      out.push_back(l);
    }
  for (size_t e = 0; e < entry_names.size(); ++e) {
    if (factor_text(e).empty()) continue;
    LegendEntry l;
    l.label = entry_names[e] + factor_text(e);
    l.swatch = false;
    l.rgb[0] = l.rgb[1] = l.rgb[2] = 40;
    out.push_back(l);
  }
  return out;
}

}  // namespace lrigid::app
