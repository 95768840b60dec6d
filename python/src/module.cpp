// The compiled part of the Python package lrigid (docs/python.md): scenes, runs with their
// state as NumPy arrays, added-mass tensors, `explain` and grid sampling, on the same library
// calls `lrigid run`, `added-mass` and `explain` make, so results are the command's own.
// lrigid/__init__.py wraps this module (dict-based entry points, docstrings of the package).
#include <chrono>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "body/mass_properties.h"
#include "compile/compile_model.h"
#include "integrate/simulation.h"
#include "io/added_mass_cache.h"
#include "io/explain.h"
#include "io/field_loader.h"
#include "io/grid_reader.h"
#include "io/result_writer.h"
#include "io/results_dir.h"
#include "io/run_recorder.h"
#include "io/sanity.h"
#include "io/scene_json.h"
#include "model/state.h"
#include "util/error.h"

namespace py = pybind11;
using namespace lrigid;

namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// nlohmann::json -> Python objects (NaN and infinities kept, unlike a JSON text round trip)
py::object to_python(const nlohmann::json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::null: return py::none();
    case nlohmann::json::value_t::boolean: return py::bool_(j.get<bool>());
    case nlohmann::json::value_t::number_integer: return py::int_(j.get<int64_t>());
    case nlohmann::json::value_t::number_unsigned: return py::int_(j.get<uint64_t>());
    case nlohmann::json::value_t::number_float: return py::float_(j.get<double>());
    case nlohmann::json::value_t::string: return py::str(j.get<std::string>());
    case nlohmann::json::value_t::array: {
      py::list l;
      for (const auto& v : j) l.append(to_python(v));
      return std::move(l);
    }
    default: {
      py::dict d;
      for (auto it = j.begin(); it != j.end(); ++it) d[py::str(it.key())] = to_python(it.value());
      return std::move(d);
    }
  }
}

[[noreturn]] void bad_value(const std::string& what) { throw Error(ExitCode::Usage, what); }

// an (n, cols) array of doubles, or an error naming `what`
Array rows(const py::handle& a, size_t n, py::ssize_t cols, const char* what) {
  Array r = Array::ensure(a);
  if (!r || r.ndim() != 2 || size_t(r.shape(0)) != n || r.shape(1) != cols)
    bad_value(std::string(what) + ": expected an array of shape (" + std::to_string(n) + ", " +
              std::to_string(cols) + ")");
  for (py::ssize_t i = 0; i < r.size(); ++i)
    if (!std::isfinite(r.data()[i])) bad_value(std::string(what) + ": values must be finite");
  return r;
}

Vec3 vec3(const py::handle& a, const char* what) {
  Array r = Array::ensure(a);
  if (!r || r.size() != 3) bad_value(std::string(what) + ": expected 3 numbers");
  const Vec3 v(r.data()[0], r.data()[1], r.data()[2]);
  if (!v.allFinite()) bad_value(std::string(what) + ": values must be finite");
  return v;
}

py::array_t<double> matrix(const Eigen::MatrixXd& m) {
  py::array_t<double> a({m.rows(), m.cols()});
  auto v = a.mutable_unchecked<2>();
  for (Eigen::Index r = 0; r < m.rows(); ++r)
    for (Eigen::Index c = 0; c < m.cols(); ++c) v(r, c) = m(r, c);
  return a;
}

struct PyScene {
  Scene scene;
};

// A read-only NumPy view of `rows` x `cols` values of type T at `data`, kept alive by `owner`
// (the Python Simulation): no copy; valid as long as the vector holding them is not resized
template <class T>
py::array readonly_view(const void* data, size_t rows, py::ssize_t cols, py::handle owner) {
  const auto item = py::ssize_t(sizeof(T));
  std::vector<py::ssize_t> shape{py::ssize_t(rows)}, strides{item * cols};
  if (cols > 1) {
    shape.push_back(cols);
    strides.push_back(item);
  }
  py::array a(py::dtype::of<T>(), shape, strides, data, owner);
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

// A run in progress: the compiled Model, the State, stepped with simulate() exactly as
// `lrigid run` steps them (same seed: same bits). With an output folder it records as
// `lrigid run -o DIR` does (io/run_recorder.h): frames at the scene's output times, committed
// when the run reaches the scene's duration.
class Simulation {
 public:
  Simulation(const PyScene& s, py::object seed, py::object threads, py::object output_dir)
      : scene_(s.scene) {
    if (!seed.is_none()) {
      const long long v = seed.cast<long long>();
      if (v < 0) bad_value("seed must be >= 0, got " + std::to_string(v));
      scene_.seed = static_cast<uint64_t>(v);
    }
    if (!threads.is_none()) {
      threads_ = threads.cast<int>();
      if (threads_ < 1 || threads_ > 1024)
        bad_value("threads must be in [1, 1024], got " + std::to_string(threads_));
    }
    if (!output_dir.is_none()) {
      scene_.output.dir = output_dir.cast<std::string>();
      if (scene_.output.dir.empty()) bad_value("output_dir: an empty name; give a directory");
    }
    py::gil_scoped_release release;
    const auto load0 = std::chrono::steady_clock::now();
    FluidField field = load_field(scene_, StreamMode::Auto, false);
    const double load_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - load0).count();
    model_ = std::make_unique<Model>(compile_model(scene_, std::move(field), cached_added_mass));
    state_ = initial_state(*model_, scene_);
    viewed_ = viewed();
    if (!output_dir.is_none()) {
      // as `lrigid run -o DIR`: a finish interrupted there is completed first, the names the
      // run writes must be free or lrigid's own, and the summary has the same facts
      complete_interrupted_finish(scene_.output.dir);
      recorder_ = std::make_unique<RunRecorder>(
          scene_, *model_, RunFacts{threads_, check_scene(scene_, *model_), load_seconds, 1});
      output_dir_ = scene_.output.dir;
    }
  }

  // advances n steps of dt
  void step(long long n) {
    if (n < 0) bad_value("step: n must be >= 0, got " + std::to_string(n));
    advance_to(state_.step + static_cast<uint64_t>(n));
  }
  // advances to the step nearest `until` (s; default: the scene's duration)
  void run(py::object until) {
    const double t = until.is_none() ? scene_.duration : until.cast<double>();
    if (!std::isfinite(t)) bad_value("run: until must be finite");
    const double steps = std::llround(t / model_->dt);
    advance_to(steps > double(state_.step) ? static_cast<uint64_t>(steps) : state_.step);
  }
  // an unfinished recording abandoned: its temporaries removed, the folder as it was
  void close() { recorder_.reset(); }
  bool recording() const { return recorder_ != nullptr; }
  const std::string& output_dir() const { return output_dir_; }

  size_t size() const { return state_.size(); }
  const Model& model() const { return *model_; }
  const Scene& scene() const { return scene_; }
  State& state() { return state_; }
  const RunStats& stats() const { return stats_; }

  py::array_t<double> orientations() const {
    return per_body(4, [&](size_t i, double* r) {
      const Quat& q = state_.q[i];
      r[0] = q.w(), r[1] = q.x(), r[2] = q.y(), r[3] = q.z();
    });
  }
  py::array_t<double> velocities() const {
    return per_body(3, [&](size_t i, double* r) {
      const Vec3 v = body_velocity(*model_, state_, i, state_.q[i].toRotationMatrix());
      std::copy_n(v.data(), 3, r);
    });
  }
  py::array_t<double> angular_velocities() const {
    return per_body(3, [&](size_t i, double* r) {
      const Vec3 w = state_.q[i].toRotationMatrix() * state_.w[i];  // as the writer does
      std::copy_n(w.data(), 3, r);
    });
  }
  // views (no copy): Vec3 is 3 doubles without padding, BodyStatus one byte
  static_assert(sizeof(Vec3) == 3 * sizeof(double) && sizeof(BodyStatus) == 1);
  py::array positions_view(py::handle self) const {
    return readonly_view<double>(state_.x.data(), size(), 3, self);
  }
  py::array status_view(py::handle self) const {
    return readonly_view<uint8_t>(state_.status.data(), size(), 1, self);
  }
  py::array types_view(py::handle self) const {
    return readonly_view<uint16_t>(state_.type.data(), size(), 1, self);
  }
  std::array<const void*, 3> viewed() const {
    return {state_.x.data(), state_.status.data(), state_.type.data()};
  }
  py::array_t<uint8_t> state_codes() const {
    py::array_t<uint8_t> a{py::ssize_t(size())};
    for (size_t i = 0; i < size(); ++i) a.mutable_data()[i] = state_.state_code(i);
    return a;
  }

  void set_positions(const py::handle& a) {
    const Array r = rows(a, size(), 3, "positions");
    for (size_t i = 0; i < size(); ++i) state_.x[i] = Vec3(r.at(i, 0), r.at(i, 1), r.at(i, 2));
  }
  void set_orientations(const py::handle& a) {
    const Array r = rows(a, size(), 4, "orientations");
    for (size_t i = 0; i < size(); ++i) {
      Quat q(r.at(i, 0), r.at(i, 1), r.at(i, 2), r.at(i, 3));
      if (!(q.norm() > 0)) bad_value("orientations: row " + std::to_string(i) + " is zero");
      state_.q[i] = q.normalized();
    }
  }
  // world-frame velocities, stored in the body frame (less u' with the "body" turbulence model,
  // which adds it back when reporting)
  void set_velocities(const py::handle& a) {
    const Array r = rows(a, size(), 3, "velocities");
    for (size_t i = 0; i < size(); ++i) {
      const Vec3 world(r.at(i, 0), r.at(i, 1), r.at(i, 2));
      const Vec3 reported = body_velocity(*model_, state_, i, state_.q[i].toRotationMatrix());
      const Vec3 extra = reported - state_.q[i] * state_.v[i];  // u' or zero
      state_.v[i] = state_.q[i].conjugate() * (world - extra);
    }
  }
  void set_angular_velocities(const py::handle& a) {
    const Array r = rows(a, size(), 3, "angular_velocities");
    for (size_t i = 0; i < size(); ++i)
      state_.w[i] = state_.q[i].conjugate() * Vec3(r.at(i, 0), r.at(i, 1), r.at(i, 2));
  }

  // An impulse J (N s, world frame) at world point `at` (default: the centre of mass) plus an
  // angular impulse L (N m s, world frame): the generalized momentum M (v, w) gains (J, L + r x J)
  // in the body frame, M the body type's mass matrix with its added mass.
  void push(size_t i, const py::handle& impulse, const py::handle& angular, const py::handle& at) {
    if (i >= size())
      bad_value("push: body " + std::to_string(i) + " out of range (" + std::to_string(size()) +
                " bodies)");
    const Vec3 J = vec3(impulse, "push: impulse");
    Vec3 L = angular.is_none() ? Vec3::Zero() : vec3(angular, "push: angular_impulse");
    if (!at.is_none()) L += (vec3(at, "push: at") - state_.x[i]).cross(J);
    const BodyType& type = model_->types[state_.type[i]];
    const Quat& q = state_.q[i];
    Vec6 nu;
    nu << state_.v[i], state_.w[i];
    Vec6 dp;
    dp << q.conjugate() * J, q.conjugate() * L;
    const Vec6 after = type.M_inv_times(type.M_times(nu) + dp);
    state_.v[i] = after.head<3>();
    state_.w[i] = after.tail<3>();
    // a landed or sleeping body pushed moves again
    if (state_.status[i] == BodyStatus::Landed || state_.status[i] == BodyStatus::Sleeping) {
      state_.status[i] = BodyStatus::Moving;
      state_.t_stop[i] = 0;
      if (i < state_.rest_steps.size()) state_.rest_steps[i] = 0;
    }
  }

 private:
  template <class F>
  py::array_t<double> per_body(py::ssize_t cols, F&& f) const {
    py::array_t<double> a({py::ssize_t(size()), cols});
    double* d = a.mutable_data();
    for (size_t i = 0; i < size(); ++i) f(i, d + i * size_t(cols));
    return a;
  }

  // Runs to step `last` in chunks of about 50 ms without the GIL; between chunks, at a step
  // boundary, it takes the GIL back and checks for signals, so Ctrl-C stops a long run() or
  // step(n) within a fraction of a second with KeyboardInterrupt and the state at the steps done.
  // A recording stops each chunk at the scene's duration, where it commits its results.
  void advance_to(uint64_t last) {
    uint64_t chunk = 1;
    while (last > state_.step) {
      uint64_t to = state_.step + std::min<uint64_t>(chunk, last - state_.step);
      if (recorder_ && state_.step < recorder_->last_step())
        to = std::min(to, recorder_->last_step());
      const auto t0 = std::chrono::steady_clock::now();
      advance_chunk(to);
      commit_at_duration();
      const double dt_wall =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      // aim at 50 ms a chunk: doubling while faster, halving while slower
      if (dt_wall < 0.025 && chunk < (uint64_t(1) << 40)) chunk *= 2;
      else if (dt_wall > 0.1 && chunk > 1) chunk /= 2;
    }
    commit_at_duration();  // a run of no steps
  }

  // a recording that reached the scene's duration: its last frame, then every result committed
  void commit_at_duration() {
    if (!recorder_ || state_.step != recorder_->last_step()) return;
    py::gil_scoped_release release;
    record([&] {
      recorder_->frame(state_);  // written already, unless the run has no steps
      recorder_->finish(state_, stats_);
    });
    recorder_.reset();
  }

  // a recording that fails is abandoned (no result, the folder as it was) before the error
  template <class F>
  void record(F&& f) {
    try {
      f();
    } catch (...) {
      recorder_.reset();
      throw;
    }
  }

  void advance_chunk(uint64_t last) {
    if (last <= state_.step) return;
    // simulate() runs to model.duration in stretches ending at outputs: one stretch to `last`
    model_->duration = static_cast<double>(last) * model_->dt;
    RunOptions opt;
    opt.every = static_cast<double>(last + 1) * model_->dt;  // no output on the way
    opt.threads = threads_;
    opt.output_at_start = false;
    if (recorder_) {
      // frames at the scene's output times (the recorder skips the chunks' other ends); the one
      // at t = 0 when the first step is taken, so that it shows what was set before
      opt.every = scene_.output.every;
      opt.on_output = [this](const State& st) { recorder_->frame(st); };
    }
    RunStats s;
    {
      py::gil_scoped_release release;
      if (recorder_) record([&] { recorder_->frame(state_); });
      record([&] { s = simulate(*model_, &state_, opt); });
      model_->duration = scene_.duration;  // as the recorder's summary reports it
    }
    if (viewed() != viewed_)
      throw Error(ExitCode::Runtime, "the state's arrays moved: views taken before are invalid");
    stats_.body_steps += s.body_steps;
    stats_.scalar_handoffs += s.scalar_handoffs;
    stats_.newton_steps += s.newton_steps;
    stats_.steps = s.steps;
    stats_.wall_seconds += s.wall_seconds;
    stats_.landed = s.landed, stats_.exited = s.exited, stats_.failed = s.failed;
    stats_.resting = s.resting;
  }

  Scene scene_;
  int threads_ = 0;
  std::unique_ptr<Model> model_;
  State state_;
  std::array<const void*, 3> viewed_{};  // where the views point: these arrays never move
  RunStats stats_;
  std::string output_dir_;
  std::unique_ptr<RunRecorder> recorder_;  // while recording: after the model it refers to
};

// A grid file read whole; samples the raw U, k, epsilon (trilinear, as foam2grid wrote them).
class Grid {
 public:
  explicit Grid(const std::string& path) : path_(path) {
    py::gil_scoped_release release;
    g_ = read_grid(path);
  }
  // (n, 3) points -> dict of U (n, 3), k (n), epsilon (n), valid (n, bool); NaN where invalid;
  // wall_distance (n): the plain trilinear blend of the grid's wall_distance (m, negative in
  // solids, as the runtime's FluidSample::wall_distance), +inf off the box or without the array
  py::dict sample(const py::handle& pts, double t) const {
    Array p = Array::ensure(pts);
    if (!p || p.ndim() != 2 || p.shape(1) != 3)
      bad_value("Grid.sample: points must be an array of shape (n, 3)");
    const size_t n = size_t(p.shape(0));
    py::array_t<double> U({py::ssize_t(n), py::ssize_t(3)}), k{py::ssize_t(n)},
        eps{py::ssize_t(n)};
    py::array_t<bool> valid{py::ssize_t(n)};
    py::array_t<double> wall{py::ssize_t(n)};
    {
      const double* x = p.data();
      double *u = U.mutable_data(), *kk = k.mutable_data(), *e = eps.mutable_data();
      double* wd = wall.mutable_data();
      bool* ok = valid.mutable_data();
      py::gil_scoped_release release;
      size_t f0, f1;
      double lam;
      bracket(t, &f0, &f1, &lam);
      for (size_t i = 0; i < n; ++i) {
        double a[5], b[5];
        ok[i] = point(g_.frames[f0], x + 3 * i, a) && point(g_.frames[f1], x + 3 * i, b);
        for (int c = 0; c < 5; ++c) a[c] = ok[i] ? (1 - lam) * a[c] + lam * b[c] : NAN;
        std::copy_n(a, 3, u + 3 * i);
        kk[i] = a[3];
        e[i] = a[4];
        wd[i] = wall_distance(g_.frames[f0], x + 3 * i);
      }
    }
    py::dict d;
    d["U"] = U, d["k"] = k, d["epsilon"] = eps, d["valid"] = valid;
    d["wall_distance"] = wall;
    return d;
  }
  const GridFile& file() const { return g_; }
  const std::string& path() const { return path_; }

 private:
  // frames around t (clamped to the first and last): f0, f1 and the weight of f1
  void bracket(double t, size_t* f0, size_t* f1, double* lam) const {
    const auto& fr = g_.frames;
    *f0 = *f1 = 0;
    *lam = 0;
    if (fr.size() < 2 || t <= fr.front().time) return;
    if (t >= fr.back().time) {
      *f0 = *f1 = fr.size() - 1;
      return;
    }
    size_t j = 1;
    while (fr[j].time < t) ++j;
    *f0 = j - 1, *f1 = j;
    *lam = (t - fr[j - 1].time) / (fr[j].time - fr[j - 1].time);
  }
  // U, k, eps at x blended trilinearly over the valid corners of its cell, with the runtime's
  // rule (fluid/field.cpp): x is in the fluid when those carry at least half the weight
  double wall_distance(const RawGridFrame& f, const double* x) const {
    const GridGeometry& geo = g_.geometry;
    if (f.wall_distance.empty()) return HUGE_VAL;
    size_t idx[3];
    double w[3];
    for (int a = 0; a < 3; ++a) {
      const double s = (x[a] - geo.origin[a]) / geo.spacing[a];
      if (!(s >= 0 && s <= geo.n[a] - 1)) return HUGE_VAL;
      const double fl = std::min(std::floor(s), double(geo.n[a] - 2));
      idx[a] = size_t(fl);
      w[a] = s - fl;
    }
    double d = 0;
    for (int c = 0; c < 8; ++c) {
      const size_t i = idx[0] + (c & 1), j = idx[1] + ((c >> 1) & 1), k = idx[2] + (c >> 2);
      const size_t p = i + size_t(geo.n[0]) * (j + size_t(geo.n[1]) * k);
      d += ((c & 1) ? w[0] : 1 - w[0]) * (((c >> 1) & 1) ? w[1] : 1 - w[1]) *
           ((c >> 2) ? w[2] : 1 - w[2]) * double(f.wall_distance[p]);
    }
    return d;
  }

  bool point(const RawGridFrame& f, const double* x, double out[5]) const {
    const GridGeometry& geo = g_.geometry;
    size_t idx[3];
    double w[3];
    for (int a = 0; a < 3; ++a) {
      const double s = (x[a] - geo.origin[a]) / geo.spacing[a];
      if (!(s >= 0 && s <= geo.n[a] - 1)) return false;
      const double fl = std::min(std::floor(s), double(geo.n[a] - 2));
      idx[a] = size_t(fl);
      w[a] = s - fl;
    }
    std::fill_n(out, 5, 0.0);
    double W = 0;
    for (int c = 0; c < 8; ++c) {
      const size_t i = idx[0] + (c & 1), j = idx[1] + ((c >> 1) & 1), k = idx[2] + (c >> 2);
      const size_t p = i + size_t(geo.n[0]) * (j + size_t(geo.n[1]) * k);
      if (!f.valid[p]) continue;
      const double wt = ((c & 1) ? w[0] : 1 - w[0]) * (((c >> 1) & 1) ? w[1] : 1 - w[1]) *
                        ((c >> 2) ? w[2] : 1 - w[2]);
      W += wt;
      for (int d = 0; d < 3; ++d) out[d] += wt * f.U[3 * p + d];
      out[3] += wt * f.k[p];
      out[4] += wt * f.epsilon[p];
    }
    if (!(W >= 0.5)) return false;
    for (int d = 0; d < 5; ++d) out[d] /= W;
    return true;
  }

  std::string path_;
  GridFile g_;
};

}  // namespace

PYBIND11_MODULE(_lrigid, m) {
  m.doc() = "Compiled part of the lrigid package; use `import lrigid` (docs/python.md).";
  // lrigid::Error (bad input, with the command's message) -> lrigid.Error, a ValueError
  py::register_exception<Error>(m, "Error", PyExc_ValueError);
  m.attr("__version__") = LRIGID_VERSION;
  // the names of Simulation.state_codes, in code order (model/state.h)
  m.attr("STATE_NAMES") =
      py::tuple(py::cast(std::vector<std::string>(kStateNames, kStateNames + kStateCount)));

  py::class_<PyScene>(m, "Scene")
      .def_static("load", [](const std::string& path) { return PyScene{read_scene(path)}; },
                  py::arg("path"))
      .def_static("from_json",
                  [](const std::string& text, const std::string& name) {
                    return PyScene{parse_scene(text, name)};
                  },
                  py::arg("text"), py::arg("name"))
      .def_property_readonly("file", [](const PyScene& s) { return s.scene.file; })
      .def_property_readonly("seed", [](const PyScene& s) { return s.scene.seed; })
      .def_property_readonly("dt", [](const PyScene& s) { return s.scene.dt; })
      .def_property_readonly("duration", [](const PyScene& s) { return s.scene.duration; })
      .def_property_readonly("integrator",
                             [](const PyScene& s) { return integrator_name(s.scene.integrator); })
      .def_property_readonly("body_count", [](const PyScene& s) {
        size_t n = 0;
        for (const auto& b : s.scene.bodies) n += size_t(b.count);
        return n;
      });

  py::class_<Simulation>(m, "Simulation")
      .def(py::init<const PyScene&, py::object, py::object, py::object>(), py::arg("scene"),
           py::arg("seed") = py::none(), py::arg("threads") = py::none(),
           py::arg("output_dir") = py::none())
      .def("step", &Simulation::step, py::arg("n") = 1, "Advances n steps of dt.")
      .def("run", &Simulation::run, py::arg("until") = py::none(),
           "Advances to the time `until` (s, nearest whole step; default: the scene's duration).")
      .def("push", &Simulation::push, py::arg("body"), py::arg("impulse"),
           py::arg("angular_impulse") = py::none(), py::arg("at") = py::none(),
           "Impulse (N s, world) at world point `at` (default: centre of mass) plus angular "
           "impulse (N m s): the generalized momentum with added mass gains them.")
      .def_property_readonly("t", [](Simulation& s) { return s.state().t; })
      .def_property_readonly("n_steps", [](Simulation& s) { return s.state().step; })
      .def_property_readonly("dt", [](const Simulation& s) { return s.model().dt; })
      .def_property_readonly("duration", [](const Simulation& s) { return s.scene().duration; })
      .def_property_readonly("seed", [](const Simulation& s) { return s.model().seed; })
      .def("__len__", &Simulation::size)
      .def_property(
          "positions",
          [](py::object self) { return self.cast<const Simulation&>().positions_view(self); },
          [](Simulation& s, const py::handle& a) { s.set_positions(a); })
      .def_property("orientations", &Simulation::orientations, &Simulation::set_orientations)
      .def_property("velocities", &Simulation::velocities, &Simulation::set_velocities)
      .def_property("angular_velocities", &Simulation::angular_velocities,
                    &Simulation::set_angular_velocities)
      .def_property_readonly(
          "status",
          [](py::object self) { return self.cast<const Simulation&>().status_view(self); })
      .def_property_readonly(
          "types", [](py::object self) { return self.cast<const Simulation&>().types_view(self); })
      .def_property_readonly("state_codes", &Simulation::state_codes)
      .def("close", &Simulation::close,
           "Abandons an unfinished recording: its temporaries removed, the folder as it was.")
      .def_property_readonly("recording", &Simulation::recording)
      .def_property_readonly("output_dir",
                             [](const Simulation& s) -> py::object {
                               if (s.output_dir().empty()) return py::none();
                               return py::str(s.output_dir());
                             })
      .def_property_readonly("type_names",
                             [](const Simulation& s) {
                               std::vector<std::string> r;
                               for (const auto& t : s.model().types) r.push_back(t.name);
                               return r;
                             })
      .def_property_readonly("stop_times", [](Simulation& s) { return s.state().t_stop; })
      .def_property_readonly("reasons", [](Simulation& s) { return s.state().reason; })
      .def_property_readonly("body_steps", [](const Simulation& s) { return s.stats().body_steps; })
      .def("type_info", [](const Simulation& s, size_t t) {
        if (t >= s.model().types.size()) bad_value("type_info: no body type " + std::to_string(t));
        const BodyType& b = s.model().types[t];
        py::dict d;
        d["name"] = b.name;
        d["shape"] = shape_type_name(b.shape.type);
        d["count"] = b.count;
        d["mass"] = b.mass;
        d["volume"] = b.volume;
        d["density"] = b.density;
        d["mass_matrix"] = matrix(b.M);
        d["added_mass"] = matrix(b.K_fluid);
        return d;
      });

  m.def("added_mass_json",
        [](const std::string& shape_text, double fluid_density, const std::string& name) {
          if (!(fluid_density >= 0) || !std::isfinite(fluid_density))
            bad_value("added_mass: fluid_density must be >= 0 kg/m^3, got " +
                      std::to_string(fluid_density));
          int panels = 0;
          const Shape shape = parse_shape(shape_text, name, &panels);
          py::gil_scoped_release release;
          const AddedMass am = cached_added_mass(shape, fluid_density, panels);
          const MassProperties mp = mass_properties(shape);
          py::gil_scoped_acquire acquire;
          py::dict d;
          d["added_mass"] = matrix(am.tensor);
          d["method"] = am.method;
          d["panels"] = am.panels;
          d["volume"] = mp.volume;
          d["centroid"] = std::vector<double>{mp.centroid.x(), mp.centroid.y(), mp.centroid.z()};
          d["inertia_per_unit_density"] = matrix(mp.inertia);
          return d;
        },
        py::arg("shape"), py::arg("fluid_density"), py::arg("name"));

  m.def("explain_scene", [](const PyScene& s) { return to_python(explain_scene(s.scene)); },
        py::arg("scene"));

  py::class_<Grid>(m, "Grid")
      .def(py::init<const std::string&>(), py::arg("path"))
      .def("sample", &Grid::sample, py::arg("points"), py::arg("t") = 0.0)
      .def_property_readonly("path", &Grid::path)
      .def_property_readonly("shape",
                             [](const Grid& g) {
                               const auto& n = g.file().geometry.n;
                               return py::make_tuple(n[0], n[1], n[2]);
                             })
      .def_property_readonly("origin",
                             [](const Grid& g) {
                               const Vec3& o = g.file().geometry.origin;
                               return py::make_tuple(o.x(), o.y(), o.z());
                             })
      .def_property_readonly("spacing",
                             [](const Grid& g) {
                               const Vec3& o = g.file().geometry.spacing;
                               return py::make_tuple(o.x(), o.y(), o.z());
                             })
      .def_property_readonly("times",
                             [](const Grid& g) {
                               std::vector<double> t;
                               for (const auto& f : g.file().frames) t.push_back(f.time);
                               return t;
                             })
      .def_property_readonly("kinematic_viscosity",
                             [](const Grid& g) { return g.file().kinematic_viscosity; });
}
