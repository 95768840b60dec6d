#include "io/scene_json.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "body/bem.h"
#include "body/mass_properties.h"
#include "body/mesh_check.h"
#include "body/shape_limits.h"
#include "body/solidify.h"
#include "effects/registry.h"
#include "io/dcc_cache.h"
#include "io/mesh_io.h"
#include "util/error.h"
#include "util/suggest.h"

namespace lrigid {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

using Keys = std::initializer_list<const char*>;

// A JSON object being read: remembers which keys were used so the rest can be reported.
// `keys` are all the keys this kind of object may hold: any other is reported at once, before
// a required key is found missing, with the nearest valid key ("densty" -> "density").
class Obj {
 public:
  Obj(const json& j, std::string path, const std::string& file, Keys keys)
      : j_(j), path_(std::move(path)), file_(file) {
    if (!j_.is_object()) fail("", "must be an object, got " + dump(j_));
    for (const char* k : keys) valid_.emplace_back(k);
    for (auto it = j_.begin(); it != j_.end(); ++it)
      if (std::find(valid_.begin(), valid_.end(), it.key()) == valid_.end())
        fail_unknown(it.key());
  }

  bool has(const std::string& key) const { return j_.contains(key); }

  const json& get(const std::string& key) {
    if (!j_.contains(key)) fail(key, "is required");
    used_.insert(key);
    return j_.at(key);
  }
  const json* find(const std::string& key) {
    if (!j_.contains(key)) return nullptr;
    used_.insert(key);
    return &j_.at(key);
  }

  double number(const std::string& key) { return as_number(get(key), key); }
  double positive(const std::string& key) {
    const double v = number(key);
    if (!(v > 0)) fail(key, "must be > 0, got " + dump(get(key)));
    return v;
  }
  double positive_or(const std::string& key, double def) { return has(key) ? positive(key) : def; }
  // a number in the closed range [lo, hi]; `range` is how the message states it
  double bounded(const std::string& key, double lo, double hi, const std::string& range) {
    const double v = number(key);
    if (!(v >= lo && v <= hi)) fail(key, "must be in " + range + ", got " + dump(get(key)));
    return v;
  }
  // three numbers, each in [-limit, limit]; `range` is how the message states it
  Vec3 bounded_vec3(const std::string& key, double limit, const std::string& range) {
    return as_bounded_vec3(get(key), key, limit, range);
  }
  Vec3 as_bounded_vec3(const json& v, const std::string& key, double limit,
                       const std::string& range) const {
    const Vec3 r = as_vec3(v, key);
    if (!(r.cwiseAbs().maxCoeff() <= limit))
      fail(key, "must all be in " + range + ", got " + dump(v));
    return r;
  }
  bool boolean(const std::string& key) {
    const json& v = get(key);
    if (!v.is_boolean()) fail(key, "must be true or false, got " + dump(v));
    return v.get<bool>();
  }
  std::string string(const std::string& key) {
    const json& v = get(key);
    if (!v.is_string()) fail(key, "must be a string, got " + dump(v));
    // a NUL ends a path early: "out\u0000x" would write into "out"
    if (v.get<std::string>().find('\0') != std::string::npos)
      fail(key, "must not contain a NUL character (\\u0000), got " + dump(v));
    return v.get<std::string>();
  }
  Vec3 vec3(const std::string& key) { return as_vec3(get(key), key); }
  Vec3 vec3_or(const std::string& key, const Vec3& def) { return has(key) ? vec3(key) : def; }
  Obj object(const std::string& key, Keys keys) { return Obj(get(key), sub(key), file_, keys); }

  double as_number(const json& v, const std::string& key) const {
    if (!v.is_number()) fail(key, "must be a number, got " + dump(v));
    const double d = v.get<double>();
    if (!std::isfinite(d)) fail(key, "must be finite, got " + dump(v));
    return d;
  }
  Vec3 as_vec3(const json& v, const std::string& key) const {
    if (!v.is_array() || v.size() != 3) fail(key, "must be an array of 3 numbers, got " + dump(v));
    Vec3 r;
    for (int i = 0; i < 3; ++i) r[i] = as_number(v[i], key + "[" + std::to_string(i) + "]");
    return r;
  }

  // unknown keys are errors (a typo must not silently fall back to a default); here: valid
  // keys that do not apply (a "radius" on a box)
  void finish() const {
    for (auto it = j_.begin(); it != j_.end(); ++it)
      if (!used_.count(it.key())) {
        std::vector<std::string> used(used_.begin(), used_.end());
        fail("", "key \"" + it.key() + "\" does not apply here" + did_you_mean(it.key(), used));
      }
  }
  [[noreturn]] void fail_unknown(const std::string& key) const {
    const auto dot = key.find('.');
    if (dot != std::string::npos && dot > 0)
      fail("", "unknown key \"" + key + "\": keys are nested, not dotted; write \"" +
                   key.substr(0, dot) + "\": { \"" + key.substr(dot + 1) + "\": ... }");
    fail("", "unknown key \"" + key + "\"" + did_you_mean(key, valid_));
  }

  std::string sub(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  [[noreturn]] void fail(const std::string& key, const std::string& msg) const {
    fail_input(file_, key.empty() ? path_ : (key[0] == '[' ? path_ + key : sub(key)), msg);
  }
  static std::string dump(const json& v) {
    std::string s = v.dump();
    return s.size() > 60 ? s.substr(0, 57) + "..." : s;
  }
  const std::string& file() const { return file_; }

 private:
  const json& j_;
  std::string path_;
  const std::string& file_;
  std::set<std::string> used_;
  std::vector<std::string> valid_;
};

std::string resolve(const std::string& rel, const std::string& scene_file) {
  fs::path p(rel);
  if (p.is_absolute()) return p.lexically_normal().string();
  return (fs::path(scene_file).parent_path() / p).lexically_normal().string();
}

// For an error about a file the scene names: where a relative name was looked for (the scene's
// folder, absolute), so that a wrong working directory or a misplaced scene shows at once; empty
// for an absolute name
std::string resolved_against(const std::string& rel, const std::string& scene_file) {
  if (fs::path(rel).is_absolute()) return "";
  std::error_code ec;
  fs::path folder = fs::absolute(fs::path(scene_file).parent_path(), ec);
  if (ec) return "";
  return " (\"" + rel + "\" is relative to the scene's folder, " +
         folder.lexically_normal().string() + ")";
}

// the keys of a shape object (a body's "shape", and Python's lrigid.added_mass)
constexpr Keys kShapeKeys = {"type",  "radius", "semi_axes", "size",
                             "file",  "scale",  "thickness", "panels"};

// the shapes' lengths (body/shape_limits.h) as the messages state them
const char* const kLengthRange = "in [1e-9, 1e6] m";

// The other quantities' ranges: far beyond any body in air or water, and within them the
// products the step forms (momenta, drag, the added mass) stay finite; outside them a force
// overflows to NaN, or "auto" judges an effect by a non-finite number and drops it.
constexpr double kMinDensity = 1e-6, kMaxDensity = 1e6;
const char* const kDensityRange = "[1e-6, 1e6] kg/m^3";
constexpr double kMaxCoordinate = 1e9;  // positions, m
const char* const kCoordinateRange = "[-1e9, 1e9] m";
constexpr double kMaxSpeed = 1e5;  // velocities, m/s
const char* const kSpeedRange = "[-1e5, 1e5] m/s";
constexpr double kMaxSpin = 1e6;  // angular velocities, rad/s
const char* const kSpinRange = "[-1e6, 1e6] rad/s";

Shape read_shape(Obj o, BodySpec* b) {
  const std::string type = o.string("type");
  Shape s;
  auto lengths = [&](const char* key, const Vec3& l) {
    if (!(l.minCoeff() >= kMinShapeLength && l.maxCoeff() <= kMaxShapeLength))
      o.fail(key, std::string("must all be ") + kLengthRange + ", got " + Obj::dump(o.get(key)));
  };
  if (type == "sphere") {
    const double r = o.positive("radius");
    if (!(r >= kMinShapeLength && r <= kMaxShapeLength))
      o.fail("radius", std::string("must be ") + kLengthRange + ", got " + Obj::dump(o.get("radius")));
    s = Shape::sphere(r);
  } else if (type == "ellipsoid") {
    const Vec3 a = o.vec3("semi_axes");
    if (!(a.minCoeff() > 0))
      o.fail("semi_axes", "must all be > 0, got " + Obj::dump(o.get("semi_axes")));
    lengths("semi_axes", a);
    s = Shape::ellipsoid(a.x(), a.y(), a.z());
  } else if (type == "box") {
    const Vec3 l = o.vec3("size");
    if (!(l.minCoeff() > 0)) o.fail("size", "must all be > 0, got " + Obj::dump(o.get("size")));
    lengths("size", l);
    if (!(l.maxCoeff() / l.minCoeff() <= kMaxBoxAspect))
      o.fail("size", "longest edge / shortest edge must be at most 1e5 (as body/shape.cpp's: the "
                     "boundary elements lose the thin direction beyond), got " +
                         Obj::dump(o.get("size")));
    s = Shape::box(l.x(), l.y(), l.z());
  } else if (type == "mesh") {
    const std::string name = o.string("file"), file = resolve(name, o.file());
    const double scale = o.positive_or("scale", 1.0);
    std::shared_ptr<TriangleMesh> mesh;
    try {
      mesh = std::make_shared<TriangleMesh>(read_mesh(file));
    } catch (const Error& e) {
      // the mesh's own message names the mesh file; add where the scene asked for it and, for a
      // file that is not there, where a relative name was looked for
      std::error_code ec;
      o.fail("file", std::string(e.what()) +
                         (fs::exists(file, ec) ? "" : resolved_against(name, o.file())));
    }
    for (Vec3& v : mesh->vertices) v *= scale;
    // the scaled mesh's size as a box's: a scale that takes it out of that range would end in
    // the mesh checks' or the boundary elements' misleading words
    if (!mesh->vertices.empty()) {
      Vec3 lo = mesh->vertices[0], hi = mesh->vertices[0];
      for (const Vec3& v : mesh->vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
      }
      const double extent = (hi - lo).maxCoeff();
      if (!(extent >= kMinShapeLength && extent <= kMaxShapeLength)) {
        std::ostringstream m;
        m << "makes " << file << " " << extent << " m wide; its largest extent must be "
          << kLengthRange << ", got " << Obj::dump(o.get("scale"));
        o.fail("scale", m.str());
      }
    }
    // a single-sided surface (a leaf, a card) becomes the thin body it stands for
    // (body/solidify.h); "thickness" is in m, as the coordinates after "scale"
    double thickness = 0;
    if (o.has("thickness")) {
      thickness = o.positive("thickness");
      if (!(thickness >= kMinShapeLength && thickness <= kMaxShapeLength))
        o.fail("thickness", std::string("must be ") + kLengthRange + ", got " +
                                Obj::dump(o.get("thickness")));
      try {
        *mesh = solidify_surface(*mesh, thickness, file);
      } catch (const Error& e) {
        o.fail("thickness", e.what());
      }
    }
    try {
      s = Shape::from_mesh(mesh, file);
      s.scale = scale;
      s.thickness = thickness;
    } catch (const Error& e) {
      // what the user most likely meant: an open mesh without a thickness is a leaf or a card
      // as a DCC tool exports it; a thick one that crosses itself is thicker than its bends
      std::string hint;
      if (thickness == 0 && boundary_edge_count(*mesh) > 0)
        hint = "; a single-sided surface (a leaf, a card) needs its thickness: \"shape\": "
               "{\"type\": \"mesh\", \"file\": ..., \"thickness\": t} (m)";
      else if (thickness > 0 && check_mesh(*mesh).defect == MeshDefect::SelfIntersecting)
        hint = "; the thickness " + Obj::dump(o.get("thickness")) +
               " m is more than the surface's bends leave room for";
      o.fail(thickness > 0 ? "thickness" : "file", e.what() + hint);
    }
  } else {
    o.fail("type", "must be sphere, ellipsoid, box or mesh, got \"" + type + "\"");
  }
  if (const json* p = o.find("panels")) {
    // checked before any tessellation: a box of 2e9 panels would be built before the solver's
    // own limit is reached
    if (!p->is_number_integer() || p->get<long long>() < 0 || p->get<long long>() > kMaxBemPanels)
      o.fail("panels", "must be an integer in [0, " + std::to_string(kMaxBemPanels) +
                           "] (0: the default), got " + Obj::dump(*p));
    b->panels = static_cast<int>(p->get<long long>());
  }
  o.finish();
  return s;
}

constexpr Keys kBodyKeys = {"name",     "shape",    "density",     "mass_offset",
                            "count",    "position", "spawn_box",   "orientation",
                            "velocity", "angular_velocity", "variation", "contact",
                            "release",  "spawn"};

// The latest release time a scene may give, s: far beyond any run, and its step count stays
// an integer the step counter holds.
constexpr double kMaxReleaseTime = 1e9;

// "release": {"rate": R, "start": t} or {"times": [t0, t1, ...]} (model/release.h)
void read_release(Obj r, BodySpec* b) {
  const bool rate = r.has("rate"), times = r.has("times");
  if (rate == times)
    r.fail("", std::string("needs exactly one of \"rate\" (bodies per second) or \"times\" (s)") +
                   (rate ? ", got both" : ""));
  if (rate) {
    b->release_rate = r.positive("rate");
    if (r.has("start")) {
      b->release_start = r.number("start");
      if (!(b->release_start >= 0 && b->release_start <= kMaxReleaseTime))
        r.fail("start", "must be in [0, 1e9] s, got " + Obj::dump(r.get("start")));
    }
    // the last body's time stays within the same bound
    if (!(b->release_start + double(b->count - 1) / b->release_rate <= kMaxReleaseTime))
      r.fail("rate", "releases the last of " + std::to_string(b->count) +
                         " bodies after 1e9 s, got " + Obj::dump(r.get("rate")));
  } else {
    if (r.has("start")) r.fail("start", "applies to \"rate\" only (the times are absolute)");
    const json& t = r.get("times");
    if (!t.is_array() || t.empty())
      r.fail("times", "must be a non-empty list of times in s, got " + Obj::dump(t));
    for (size_t i = 0; i < t.size(); ++i) {
      const std::string key = "times[" + std::to_string(i) + "]";
      const double ti = r.as_number(t[i], key);
      if (!(ti >= 0 && ti <= kMaxReleaseTime))
        r.fail(key, "must be in [0, 1e9] s, got " + Obj::dump(t[i]));
      if (i > 0 && !(ti > b->release_times.back()))
        r.fail(key, "must be greater than the time before it (" +
                        Obj::dump(t[i - 1]) + "): times increase, got " + Obj::dump(t[i]));
      b->release_times.push_back(ti);
    }
  }
  r.finish();
}

// A "contact" object (a body type's, or the scene's defaults): restitution in [0, 1],
// friction >= 0 and rolling_resistance >= 0, each optional; *given says which were.
void read_contact(Obj o, ContactSpec* c, bool* restitution_given, bool* friction_given,
                  bool* rolling_given) {
  if (o.has("restitution")) {
    const double e = o.number("restitution");
    if (!(e >= 0 && e <= 1))
      o.fail("restitution", "must lie in [0, 1] (normal speed after / before an impact), got " +
                                Obj::dump(o.get("restitution")));
    c->restitution = e;
    *restitution_given = true;
  }
  if (o.has("friction")) {
    const double mu = o.number("friction");
    if (!(mu >= 0))
      o.fail("friction", "must be >= 0 (Coulomb coefficient), got " +
                             Obj::dump(o.get("friction")));
    c->friction = mu;
    *friction_given = true;
  }
  if (o.has("rolling_resistance")) {
    const double mur = o.number("rolling_resistance");
    if (!(mur >= 0))
      o.fail("rolling_resistance",
             "must be >= 0 (rolling resistance coefficient), got " +
                 Obj::dump(o.get("rolling_resistance")));
    c->rolling_resistance = mur;
    *rolling_given = true;
  }
  o.finish();
}

constexpr Keys kContactKeys = {"restitution", "friction", "rolling_resistance"};

// "contact": "collide" | "stop" of the object o (ground, walls)
ContactMode read_contact_mode(Obj& o) {
  const std::string m = o.string("contact");
  if (m == "collide") return ContactMode::Collide;
  if (m == "stop") return ContactMode::Stop;
  o.fail("contact", "must be \"collide\" or \"stop\", got \"" + m + "\"");
}

// the scene's contact keys: "contact" (the body types' defaults, applied to every body type
// for the keys it does not give), "walls" and "outside" (ground.contact is read with the ground)
void read_scene_contacts(Obj& top, Scene* s) {
  if (top.has("contact")) {
    bool e_given = false, mu_given = false, mur_given = false;
    read_contact(top.object("contact", kContactKeys), &s->contact, &e_given, &mu_given,
                 &mur_given);
  }
  for (BodySpec& b : s->bodies) {
    if (!b.restitution_given) b.contact.restitution = s->contact.restitution;
    if (!b.friction_given) b.contact.friction = s->contact.friction;
    if (!b.rolling_given) b.contact.rolling_resistance = s->contact.rolling_resistance;
  }
  if (top.has("walls")) {
    Obj w = top.object("walls", {"contact"});
    if (w.has("contact")) s->walls_contact = read_contact_mode(w);
    w.finish();
  }
  if (top.has("outside")) {
    const std::string m = top.string("outside");
    if (m == "remove") s->outside = OutsideMode::Remove;
    else if (m == "stop") s->outside = OutsideMode::Stop;
    else top.fail("outside", "must be \"remove\" or \"stop\", got \"" + m + "\"");
  }
  if (top.has("body_contact")) {
    const std::string m = top.string("body_contact");
    if (m == "collide") s->body_contact = true;
    else if (m == "off") s->body_contact = false;
    else top.fail("body_contact", "must be \"collide\" or \"off\", got \"" + m + "\"");
  }
}

BodySpec read_body(Obj o) {
  BodySpec b;
  b.name = o.string("name");
  // the name is a field of trajectories.csv and landings.csv: nothing that would split or
  // quote a row
  for (const char c : b.name)
    if (c == ',' || c == '"' || static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      o.fail("name", "must not contain commas, double quotes or control characters (it is a "
                     "CSV field), got " + Obj::dump(o.get("name")));
  if (b.name.empty()) o.fail("name", "must not be empty");
  b.shape = read_shape(o.object("shape", kShapeKeys), &b);
  b.density = o.bounded("density", kMinDensity, kMaxDensity, kDensityRange);
  b.mass_offset = o.vec3_or("mass_offset", Vec3::Zero());
  if (const std::string why = offset_outside_shape(b.shape, b.mass_offset); !why.empty())
    o.fail("mass_offset", why);
  {
    const json& c = o.get("count");
    if (!c.is_number_integer() || c.get<long long>() < 1)
      o.fail("count", "must be an integer >= 1, got " + Obj::dump(c));
    if (c.get<long long>() > 100000000LL) o.fail("count", "more than 1e8 bodies is not supported");
    b.count = c.get<int>();
  }
  const bool pos = o.has("position"), box = o.has("spawn_box"), surf = o.has("spawn");
  if (int(pos) + int(box) + int(surf) != 1)
    o.fail("", "needs exactly one of \"position\", \"spawn_box\" or \"spawn\"");
  if (surf) {
    // {"surface": "solids", "box": [[x0,y0,z0],[x1,y1,z1]], "offset": m}
    Obj sp = o.object("spawn", {"surface", "box", "offset"});
    const json& kind = sp.get("surface");
    if (!kind.is_string() || kind.get<std::string>() != "solids")
      sp.fail("surface", "must be \"solids\" (the grid's solids), got " + Obj::dump(kind));
    b.spawn_on_solids = true;
    if (sp.has("box")) {
      const json& sb = sp.get("box");
      if (!sb.is_array() || sb.size() != 2)
        sp.fail("box", "must be [[x0,y0,z0],[x1,y1,z1]], got " + Obj::dump(sb));
      b.spawn_surface_box = true;
      b.box_lo = sp.as_bounded_vec3(sb[0], "box[0]", kMaxCoordinate, kCoordinateRange);
      b.box_hi = sp.as_bounded_vec3(sb[1], "box[1]", kMaxCoordinate, kCoordinateRange);
      for (int a = 0; a < 3; ++a)
        if (!(b.box_hi[a] >= b.box_lo[a])) sp.fail("box", "upper corner below lower corner");
    }
    if (sp.has("offset")) {
      b.spawn_offset = sp.number("offset");
      if (!(b.spawn_offset >= 0 && b.spawn_offset <= kMaxCoordinate))
        sp.fail("offset", "must be in [0, 1e9] m, got " + Obj::dump(sp.get("offset")));
    }
    sp.finish();
  } else if (pos) {
    b.position = o.bounded_vec3("position", kMaxCoordinate, kCoordinateRange);
  } else {
    const json& sb = o.get("spawn_box");
    if (!sb.is_array() || sb.size() != 2)
      o.fail("spawn_box", "must be [[x0,y0,z0],[x1,y1,z1]], got " + Obj::dump(sb));
    b.spawn_in_box = true;
    b.box_lo = o.as_bounded_vec3(sb[0], "spawn_box[0]", kMaxCoordinate, kCoordinateRange);
    b.box_hi = o.as_bounded_vec3(sb[1], "spawn_box[1]", kMaxCoordinate, kCoordinateRange);
    for (int a = 0; a < 3; ++a)
      if (!(b.box_hi[a] >= b.box_lo[a])) o.fail("spawn_box", "upper corner below lower corner");
  }
  if (const json* q = o.find("orientation")) {
    if (q->is_string() && q->get<std::string>() == "random") {
      b.random_orientation = true;
    } else if (q->is_array() && q->size() == 4) {
      double c[4];
      for (int i = 0; i < 4; ++i)
        c[i] = o.as_number((*q)[i], "orientation[" + std::to_string(i) + "]");
      // scaled by its largest component first: the squares of [1e300, 1e300, 0, 0] overflow
      const double cmax = std::max({std::abs(c[0]), std::abs(c[1]), std::abs(c[2]), std::abs(c[3])});
      if (!(cmax > 0)) o.fail("orientation", "quaternion must not be zero");
      const Quat qq(c[0] / cmax, c[1] / cmax, c[2] / cmax, c[3] / cmax);
      b.orientation = qq.normalized();
    } else {
      o.fail("orientation", "must be [w,x,y,z] or \"random\", got " + Obj::dump(*q));
    }
  }
  if (o.has("velocity")) b.velocity = o.bounded_vec3("velocity", kMaxSpeed, kSpeedRange);
  if (o.has("angular_velocity"))
    b.angular_velocity = o.bounded_vec3("angular_velocity", kMaxSpin, kSpinRange);
  if (o.has("variation")) {
    // art direction: per-body draws from [lo, hi] (docs/effects.md)
    Obj v = o.object("variation", {"size", "density", "spin", "variants"});
    auto range = [&v](const std::string& key, double lo_min, double* lo, double* hi) {
      const json& r = v.get(key);
      if (!r.is_array() || r.size() != 2)
        v.fail(key, "must be [lo, hi], got " + Obj::dump(r));
      *lo = v.as_number(r[0], key + "[0]");
      *hi = v.as_number(r[1], key + "[1]");
      if (!(*lo >= lo_min) || (lo_min > 0 && !(*lo > 0)))
        v.fail(key, "lower bound must be " + std::string(lo_min > 0 ? "> 0" : ">= 0") +
                        ", got " + Obj::dump(r));
      if (!(*hi >= *lo)) v.fail(key, "upper bound below lower bound, got " + Obj::dump(r));
    };
    if (v.has("size")) {
      range("size", 1e-300, &b.size_min, &b.size_max);
      // the varied shapes keep to the shapes' lengths: a box is given by its edges, a mesh by
      // its extent, a sphere and an ellipsoid by their semi-axes
      const Vec3 l = b.shape.type == ShapeType::Sphere || b.shape.type == ShapeType::Ellipsoid
                         ? b.shape.half_extents
                         : Vec3(2 * b.shape.half_extents);
      if (!(b.size_min * l.minCoeff() >= kMinShapeLength &&
            b.size_max * l.maxCoeff() <= kMaxShapeLength)) {
        std::ostringstream m;
        m << "makes the shape's lengths " << b.size_min * l.minCoeff() << " to "
          << b.size_max * l.maxCoeff() << " m; they must stay " << kLengthRange << ", got "
          << Obj::dump(v.get("size"));
        v.fail("size", m.str());
      }
    }
    if (v.has("density")) {
      range("density", 1e-300, &b.density_min, &b.density_max);
      if (!(b.density_min * b.density >= kMinDensity && b.density_max * b.density <= kMaxDensity)) {
        std::ostringstream m;
        m << "makes the density " << b.density_min * b.density << " to "
          << b.density_max * b.density << " kg/m^3; it must stay in " << kDensityRange
          << ", got " << Obj::dump(v.get("density"));
        v.fail("density", m.str());
      }
    }
    if (v.has("spin")) {
      range("spin", 0, &b.spin_min, &b.spin_max);
      if (!(b.spin_max <= kMaxSpin))
        v.fail("spin", "upper bound must be at most 1e6 rad/s, got " + Obj::dump(v.get("spin")));
    }
    if (const json* n = v.find("variants")) {
      if (!n->is_number_integer() || n->get<long long>() < 1 || n->get<long long>() > 256)
        v.fail("variants", "must be an integer in [1, 256], got " + Obj::dump(*n));
      b.variants = n->get<int>();
    } else if (v.has("size") || v.has("density")) {
      b.variants = 16;
    }
    v.finish();
  }
  if (o.has("contact"))
    read_contact(o.object("contact", kContactKeys), &b.contact, &b.restitution_given,
                 &b.friction_given, &b.rolling_given);
  if (o.has("release")) read_release(o.object("release", {"rate", "start", "times"}), &b);
  o.finish();
  return b;
}

}  // namespace

namespace {

// The deepest nesting of objects and arrays a scene may have; a scene needs about 5.
constexpr int kMaxJsonDepth = 64;

// Parses scene text refusing what nlohmann would accept without a word: nesting deeper than
// kMaxJsonDepth (a deep document would exhaust the stack when dumped for a message) and a key
// repeated in one object (where the last one would silently win).
json parse_strict(const std::string& text, const std::string& path) {
  std::vector<std::vector<std::string>> keys;  // keys seen so far in each open object
  std::string where;                           // the key path of the innermost open object
  std::vector<size_t> where_len;
  std::string last_key;
  auto cb = [&](int depth, json::parse_event_t event, json& parsed) {
    using E = json::parse_event_t;
    if ((event == E::object_start || event == E::array_start) && depth >= kMaxJsonDepth)
      fail_input(path, where, "JSON nested deeper than " + std::to_string(kMaxJsonDepth) +
                                  " levels (accepted: 1 to " + std::to_string(kMaxJsonDepth) + ")");
    if (event == E::object_start || event == E::array_start) {
      if (event == E::object_start) keys.emplace_back();
      where_len.push_back(where.size());
      if (!last_key.empty()) where += (where.empty() ? "" : ".") + last_key;
      last_key.clear();
    } else if ((event == E::object_end || event == E::array_end) && !where_len.empty()) {
      if (event == E::object_end && !keys.empty()) keys.pop_back();
      where.resize(where_len.back());
      where_len.pop_back();
      last_key.clear();
    } else if (event == E::key && !keys.empty()) {
      const std::string k = parsed.get<std::string>();
      auto& seen = keys.back();
      for (const auto& s : seen)
        if (s == k)
          fail_input(path, where.empty() ? k : where + "." + k,
                     "duplicated key: \"" + k + "\" appears twice in one object");
      seen.push_back(k);
      last_key = k;
    }
    return true;
  };
  return json::parse(text, cb);
}

Scene parse_scene_unchecked(const std::string& text, const std::string& path) {
  json j;
  try {
    j = parse_strict(text, path);
  } catch (const json::parse_error& e) {
    // nlohmann reports a byte offset: turn it into line and column
    size_t line = 1, col = 1;
    for (size_t i = 0; i + 1 < e.byte && i < text.size(); ++i) {
      if (text[i] == '\n') {
        ++line;
        col = 1;
      } else {
        ++col;
      }
    }
    std::string what = e.what();
    const auto pos = what.find("parse error");
    if (pos != std::string::npos) what = what.substr(pos);
    fail_input(path, "", "malformed JSON at line " + std::to_string(line) + ", column " +
                             std::to_string(col) + ": " + what);
  }
  Scene s;
  s.file = path;
  Obj top(j, "", path, {"version", "fluid", "gravity", "effects", "integrator", "duration", "seed", "bodies", "ground", "turbulence", "art", "output", "contact", "walls", "outside", "body_contact"});
  if (const json* v = top.find("version")) {
    if (!v->is_number_integer() || v->get<int>() != 1)
      top.fail("version", "only schema version 1 is supported, got " + Obj::dump(*v));
  }
  {
    Obj f = top.object("fluid", {"density", "kinematic_viscosity", "field", "uniform", "time"});
    s.fluid_density = f.bounded("density", kMinDensity, kMaxDensity, kDensityRange);
    s.kinematic_viscosity = f.bounded("kinematic_viscosity", 1e-9, 1e3, "[1e-9, 1e3] m^2/s");
    const bool field = f.has("field"), uniform = f.has("uniform");
    if (field == uniform) f.fail("", "needs exactly one of \"field\" or \"uniform\"");
    if (field) {
      s.uniform_field = false;
      const std::string name = f.string("field");
      s.field_path = resolve(name, path);
      std::error_code ec;
      if (!fs::exists(s.field_path, ec))
        f.fail("field", "file not found: " + s.field_path + resolved_against(name, path));
      if (f.has("time")) {
        const std::string m = f.string("time");
        if (m == "loop") s.time_mode = TimeMode::Loop;
        else if (m == "clamp") s.time_mode = TimeMode::Clamp;
        else f.fail("time", "must be \"loop\" or \"clamp\", got \"" + m + "\"");
      }
    } else {
      Obj u = f.object("uniform", {"U", "k", "epsilon"});
      s.uniform_U = u.bounded_vec3("U", kMaxSpeed, kSpeedRange);
      s.uniform_k = u.bounded("k", 0, 1e8, "[0, 1e8] m^2/s^2");
      s.uniform_epsilon = u.bounded("epsilon", 0, 1e12, "[0, 1e12] m^2/s^3");
      if ((s.uniform_k > 0) != (s.uniform_epsilon > 0))
        u.fail("", "k and epsilon must both be > 0 or both be 0");
      u.finish();
    }
    f.finish();
  }
  s.gravity = top.bounded_vec3("gravity", 1e4, "[-1e4, 1e4] m/s^2");
  {
    const json& e = top.get("effects");
    if (e.is_string() && e.get<std::string>() == "auto") {
      s.effects_auto = true;
    } else if (e.is_array()) {
      for (size_t i = 0; i < e.size(); ++i) {
        Effect eff;
        if (!e[i].is_string() || !effect_from_name(e[i].get<std::string>(), &eff)) {
          std::string names;
          for (const auto& info : all_effects())
            names += std::string(names.empty() ? "" : ", ") + info.name;
          top.fail("effects[" + std::to_string(i) + "]",
                   "unknown effect " + Obj::dump(e[i]) + " (known: " + names + ")");
        }
        s.effects.add(eff);
      }
    } else {
      top.fail("effects", "must be a list of effect names or \"auto\", got " + Obj::dump(e));
    }
  }
  {
    Obj in = top.object("integrator", {"scheme", "dt", "batched", "precision"});
    const std::string scheme = in.string("scheme");
    if (!integrator_from_name(scheme, &s.integrator))
      in.fail("scheme", std::string("must be ") + kIntegratorNames + ", got \"" + scheme + "\"");
    s.dt = in.positive("dt");
    if (in.has("batched")) s.batched = in.boolean("batched");
    if (in.has("precision")) {
      const std::string p = in.string("precision");
      if (p == "double") s.precision = Precision::Double;
      else if (p == "float") s.precision = Precision::Float;
      else in.fail("precision", "must be double or float, got \"" + p + "\"");
    }
    in.finish();
  }
  s.duration = top.positive("duration");
  if (s.duration / s.dt > 4e9) top.fail("duration", "more than 4e9 steps of integrator.dt");
  if (s.dt > s.duration)
    top.fail("integrator.dt", "must be at most duration (" + Obj::dump(top.get("duration")) +
                                  " s): the run would take no step, got " +
                                  Obj::dump(top.get("integrator").at("dt")));
  {
    const json& seed = top.get("seed");
    if (!seed.is_number_unsigned())
      top.fail("seed", "must be an integer in [0, 2^64 - 1], got " + Obj::dump(seed));
    s.seed = seed.get<uint64_t>();
  }
  {
    const json& bodies = top.get("bodies");
    if (!bodies.is_array() || bodies.empty())
      top.fail("bodies", "must be a non-empty list of body types");
    size_t total = 0;
    for (size_t i = 0; i < bodies.size(); ++i) {
      s.bodies.push_back(read_body(Obj(bodies[i], "bodies[" + std::to_string(i) + "]", path, kBodyKeys)));
      total += size_t(s.bodies.back().count);
    }
    if (total > 100000000) top.fail("bodies", "more than 1e8 bodies in total");
    if (s.bodies.size() > 65535) top.fail("bodies", "more than 65535 body types");
    // the variants each entry becomes (as compile_model makes them), counted before any of
    // them is built: each box or mesh variant takes a boundary-element solve
    size_t variants = 0;
    for (const BodySpec& b : s.bodies)
      variants += b.variants > 1 && (b.size_max != b.size_min || b.density_max != b.density_min)
                      ? size_t(std::min(b.variants, b.count))
                      : 1;
    if (variants > 65535)
      top.fail("bodies", "more than 65535 body types with their variation.variants, got " +
                             std::to_string(variants));
  }
  if (top.has("ground")) {
    Obj g = top.object("ground", {"z", "contact"});
    s.has_ground = true;
    s.ground_z = g.bounded("z", -kMaxCoordinate, kMaxCoordinate, kCoordinateRange);
    if (g.has("contact")) s.ground_contact = read_contact_mode(g);
    g.finish();
  }
  if (top.has("turbulence")) {
    Obj t = top.object("turbulence", {"model", "drift", "crossing_trajectories"});
    if (t.has("model")) {
      const std::string m = t.string("model");
      if (m == "body") s.turbulence_model = TurbulenceModel::Body;
      else if (m == "seen") s.turbulence_model = TurbulenceModel::Seen;
      else t.fail("model", "must be \"body\" or \"seen\", got \"" + m + "\"");
    }
    if (t.has("drift")) {
      const std::string d = t.string("drift");
      if (d == "original") s.drift = Drift::Original;
      else if (d == "stationary") s.drift = Drift::Stationary;
      else t.fail("drift", "must be \"original\" or \"stationary\", got \"" + d + "\"");
    }
    if (t.has("crossing_trajectories"))
      s.crossing_trajectories = t.boolean("crossing_trajectories");
    t.finish();
  }
  if (top.has("art")) {
    // art direction: scales of what the bodies see of the field (docs/effects.md)
    Obj a = top.object("art", {"mean_flow_scale", "turbulence_scale"});
    for (const char* key : {"mean_flow_scale", "turbulence_scale"}) {
      if (!a.has(key)) continue;
      const double v = a.number(key);
      // beyond 1000 the speeds' squares leave the range of a double and forces become NaN
      if (!(v >= 0 && v <= 1000))
        a.fail(key, "must be in [0, 1000], got " + Obj::dump(a.get(key)));
      (std::string(key) == "mean_flow_scale" ? s.mean_flow_scale : s.turbulence_scale) = v;
    }
    a.finish();
  }
  if (top.has("output")) {
    Obj o = top.object("output", {"dir", "every", "formats", "checkpoint_every"});
    if (o.has("dir")) {
      s.output.dir = o.string("dir");  // relative to the working directory
      if (s.output.dir.empty()) o.fail("dir", "must not be empty (leave it out for \"results\")");
    }
    s.output.every = o.positive_or("every", s.output.every);
    // the output stride is every / dt steps, an integer: beyond 4e9 steps it overflows
    if (o.has("every") && s.output.every / s.dt > 4e9)
      o.fail("every", "must be at most 4e9 steps of integrator.dt (" + std::to_string(4e9 * s.dt) +
                          " s), got " + Obj::dump(o.get("every")));
    if (o.has("checkpoint_every")) {
      s.output.checkpoint_every = o.number("checkpoint_every");
      if (!(s.output.checkpoint_every >= 0))
        o.fail("checkpoint_every", "must be >= 0 (0: no checkpoints), got " +
                                       Obj::dump(o.get("checkpoint_every")));
    }
    if (const json* f = o.find("formats")) {
      std::string names = "\"csv\", \"pvd\"";
      for (const DccFormat& d : kDccFormats) names += std::string(", \"") + d.format + "\"";
      if (!f->is_array()) o.fail("formats", "must be a list of " + names);
      s.output.csv = s.output.pvd = false;
      for (const DccFormat& d : kDccFormats) s.output.*d.enabled = false;
      for (size_t i = 0; i < f->size(); ++i) {
        const std::string k = (*f)[i].is_string() ? (*f)[i].get<std::string>() : "";
        const DccFormat* d = std::find_if(std::begin(kDccFormats), std::end(kDccFormats),
                                          [&](const DccFormat& x) { return k == x.format; });
        if (k == "csv") s.output.csv = true;
        else if (k == "pvd") s.output.pvd = true;
        else if (d != std::end(kDccFormats)) s.output.*d->enabled = true;
        else o.fail("formats[" + std::to_string(i) + "]",
                    "must be one of " + names + ", got " + Obj::dump((*f)[i]));
      }
    }
    o.finish();
  }
  read_scene_contacts(top, &s);
  top.finish();
  return s;
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& path) {
  try {
    return parse_scene_unchecked(text, path);
  } catch (const json::exception& e) {
    // e.g. a number too large for a double (out_of_range): still a bad input, never a crash
    fail_input(path, "", std::string("invalid JSON: ") + e.what());
  }
}

Shape parse_shape(const std::string& text, const std::string& path, int* panels) {
  try {
    const json j = parse_strict(text, path);
    BodySpec b;
    Shape s = read_shape(Obj(j, "shape", path, kShapeKeys), &b);
    *panels = b.panels;
    return s;
  } catch (const json::exception& e) {
    fail_input(path, "shape", std::string("invalid JSON: ") + e.what());
  }
}

Scene read_scene(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) fail_input(path, "", "is a directory, not a scene file");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail_input(path, "", fs::exists(path, ec) ? "cannot be read" : "file not found");
  std::stringstream ss;
  ss << in.rdbuf();
  if (ss.str().find_first_not_of(" \t\r\n") == std::string::npos)
    fail_input(path, "", "is empty, not a scene file");
  return parse_scene(ss.str(), path);
}

}  // namespace lrigid
