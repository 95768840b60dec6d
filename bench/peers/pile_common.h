// The box pile benchmark's shared parts (bench/peers/pile.md): the initial poses file, the
// flags every pile harness takes, the measures of the pile (deepest overlaps, kinetic energy,
// height) computed from the bodies' poses and velocities alone, the same code for every engine,
// and the JSON report. Header-only: each harness is one translation unit.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

namespace pile {

// one body's state: centre of mass (m), orientation body -> world (w, x, y, z), velocity (m/s)
// and angular velocity (rad/s), both in world axes
struct Body {
  std::array<double, 3> x{};
  std::array<double, 4> q{1, 0, 0, 0};
  std::array<double, 3> v{};
  std::array<double, 3> w{};
};

// the pile's parameters (run_pile.sh passes them from pile.json)
struct Params {
  std::string poses;                          // the initial poses file (pile_poses.py)
  std::array<double, 3> size{0.04, 0.03, 0.02};  // box edges, m
  double density = 1000;                      // kg/m^3
  double friction = 0.5;                      // Coulomb, box-box and box-ground
  double restitution = 0;
  double gravity = 9.81;                      // m/s^2, along -z
  double dt = 0.002;                          // s
  int steps = 1500;
  double sample_every = 0.1;                  // s between measures of the pile
  int n = 0;                                  // bodies to take from the poses file (0: all)

  double mass() const { return density * size[0] * size[1] * size[2]; }
  // principal moments of inertia of the box about its centre
  std::array<double, 3> inertia() const {
    const double m = mass(), a = size[0], b = size[1], c = size[2];
    return {m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12};
  }
};

[[noreturn]] inline void usage_error(const char* prog, const std::string& what) {
  std::fprintf(stderr, "%s: %s\n", prog, what.c_str());
  std::exit(2);
}

inline double parse_number(const char* prog, const char* flag, const char* s) {
  char* end = nullptr;
  const double v = std::strtod(s, &end);
  if (end == s || *end != '\0' || !std::isfinite(v))
    usage_error(prog, std::string(flag) + ": not a number: " + s);
  return v;
}

// Takes the common flags; returns the index of the first flag it does not know (the harness's
// own), leaving those to the caller. extra(i) handles argv[i] and returns how many it consumed
// (0: unknown).
template <typename Extra>
Params parse_flags(int argc, char** argv, Extra extra) {
  const char* prog = argv[0];
  Params p;
  for (int i = 1; i < argc;) {
    const std::string f = argv[i];
    auto need = [&](int k) {
      if (i + k >= argc) usage_error(prog, f + ": needs " + std::to_string(k) + " value(s)");
    };
    if (f == "--poses") { need(1); p.poses = argv[i + 1]; i += 2; }
    else if (f == "--size") {
      need(3);
      for (int k = 0; k < 3; ++k) p.size[size_t(k)] = parse_number(prog, "--size", argv[i + 1 + k]);
      i += 4;
    }
    else if (f == "--density") { need(1); p.density = parse_number(prog, "--density", argv[i + 1]); i += 2; }
    else if (f == "--friction") { need(1); p.friction = parse_number(prog, "--friction", argv[i + 1]); i += 2; }
    else if (f == "--restitution") { need(1); p.restitution = parse_number(prog, "--restitution", argv[i + 1]); i += 2; }
    else if (f == "--gravity") { need(1); p.gravity = parse_number(prog, "--gravity", argv[i + 1]); i += 2; }
    else if (f == "--dt") { need(1); p.dt = parse_number(prog, "--dt", argv[i + 1]); i += 2; }
    else if (f == "--steps") { need(1); p.steps = int(parse_number(prog, "--steps", argv[i + 1])); i += 2; }
    else if (f == "--sample-every") { need(1); p.sample_every = parse_number(prog, "--sample-every", argv[i + 1]); i += 2; }
    else if (f == "--n") { need(1); p.n = int(parse_number(prog, "--n", argv[i + 1])); i += 2; }
    else {
      const int used = extra(i);
      if (used <= 0) usage_error(prog, "unknown option " + f);
      i += used;
    }
  }
  if (p.poses.empty()) usage_error(prog, "--poses FILE is required (bench/peers/pile_poses.py writes it)");
  if (!(p.size[0] > 0 && p.size[1] > 0 && p.size[2] > 0)) usage_error(prog, "--size: edges must be > 0");
  if (!(p.density > 0)) usage_error(prog, "--density must be > 0");
  if (!(p.friction >= 0)) usage_error(prog, "--friction must be >= 0");
  if (!(p.restitution >= 0 && p.restitution <= 1)) usage_error(prog, "--restitution must lie in [0, 1]");
  if (!(p.dt > 0)) usage_error(prog, "--dt must be > 0");
  if (p.steps < 1) usage_error(prog, "--steps must be >= 1");
  if (!(p.sample_every > 0)) usage_error(prog, "--sample-every must be > 0");
  if (p.n < 0) usage_error(prog, "--n must be >= 0");
  return p;
}

// the poses file: a header line "body,x,y,z,qw,qx,qy,qz", then one body per line (m, unit
// quaternion body -> world); the bodies start at rest
inline std::vector<Body> read_poses(const std::string& path, int n) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::string line;
  if (!std::getline(in, line) || line.rfind("body,x,y,z,qw,qx,qy,qz", 0) != 0)
    throw std::runtime_error(path + ": the first line must be body,x,y,z,qw,qx,qy,qz");
  std::vector<Body> bodies;
  int lineno = 1;
  while (std::getline(in, line)) {
    ++lineno;
    if (line.empty()) continue;
    std::istringstream s(line);
    std::string cell;
    std::vector<double> v;
    while (std::getline(s, cell, ',')) v.push_back(std::strtod(cell.c_str(), nullptr));
    if (v.size() != 8)
      throw std::runtime_error(path + ":" + std::to_string(lineno) + ": expected 8 fields");
    Body b;
    b.x = {v[1], v[2], v[3]};
    const double qn = std::sqrt(v[4] * v[4] + v[5] * v[5] + v[6] * v[6] + v[7] * v[7]);
    if (!(qn > 0)) throw std::runtime_error(path + ":" + std::to_string(lineno) + ": zero quaternion");
    b.q = {v[4] / qn, v[5] / qn, v[6] / qn, v[7] / qn};
    bodies.push_back(b);
    if (n > 0 && int(bodies.size()) == n) break;
  }
  if (bodies.empty()) throw std::runtime_error(path + ": no bodies");
  if (n > 0 && int(bodies.size()) < n)
    throw std::runtime_error(path + ": holds " + std::to_string(bodies.size()) + " bodies, --n asks for " +
                             std::to_string(n));
  return bodies;
}

// rotation matrix (rows) of a unit quaternion (w, x, y, z)
inline std::array<std::array<double, 3>, 3> rotation(const std::array<double, 4>& q) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  return {{{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
           {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
           {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}}};
}

// what a sample of the pile records
struct Measure {
  double t = 0;
  double body_overlap = 0;    // deepest box-box penetration, m
  double ground_overlap = 0;  // deepest box-ground penetration (lowest corner below z = 0), m
  double kinetic_energy = 0;  // J, translation and rotation
  double height = 0;          // highest corner, m
  double max_speed = 0;       // fastest centre of mass, m/s
  int pairs_overlapping = 0;  // box pairs that overlap (any depth)
};

// the penetration depth of two boxes (half extents h, centres a and b, rotations A and B, the
// columns the boxes' axes): the smallest overlap of their projections over the 15 separating
// axes, which for two convex polyhedra is the depth of the shortest translation that separates
// them; <= 0 when they do not overlap
inline double box_box_depth(const std::array<double, 3>& h, const std::array<double, 3>& a,
                            const std::array<std::array<double, 3>, 3>& A,
                            const std::array<double, 3>& b,
                            const std::array<std::array<double, 3>, 3>& B) {
  const std::array<double, 3> d{b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  auto col = [](const std::array<std::array<double, 3>, 3>& R, int k) {
    return std::array<double, 3>{R[0][size_t(k)], R[1][size_t(k)], R[2][size_t(k)]};
  };
  auto dot = [](const std::array<double, 3>& u, const std::array<double, 3>& v) {
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
  };
  double depth = 1e300;
  auto axis = [&](std::array<double, 3> L) {
    const double len = std::sqrt(dot(L, L));
    if (len < 1e-9) return;  // parallel edges: covered by the face axes
    for (auto& c : L) c /= len;
    double ra = 0, rb = 0;
    for (int k = 0; k < 3; ++k) {
      ra += h[size_t(k)] * std::fabs(dot(col(A, k), L));
      rb += h[size_t(k)] * std::fabs(dot(col(B, k), L));
    }
    depth = std::min(depth, ra + rb - std::fabs(dot(d, L)));
  };
  for (int k = 0; k < 3; ++k) axis(col(A, k));
  for (int k = 0; k < 3; ++k) axis(col(B, k));
  for (int i = 0; i < 3 && depth > 0; ++i)
    for (int j = 0; j < 3; ++j) {
      const auto u = col(A, i), v = col(B, j);
      axis({u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]});
    }
  return depth;
}

inline Measure measure(const Params& p, const std::vector<Body>& bodies, double t) {
  Measure m;
  m.t = t;
  const std::array<double, 3> h{p.size[0] / 2, p.size[1] / 2, p.size[2] / 2};
  const double r = std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);  // bounding sphere
  const double mass = p.mass();
  const auto I = p.inertia();
  std::vector<std::array<std::array<double, 3>, 3>> R(bodies.size());
  m.height = -1e300;
  for (size_t i = 0; i < bodies.size(); ++i) {
    const Body& b = bodies[i];
    R[i] = rotation(b.q);
    double ext = 0;  // half height of the box along z
    for (int k = 0; k < 3; ++k) ext += h[size_t(k)] * std::fabs(R[i][2][size_t(k)]);
    m.ground_overlap = std::max(m.ground_overlap, ext - b.x[2]);
    m.height = std::max(m.height, b.x[2] + ext);
    const double v2 = b.v[0] * b.v[0] + b.v[1] * b.v[1] + b.v[2] * b.v[2];
    m.max_speed = std::max(m.max_speed, std::sqrt(v2));
    double rot = 0;  // w in body axes: R^T w
    for (int k = 0; k < 3; ++k) {
      const double wk = R[i][0][size_t(k)] * b.w[0] + R[i][1][size_t(k)] * b.w[1] + R[i][2][size_t(k)] * b.w[2];
      rot += I[size_t(k)] * wk * wk;
    }
    m.kinetic_energy += 0.5 * mass * v2 + 0.5 * rot;
  }
  // pairs: a uniform grid of cells one bounding diameter wide
  const double cell = 2 * r;
  auto key = [](long long i, long long j, long long k) {
    return ((i & 0x1fffff) << 42) | ((j & 0x1fffff) << 21) | (k & 0x1fffff);
  };
  std::unordered_map<long long, std::vector<int>> grid;
  grid.reserve(bodies.size() * 2);
  std::vector<std::array<long long, 3>> c(bodies.size());
  for (size_t i = 0; i < bodies.size(); ++i) {
    for (int k = 0; k < 3; ++k) c[i][size_t(k)] = (long long)std::floor(bodies[i].x[size_t(k)] / cell);
    grid[key(c[i][0], c[i][1], c[i][2])].push_back(int(i));
  }
  for (size_t i = 0; i < bodies.size(); ++i)
    for (long long di = -1; di <= 1; ++di)
      for (long long dj = -1; dj <= 1; ++dj)
        for (long long dk = -1; dk <= 1; ++dk) {
          auto it = grid.find(key(c[i][0] + di, c[i][1] + dj, c[i][2] + dk));
          if (it == grid.end()) continue;
          for (int j : it->second) {
            if (size_t(j) <= i) continue;
            const auto& a = bodies[i].x;
            const auto& b = bodies[size_t(j)].x;
            const double dx = b[0] - a[0], dy = b[1] - a[1], dz = b[2] - a[2];
            if (dx * dx + dy * dy + dz * dz >= 4 * r * r) continue;
            const double dep = box_box_depth(h, a, R[i], b, R[size_t(j)]);
            if (dep > 0) {
              ++m.pairs_overlapping;
              m.body_overlap = std::max(m.body_overlap, dep);
            }
          }
        }
  return m;
}

inline double cpu_seconds() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// A run: the engine steps (timed, CPU time of this process), the pile is measured every
// sample_every seconds outside the timing. get(bodies) fills the bodies' state from the engine.
struct Run {
  std::vector<Measure> samples;
  std::vector<double> window_rates;  // body-steps per CPU second over each sample interval
  double step_cpu = 0;               // s, stepping only
  long long body_steps = 0;
};

template <typename Step, typename Get>
Run run(const Params& p, size_t n, Step step, Get get) {
  Run out;
  std::vector<Body> state(n);
  const int every = std::max(1, int(std::lround(p.sample_every / p.dt)));
  get(state);
  out.samples.push_back(measure(p, state, 0));
  double window = 0;
  for (int s = 1; s <= p.steps; ++s) {
    const double t0 = cpu_seconds();
    step();
    const double t = cpu_seconds() - t0;
    out.step_cpu += t;
    window += t;
    out.body_steps += (long long)n;
    if (s % every == 0 || s == p.steps) {
      get(state);
      out.samples.push_back(measure(p, state, s * p.dt));
      const int in_window = (s % every == 0) ? every : s % every;
      out.window_rates.push_back(double(n) * in_window / window);
      window = 0;
    }
  }
  for (const auto& b : state)
    for (double x : {b.x[0], b.x[1], b.x[2], b.v[0], b.v[1], b.v[2]})
      if (!std::isfinite(x)) throw std::runtime_error("non-finite state at the end");
  return out;
}

// the report: one JSON object on stdout; params is the engine's settings as a JSON object
inline void report(const char* engine, const std::string& version, const Params& p, size_t n,
                   const Run& r, const std::string& params) {
  double max_body = 0, max_ground = 0;
  for (const auto& m : r.samples) {
    max_body = std::max(max_body, m.body_overlap);
    max_ground = std::max(max_ground, m.ground_overlap);
  }
  const Measure& f = r.samples.back();
  std::printf("{\"engine\": \"%s\", \"version\": \"%s\", \"n\": %zu, \"dt\": %g, \"steps\": %d, "
              "\"body_steps_per_s\": %.6g, \"cpu_s\": %.6g, "
              "\"max_overlap_m\": %.6g, \"max_body_overlap_m\": %.6g, \"max_ground_overlap_m\": %.6g, "
              "\"final_overlap_m\": %.6g, \"final_body_overlap_m\": %.6g, \"final_ground_overlap_m\": %.6g, "
              "\"final_pairs_overlapping\": %d, "
              "\"kinetic_energy_J\": %.6g, \"max_speed_m_s\": %.6g, \"height_m\": %.6g, "
              "\"params\": %s, \"samples\": [",
              engine, version.c_str(), n, p.dt, p.steps, double(r.body_steps) / r.step_cpu, r.step_cpu,
              std::max(max_body, max_ground), max_body, max_ground,
              std::max(f.body_overlap, f.ground_overlap), f.body_overlap, f.ground_overlap,
              f.pairs_overlapping, f.kinetic_energy, f.max_speed, f.height, params.c_str());
  for (size_t i = 0; i < r.samples.size(); ++i) {
    const Measure& m = r.samples[i];
    std::printf("%s{\"t\": %.4g, \"body_overlap_m\": %.4g, \"ground_overlap_m\": %.4g, "
                "\"kinetic_energy_J\": %.4g, \"height_m\": %.4g, \"max_speed_m_s\": %.4g, "
                "\"body_steps_per_s\": %.4g}",
                i ? ", " : "", m.t, m.body_overlap, m.ground_overlap, m.kinetic_energy, m.height,
                m.max_speed, i ? r.window_rates[i - 1] : 0.0);
  }
  std::printf("]}\n");
}

}  // namespace pile
