// MuJoCo peer for bench/peers/run_peers.sh: free ellipsoids in air with MuJoCo's
// ellipsoid fluid model (fluidshape="ellipsoid"), contacts off, stepped with RK4 and with Euler.
// Two layouts: one body per model (many mjData of a one-body model: MuJoCo's best case) and all
// bodies in one model. Prints one JSON object of body-steps per second of CPU time (one core).
//   mujoco_harness [--n N] [--dt DT] [--steps S] [--one-model-max M] [--body pod|leaf|bead]
// --body: the wind scene's seed pod (default; scenes/leaves_wind.json), its leaf (a falling plate,
// the box 6 x 4 x 0.04 cm of 600 kg/m^3: explicit_schemes.sh's comparison) or the 500 um glass bead
// of scenes/beads_wind.json (a sphere; the OpenFOAM peer's parcel, for bench/perf/batch_bench.py).
// One model of many bodies costs MuJoCo O(bodies^2) per step (mj_applyFT builds a dense 3 x nv
// Jacobian for each body's fluid force), so that layout is measured with min(N, M) bodies
// (default M = 1000) and at most 10 steps: at N = 10^4 it would take about 15 min.
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

// the body's geom: the wind scene's seed pod, an ellipsoid 8 x 4 x 4 mm of 400 kg/m^3, or the
// beads scene's glass bead, a sphere of 0.25 mm radius and 2500 kg/m^3
const char* g_geom = "type=\"ellipsoid\" size=\"0.004 0.002 0.002\" density=\"400\"";

// bodies in air (1.204 kg/m^3, mu = 1.204 * 1.5e-5 Pa s) blowing at 5 m/s
std::string model_xml(int bodies, double dt, const char* integrator) {
  std::string xml = "<mujoco><option timestep=\"" + std::to_string(dt) + "\" integrator=\"" +
                    integrator +
                    "\" density=\"1.204\" viscosity=\"1.806e-5\" wind=\"5 0 0\""
                    " gravity=\"0 0 -9.81\"><flag contact=\"disable\"/></option><worldbody>";
  for (int i = 0; i < bodies; ++i) {
    // bodies 1 m apart on a square lattice, so nothing overlaps (contacts are off anyway)
    const int side = 1 + static_cast<int>(std::sqrt(double(bodies)));
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "<body pos=\"%d %d 20\" euler=\"%d %d 0\"><freejoint/>"
                  "<geom %s fluidshape=\"ellipsoid\" contype=\"0\" conaffinity=\"0\"/></body>",
                  i % side, i / side, (17 * i) % 180, (29 * i) % 180, g_geom);
    xml += buf;
  }
  return xml + "</worldbody></mujoco>";
}

mjModel* load(const std::string& xml) {
  char err[1000] = "";
  auto vfs = std::make_unique<mjVFS>();  // megabytes: not on the stack
  mj_defaultVFS(vfs.get());
  if (mj_makeEmptyFileVFS(vfs.get(), "peer.xml", static_cast<int>(xml.size())) != 0)
    throw std::runtime_error("mujoco: cannot make a VFS file");
  std::memcpy(vfs->filedata[vfs->nfile - 1], xml.data(), xml.size());
  mjModel* m = mj_loadXML("peer.xml", vfs.get(), err, sizeof err);
  mj_deleteVFS(vfs.get());
  if (!m) throw std::runtime_error(std::string("mujoco: ") + err);
  return m;
}

double cpu_seconds() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// body-steps per CPU second: `copies` mjData of a model with `bodies` bodies, `steps` each
double rate(int bodies, int copies, int steps, double dt, const char* integrator) {
  mjModel* m = load(model_xml(bodies, dt, integrator));
  std::vector<mjData*> d(static_cast<size_t>(copies), nullptr);
  for (auto& p : d) p = mj_makeData(m);
  for (auto* p : d) mj_step(m, p);  // warm-up outside the timing
  const double t0 = cpu_seconds();
  for (int s = 0; s < steps; ++s)
    for (auto* p : d) mj_step(m, p);
  const double t = cpu_seconds() - t0;
  double check = 0;  // the bodies moved: the wind carried them downstream
  for (auto* p : d) check += p->qpos[0];
  for (auto* p : d) mj_deleteData(p);
  mj_deleteModel(m);
  if (!(check == check)) throw std::runtime_error("mujoco: non-finite state");
  return double(bodies) * copies * steps / t;
}

}  // namespace

int main(int argc, char** argv) {
  int n = 10000, steps = 100, one_model_max = 1000;
  const char* body = "pod";
  double dt = 0.002;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--n")) n = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--dt")) dt = std::atof(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--steps")) steps = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--one-model-max")) one_model_max = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--body") && !std::strcmp(argv[i + 1], "pod")) body = "pod";
    else if (!std::strcmp(argv[i], "--body") && !std::strcmp(argv[i + 1], "leaf")) {
      body = "leaf";
      g_geom = "type=\"box\" size=\"0.03 0.02 0.0002\" density=\"600\"";
    } else if (!std::strcmp(argv[i], "--body") && !std::strcmp(argv[i + 1], "bead")) {
      body = "bead";
      g_geom = "type=\"sphere\" size=\"0.00025\" density=\"2500\"";
    } else if (!std::strcmp(argv[i], "--body")) {
      std::fprintf(stderr, "mujoco_harness: --body must be pod, leaf or bead, got %s\n",
                   argv[i + 1]);
      return 2;
    } else {
      std::fprintf(stderr, "mujoco_harness: unknown option %s\n", argv[i]);
      return 2;
    }
  }
  if (n < 1 || steps < 1 || one_model_max < 1 || !(dt > 0)) {
    std::fprintf(stderr,
                 "mujoco_harness: need --n >= 1, --steps >= 1, --one-model-max >= 1, --dt > 0\n");
    return 2;
  }
  try {
    // one body per model: N copies of the state; all in one model: one model of N bodies
    // (at most 64 mjData, each stepped more often: every mjData holds megabytes of arena)
    const int copies = std::min(n, 64);
    const int steps_one = int((double(n) * steps + copies - 1) / copies);
    const double rk4_one = rate(1, copies, steps_one, dt, "RK4");
    const double euler_one = rate(1, copies, steps_one, dt, "Euler");
    // all in one model: quadratic in its size, so at most one_model_max bodies, 10 steps
    const int n_many = std::min(n, one_model_max);
    const int steps_many = std::min(steps, 10);
    const double rk4_many = rate(n_many, 1, steps_many, dt, "RK4");
    const double euler_many = rate(n_many, 1, steps_many, dt, "Euler");
    std::printf("{\"mujoco_version\": %d, \"body\": \"%s\", \"n\": %d, \"dt\": %g, "
                "\"steps\": %d, "
                "\"one_body_per_model\": {\"rk4\": %.6g, \"euler\": %.6g, \"copies\": %d, "
                "\"steps_per_copy\": %d}, "
                "\"one_model\": {\"rk4\": %.6g, \"euler\": %.6g, \"bodies\": %d, "
                "\"steps\": %d}}\n",
                mj_version(), body, n, dt, steps, rk4_one, euler_one, copies, steps_one, rk4_many,
                euler_many, n_many, steps_many);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
