// MuJoCo peer of the box pile (bench/peers/pile.md, run by run_pile.sh): the pile's boxes from
// the poses file, each a free body with one box geom, dropped onto a ground plane z = 0 under
// gravity in one model, stepped with mj_step at a fixed dt (one thread). Prints one JSON object
// (pile_common.h): body-steps per CPU second of the stepping, the pile's deepest overlaps,
// kinetic energy and height.
//   pile_mujoco --poses FILE [--n N] [--size LX LY LZ] [--density RHO] [--friction MU]
//               [--restitution E] [--gravity G] [--dt DT] [--steps S] [--sample-every T]
//               [--solver CG|Newton|PGS] [--iterations K] [--tolerance TOL]
//               [--cone pyramidal|elliptic] [--solref TC DR] [--solimp D0 DW W] [--margin M]
//               [--rows-per-body R] [--contacts-per-body C]
// MuJoCo 2.2 sizes mjData for njmax constraint rows with dense njmax x nv and njmax x njmax
// arrays (efc_J, efc_JT, efc_AR), so its memory grows as N^2: --rows-per-body sets
// njmax = R * N, and the harness refuses, before allocating, a model whose mjData would exceed
// the 2^31 bytes MuJoCo 2.2 can address (its buffer size is an int): about 630 bodies at R = 16
// (the settled pile needs about 13 rows per body with the elliptic cone).
// MuJoCo has no coefficient of restitution: its contacts are damped springs (solref); a damping
// ratio of 1 (critical) gives no rebound, which is the pile's restitution 0.
#include <mujoco/mujoco.h>

#include <memory>

#include "pile_common.h"

namespace {

mjModel* load(const std::string& xml) {
  char err[1000] = "";
  auto vfs = std::make_unique<mjVFS>();  // megabytes: not on the stack
  mj_defaultVFS(vfs.get());
  if (mj_makeEmptyFileVFS(vfs.get(), "pile.xml", static_cast<int>(xml.size())) != 0)
    throw std::runtime_error("mujoco: cannot make a VFS file");
  std::memcpy(vfs->filedata[vfs->nfile - 1], xml.data(), xml.size());
  mjModel* m = mj_loadXML("pile.xml", vfs.get(), err, sizeof err);
  mj_deleteVFS(vfs.get());
  if (!m) throw std::runtime_error(std::string("mujoco: ") + err);
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  std::string solver = "CG", cone = "elliptic";
  // CG, 30 iterations, tolerance 1e-6: the fastest of MuJoCo's solvers at the same overlaps
  // (pile.md); MuJoCo's defaults are Newton, 100, 1e-8
  int iterations = 30;
  double tolerance = 1e-6;
  double solref[2] = {0.004, 1.0};      // time constant (s, at least 2 dt), damping ratio
  double solimp[3] = {0.95, 0.99, 0.001};  // impedance at 0 and at `width` (m) of penetration
  double margin = 0;
  double rows_per_body = 16, contacts_per_body = 6;
  const char* prog = argv[0];
  pile::Params p;
  try {
    p = pile::parse_flags(argc, argv, [&](int i) {
      const std::string f = argv[i];
      auto val = [&](int k) {
        if (i + k >= argc) pile::usage_error(prog, f + ": needs a value");
        return pile::parse_number(prog, f.c_str(), argv[i + k]);
      };
      if (f == "--solver" || f == "--cone") {
        if (i + 1 >= argc) pile::usage_error(prog, f + ": needs a value");
        (f == "--solver" ? solver : cone) = argv[i + 1];
        return 2;
      }
      if (f == "--iterations") { iterations = int(val(1)); return 2; }
      if (f == "--tolerance") { tolerance = val(1); return 2; }
      if (f == "--margin") { margin = val(1); return 2; }
      if (f == "--rows-per-body") { rows_per_body = val(1); return 2; }
      if (f == "--contacts-per-body") { contacts_per_body = val(1); return 2; }
      if (f == "--solref") { solref[0] = val(1); solref[1] = val(2); return 3; }
      if (f == "--solimp") { solimp[0] = val(1); solimp[1] = val(2); solimp[2] = val(3); return 4; }
      return 0;
    });
    if (solver != "CG" && solver != "Newton" && solver != "PGS")
      pile::usage_error(prog, "--solver must be CG, Newton or PGS, got " + solver);
    if (cone != "pyramidal" && cone != "elliptic")
      pile::usage_error(prog, "--cone must be pyramidal or elliptic, got " + cone);
    if (iterations < 1 || !(tolerance >= 0) || !(margin >= 0) || !(rows_per_body > 0) ||
        !(contacts_per_body > 0))
      pile::usage_error(prog, "need --iterations >= 1, --tolerance >= 0, --margin >= 0, "
                              "--rows-per-body, --contacts-per-body > 0");
    std::vector<pile::Body> init = pile::read_poses(p.poses, p.n);
    const size_t n = init.size();
    const long long nv = 6 * (long long)n;
    const long long njmax = (long long)(rows_per_body * double(n));
    const long long nconmax = (long long)(contacts_per_body * double(n));
    // mjData's njmax-sized arrays: efc_J, efc_JT (8 bytes) and their column indices (4) per
    // row and dof, efc_AR (8) and its column indices (4) per row and row; MuJoCo 2.2 counts
    // mjData's buffer in an int, so it holds at most 2^31 - 1 bytes
    const double bytes = double(njmax) * double(nv) * 24 + double(njmax) * double(njmax) * 12;
    if (bytes > 2147483647.0) {
      std::fprintf(stderr,
                   "pile_mujoco: %zu bodies need %.1f GB of mjData (njmax = %lld rows, nv = %lld: "
                   "MuJoCo 2.2 allocates njmax x nv and njmax x njmax arrays), beyond the 2^31 "
                   "bytes its int-sized buffer holds; at most about %.0f bodies at %g rows each\n",
                   n, bytes / 1e9, njmax, nv,
                   std::sqrt(2147483647.0 / (rows_per_body * 144 + rows_per_body * rows_per_body * 12)),
                   rows_per_body);
      return 3;
    }

    std::string xml;
    char buf[1200];
    std::snprintf(buf, sizeof buf,
                  "<mujoco model=\"pile\"><size njmax=\"%lld\" nconmax=\"%lld\"/>"
                  "<option timestep=\"%.17g\" gravity=\"0 0 %.17g\" solver=\"%s\" "
                  "iterations=\"%d\" tolerance=\"%.17g\" jacobian=\"sparse\" cone=\"%s\"/>"
                  "<default><geom condim=\"3\" friction=\"%.17g 0 0\" solref=\"%.17g %.17g\" "
                  "solimp=\"%.17g %.17g %.17g\" margin=\"%.17g\" density=\"%.17g\"/></default>"
                  "<worldbody><geom name=\"ground\" type=\"plane\" size=\"100 100 1\"/>",
                  njmax, nconmax, p.dt, -p.gravity, solver.c_str(), iterations, tolerance,
                  cone.c_str(), p.friction, solref[0], solref[1], solimp[0], solimp[1], solimp[2],
                  margin, p.density);
    xml = buf;
    for (const pile::Body& b : init) {
      std::snprintf(buf, sizeof buf,
                    "<body pos=\"%.17g %.17g %.17g\" quat=\"%.17g %.17g %.17g %.17g\"><freejoint/>"
                    "<geom type=\"box\" size=\"%.17g %.17g %.17g\"/></body>",
                    b.x[0], b.x[1], b.x[2], b.q[0], b.q[1], b.q[2], b.q[3], p.size[0] / 2,
                    p.size[1] / 2, p.size[2] / 2);
      xml += buf;
    }
    xml += "</worldbody></mujoco>";
    mjModel* m = load(xml);
    mjData* d = mj_makeData(m);
    if (!d) throw std::runtime_error("mujoco: mj_makeData failed (out of memory?)");

    auto get = [&](std::vector<pile::Body>& st) {
      for (size_t i = 0; i < n; ++i) {
        const mjtNum* q = d->qpos + 7 * i;
        const mjtNum* v = d->qvel + 6 * i;
        st[i].x = {q[0], q[1], q[2]};
        st[i].q = {q[3], q[4], q[5], q[6]};
        st[i].v = {v[0], v[1], v[2]};
        // a free joint's angular velocity is in the body's axes: to world axes
        const auto R = pile::rotation(st[i].q);
        for (int k = 0; k < 3; ++k)
          st[i].w[size_t(k)] = R[size_t(k)][0] * v[3] + R[size_t(k)][1] * v[4] + R[size_t(k)][2] * v[5];
      }
    };
    int max_ncon = 0, max_nefc = 0;
    auto step = [&] {
      mj_step(m, d);
      max_ncon = std::max(max_ncon, d->ncon);
      max_nefc = std::max(max_nefc, d->nefc);
    };
    const pile::Run r = pile::run(p, n, step, get);
    const int full_rows = d->warning[mjWARN_CNSTRFULL].number;
    const int full_contacts = d->warning[mjWARN_CONTACTFULL].number;
    const int bad_acc = d->warning[mjWARN_BADQACC].number;

    char params[1200];
    std::snprintf(params, sizeof params,
                  "{\"solver\": \"%s\", \"iterations\": %d, \"tolerance\": %g, \"cone\": \"%s\", "
                  "\"jacobian\": \"sparse\", \"condim\": 3, \"solref\": [%g, %g], "
                  "\"solimp\": [%g, %g, %g], \"margin_m\": %g, \"friction\": %g, "
                  "\"restitution\": \"none (damping ratio %g)\", \"njmax\": %lld, \"nconmax\": %lld, "
                  "\"mjdata_gb\": %.3g, \"contacts_at_end\": %d, \"rows_at_end\": %d, "
                  "\"max_contacts\": %d, \"max_rows\": %d, "
                  "\"warnings\": {\"constraint_full\": %d, \"contact_full\": %d, \"bad_qacc\": %d}}",
                  solver.c_str(), iterations, tolerance, cone.c_str(), solref[0], solref[1],
                  solimp[0], solimp[1], solimp[2], margin, p.friction, solref[1], njmax, nconmax,
                  double(m->nbuffer) / 1e9 + double(d->nbuffer) / 1e9, d->ncon, d->nefc, max_ncon,
                  max_nefc, full_rows,
                  full_contacts, bad_acc);
    pile::report("mujoco", std::to_string(mj_version()), p, n, r, params);
    mj_deleteData(d);
    mj_deleteModel(m);
    if (full_rows || full_contacts) {
      std::fprintf(stderr,
                   "pile_mujoco: MuJoCo ran out of %s: constraints were dropped, the result is "
                   "not valid; raise --rows-per-body / --contacts-per-body\n",
                   full_rows ? "constraint rows (njmax)" : "contacts (nconmax)");
      return 4;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "pile_mujoco: %s\n", e.what());
    return 1;
  }
  return 0;
}
