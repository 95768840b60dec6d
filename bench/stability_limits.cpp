// Measures the time-step stability limits of the explicit schemes (euler, rk4) by bisection on
// dt and compares them with the linear theory of physics-notes §9: explicit Euler is stable
// for h lambda < 2, classic RK4 for h lambda < 2.785, Euler-Maruyama's OU decay for alpha h < 2.
// The splitting scheme is run at the largest dt tried to show it has no such limit.
//   stability_limits [docs/stability.md]
// prints a Markdown table and, given a file, replaces the block between
// "<!-- stability-limits:begin -->" and "<!-- stability-limits:end -->" in it.
#include <sys/utsname.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include "body/added_mass.h"
#include "compile/compile_model.h"
#include "effects/drag.h"
#include "integrate/simulation.h"
#include "model/model.h"
#include "model/state.h"

using namespace lrigid;

namespace {

Model compile(const Scene& s) {
  FluidField f = FluidField::uniform(s.uniform_U, s.uniform_k, s.uniform_epsilon,
                                     s.kinematic_viscosity, s.drift);
  return compile_model(s, std::move(f), [](const Shape& sh, double rho, int panels) {
    return added_mass(sh, rho, panels);
  });
}

struct Sphere {
  const char* name;
  double d, rho_b, rho_f, nu;
};

// drag force magnitude at relative speed u (Schiller-Naumann), N
double drag(const Sphere& c, double u) {
  const double A = M_PI * c.d * c.d / 4;
  return 0.5 * c.rho_f * schiller_naumann(u * c.d / c.nu) * A * u * u;
}

double terminal_speed(const Sphere& c, double g) {
  const double V = M_PI * c.d * c.d * c.d / 6, W = std::abs(c.rho_b - c.rho_f) * V * g;
  double lo = 0, hi = 1000;
  for (int i = 0; i < 200; ++i) {
    const double u = 0.5 * (lo + hi);
    (drag(c, u) > W ? hi : lo) = u;
  }
  return 0.5 * (lo + hi);
}

Scene sphere_scene(const Sphere& c, Integrator scheme, double dt, double u0) {
  Scene s;
  s.file = "<stability_limits>";
  s.fluid_density = c.rho_f;
  s.kinematic_viscosity = c.nu;
  BodySpec b;
  b.name = c.name;
  b.shape = Shape::sphere(c.d / 2);
  b.density = c.rho_b;
  b.velocity = Vec3(0, 0, c.rho_b > c.rho_f ? -u0 : u0);
  s.bodies.push_back(b);
  for (Effect e : {Effect::Gravity, Effect::Buoyancy, Effect::AddedMass, Effect::Drag})
    s.effects.add(e);
  s.integrator = scheme;
  s.dt = dt;
  s.duration = 20000 * dt;
  return s;
}

// drag case: stable when the speed settles on the terminal speed (linear stability of the fixed
// point) starting 1 % away from it
bool drag_stable(const Sphere& c, Integrator scheme, double dt, double uT) {
  const Scene s = sphere_scene(c, scheme, dt, 0.99 * uT);
  const Model m = compile(s);
  State st = initial_state(m, s);
  RunOptions opt;
  opt.every = s.duration;
  opt.threads = 1;
  simulate(m, &st, opt);
  if (st.status[0] != BodyStatus::Moving) return false;
  const double u = (st.q[0] * st.v[0]).norm();
  return std::isfinite(u) && std::abs(u / uT - 1) < 1e-3;
}

// turbulence case: the seen velocity's Euler-Maruyama OU update; stable when it stays within
// 10^3 standard deviations over 20000 steps
bool ou_stable(Integrator scheme, double dt, double* alpha) {
  Scene s;
  s.file = "<stability_limits>";
  s.fluid_density = 1000;
  s.kinematic_viscosity = 1e-6;
  s.uniform_k = 1;
  s.uniform_epsilon = 1000;
  BodySpec b;
  b.name = "tracer";
  b.shape = Shape::sphere(1e-3);
  b.density = 1000;
  s.bodies.push_back(b);
  s.effects.add(Effect::Turbulence);
  s.integrator = scheme;
  s.dt = dt;
  s.duration = 20000 * dt;
  const Model m = compile(s);
  FluidSample fs;
  m.field.sample(Vec3::Zero(), 0, false, &fs);
  *alpha = fs.alpha;
  State st = initial_state(m, s);
  double worst = 0;
  RunOptions opt;
  opt.every = 100 * dt;
  opt.threads = 1;
  opt.on_output = [&](const State& x) {
    const double n = x.u_seen[0].norm();
    worst = std::isfinite(n) ? std::max(worst, n) : INFINITY;
  };
  simulate(m, &st, opt);
  return st.status[0] == BodyStatus::Moving && worst < 1e3 * std::sqrt(fs.sigma2);
}

// largest stable dt by bisection in log dt between a stable lo and an unstable hi
template <typename F>
double bisect(F stable, double lo, double hi) {
  if (!stable(lo)) return NAN;
  if (stable(hi)) return INFINITY;
  for (int i = 0; i < 30 && hi / lo > 1.0005; ++i) {
    const double mid = std::sqrt(lo * hi);
    (stable(mid) ? lo : hi) = mid;
  }
  return lo;
}

std::string machine() {
  std::string cpu = "unknown CPU";
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  utsname u{};
  uname(&u);
  return cpu + ", " + u.sysname + " " + u.release;
}

}  // namespace

int main(int argc, char** argv) {
  const double g = 9.81;
  std::ostringstream t;
  char date[64];
  const std::time_t now = std::time(nullptr);
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  t << "Measured by `build/bin/stability_limits` on " << date << " (" << machine() << ").\n"
    << "Bisection on dt (relative resolution 5e-4); 20000 steps per trial.\n\n"
    << "| case | rate (1/s) | scheme | measured dt_max (s) | rate x dt_max | theory |\n"
    << "|---|---|---|---|---|---|\n";
  const Sphere spheres[] = {
      {"EPS bead 5 mm in air (drag-dominated, light)", 5e-3, 30, 1.204, 1.5e-5},
      {"air-like sphere 2 mm in water (added mass 500x own)", 2e-3, 1.2, 998.2, 1.0e-6},
      {"glass bead 1 mm in water", 1e-3, 2500, 998.2, 1.0e-6},
  };
  for (const Sphere& c : spheres) {
    const double uT = terminal_speed(c, g);
    // lambda = dF/du at u_T over the effective mass m + m_a (sphere: m_a = rho_f V / 2)
    const double V = M_PI * c.d * c.d * c.d / 6;
    const double m_eff = (c.rho_b + 0.5 * c.rho_f) * V;
    const double dF = (drag(c, uT * (1 + 1e-6)) - drag(c, uT * (1 - 1e-6))) / (2e-6 * uT);
    const double lambda = dF / m_eff;
    for (Integrator sch : {Integrator::Euler, Integrator::RK4}) {
      const double dt = bisect([&](double h) { return drag_stable(c, sch, h, uT); },
                               0.2 / lambda, 10 / lambda);
      const double theory = sch == Integrator::Euler ? 2.0 : 2.785;
      char row[400];
      std::snprintf(row, sizeof row,
                    "| %s, u_T = %.4g m/s | lambda = %.4g | %s | %.4g | %.4f | %.3f |\n", c.name,
                    uT, lambda, integrator_name(sch), dt, lambda * dt, theory);
      t << row;
      std::fprintf(stderr, "%s", row);
    }
    const double big = 100 / lambda;
    char row[400];
    std::snprintf(row, sizeof row,
                  "| %s | lambda = %.4g | splitting | stable at %.4g (%.0f/lambda) | - | none |\n",
                  c.name, lambda, big, big * lambda);
    if (drag_stable(c, Integrator::Splitting, big, uT)) t << row;
    else t << "| " << c.name << " | | splitting | **unstable at " << big << "** | | none |\n";
  }
  double alpha = 0;
  ou_stable(Integrator::Euler, 1e-4, &alpha);
  for (Integrator sch : {Integrator::Euler, Integrator::RK4}) {
    const double dt = bisect([&](double h) { return ou_stable(sch, h, &alpha); },
                             0.2 / alpha, 10 / alpha);
    char row[400];
    std::snprintf(
        row, sizeof row,
        "| seen turbulence, k = 1, eps = 1000 (water) | alpha = %.4g | %s | %.4g | %.4f | 2 |\n",
        alpha, integrator_name(sch), dt, alpha * dt);
    t << row;
    std::fprintf(stderr, "%s", row);
  }
  {
    const double big = 100 / alpha;
    const bool ok = ou_stable(Integrator::Splitting, big, &alpha);
    t << "| seen turbulence, k = 1, eps = 1000 (water) | | splitting | "
      << (ok ? "stable at " : "**unstable at ") << big << (ok ? "" : "**")
      << " (100/alpha) | - | none |\n";
  }
  std::cout << t.str();
  if (argc > 1) {
    std::ifstream in(argv[1]);
    std::stringstream ss;
    ss << in.rdbuf();
    std::string doc = ss.str();
    const std::string b = "<!-- stability-limits:begin -->", e = "<!-- stability-limits:end -->";
    const size_t pb = doc.find(b), pe = doc.find(e);
    if (pb == std::string::npos || pe == std::string::npos || pe < pb) {
      std::cerr << argv[1] << ": markers " << b << " ... " << e << " not found\n";
      return 1;
    }
    doc = doc.substr(0, pb + b.size()) + "\n" + t.str() + doc.substr(pe);
    const std::string tmp = std::string(argv[1]) + ".tmp";
    std::ofstream(tmp) << doc;
    if (std::rename(tmp.c_str(), argv[1]) != 0) return 1;
    std::cerr << "table written into " << argv[1] << "\n";
  }
  return 0;
}
