#include "body/added_mass.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <vector>

#include "body/bem.h"
#include "body/mass_properties.h"
#include "body/tessellate.h"
#include "util/error.h"

namespace lrigid {

// duplication theorem until the arguments agree to ~1e-4, then the 5th-order series
// (Carlson, Numer. Algorithms 10 (1995) 13; DLMF 19.36.2): truncation error ~ 1e-4^6
double carlson_rd(double x, double y, double z) {
  if (!(x >= 0 && y >= 0 && z > 0 && x + y > 0))
    throw Error(ExitCode::Runtime, "carlson_rd: invalid arguments");
  double sum = 0, scale = 1;
  double mu = 0, dx = 0, dy = 0, dz = 0;
  for (int it = 0; it < 100; ++it) {
    mu = (x + y + 3.0 * z) / 5.0;
    dx = (mu - x) / mu;
    dy = (mu - y) / mu;
    dz = (mu - z) / mu;
    if (std::max({std::abs(dx), std::abs(dy), std::abs(dz)}) < 1e-4) break;
    const double sx = std::sqrt(x), sy = std::sqrt(y), sz = std::sqrt(z);
    const double lambda = sx * sy + sx * sz + sy * sz;
    sum += scale / (sz * (z + lambda));
    scale *= 0.25;
    x = 0.25 * (x + lambda);
    y = 0.25 * (y + lambda);
    z = 0.25 * (z + lambda);
  }
  const double e2 = dx * dy - 6.0 * dz * dz;
  const double e3 = (3.0 * dx * dy - 8.0 * dz * dz) * dz;
  const double e4 = 3.0 * (dx * dy - dz * dz) * dz * dz;
  const double e5 = dx * dy * dz * dz * dz;
  const double series = 1.0 - 3.0 / 14.0 * e2 + e3 / 6.0 + 9.0 / 88.0 * e2 * e2 - 3.0 / 22.0 * e4 -
                        9.0 / 52.0 * e2 * e3 + 3.0 / 26.0 * e5;
  return 3.0 * sum + scale * series / (mu * std::sqrt(mu));
}

// alpha0 = a b c int dl / ((a^2 + l) Delta) = (2/3) a b c R_D(b^2, c^2, a^2), cyclically
Vec3 ellipsoid_constants(const Vec3& s) {
  const Vec3 q = s.cwiseAbs2();
  const double abc = s.prod();
  return Vec3(2.0 / 3.0 * abc * carlson_rd(q.y(), q.z(), q.x()),
              2.0 / 3.0 * abc * carlson_rd(q.z(), q.x(), q.y()),
              2.0 / 3.0 * abc * carlson_rd(q.x(), q.y(), q.z()));
}

namespace {

// Lamb, Hydrodynamics (6th ed.) sections 114-115: per unit fluid density,
//   translation along x: V alpha0 / (2 - alpha0);
//   rotation about x: V/5 (b^2 - c^2)^2 (gamma0 - beta0) / (2 (b^2 - c^2) + (b^2 + c^2)(beta0 -
//   gamma0))
// and cyclically; the tensor is diagonal in the ellipsoid axes.
Mat6 lamb_ellipsoid(const Vec3& s) {
  const double volume = 4.0 / 3.0 * M_PI * s.prod();
  const Vec3 k = ellipsoid_constants(s);
  Vec6 d;
  for (int i = 0; i < 3; ++i) {
    d[i] = volume * k[i] / (2.0 - k[i]);
    const int j = (i + 1) % 3, l = (i + 2) % 3;
    const double bj = s[j] * s[j], cl = s[l] * s[l];
    const double diff = bj - cl;
    // axisymmetric about i: no rotational added inertia (also the 0/0 limit of the formula)
    if (std::abs(diff) <= 1e-12 * (bj + cl)) {
      d[3 + i] = 0;
    } else {
      d[3 + i] =
          volume / 5.0 * diff * diff * (k[l] - k[j]) / (2.0 * diff + (bj + cl) * (k[j] - k[l]));
    }
  }
  return d.asDiagonal();
}

int resolve_panels(int panels) {
  // checked before any tessellation: 2e9 panels would be built before the solver's own limit
  if (panels < 0 || panels > kMaxBemPanels)
    throw Error(ExitCode::Usage, "added mass: panel count must be in [0, " +
                                     std::to_string(kMaxBemPanels) + "] (0 = default), got " +
                                     std::to_string(panels));
  return panels == 0 ? kDefaultPanels : panels;
}

void check_density(double rho) {
  if (!(rho >= 0 && rho <= 1e6))
    throw Error(ExitCode::Usage, "added mass: fluid density must be in [0, 1e6] kg/m^3, got " +
                                     std::to_string(rho));
}

}  // namespace

namespace {

// The panel solutions this process has made, per unit fluid density: a scene compiled again
// (the same shape in another scene, a Python script, a test) reuses the solve of the same
// geometry and panel target, which is a pure function of them, so the result is the same to
// the bit. Bounded: the oldest entry goes first.
struct BemMemo {
  struct Entry {
    ShapeType type;
    Vec3 half_extents;
    int target;
    std::shared_ptr<const TriangleMesh> mesh;  // meshes: compared by content
    BemResult result;
  };
  std::mutex lock;
  std::vector<Entry> entries;
  int solves = 0;
  static constexpr size_t kMaxEntries = 64;

  static bool same_geometry(const Entry& e, const Shape& shape, int target) {
    if (e.type != shape.type || e.target != target || e.half_extents != shape.half_extents)
      return false;
    if (shape.type != ShapeType::Mesh) return true;
    if (!e.mesh || !shape.mesh) return false;
    return e.mesh == shape.mesh || (e.mesh->vertices == shape.mesh->vertices &&
                                    e.mesh->faces == shape.mesh->faces);
  }
  bool find(const Shape& shape, int target, BemResult* out) {
    std::lock_guard<std::mutex> guard(lock);
    for (const Entry& e : entries)
      if (same_geometry(e, shape, target)) {
        *out = e.result;
        return true;
      }
    return false;
  }
  void add(const Shape& shape, int target, const BemResult& r) {
    std::lock_guard<std::mutex> guard(lock);
    ++solves;
    if (entries.size() >= kMaxEntries) entries.erase(entries.begin());
    entries.push_back({shape.type, shape.half_extents, target, shape.mesh, r});
  }
};

BemMemo& bem_memo() {
  static BemMemo memo;
  return memo;
}

}  // namespace

int bem_solve_count() {
  std::lock_guard<std::mutex> guard(bem_memo().lock);
  return bem_memo().solves;
}

AddedMass added_mass_bem(const Shape& shape, double fluid_density, int panels) {
  check_density(fluid_density);
  const int target = resolve_panels(panels);
  BemResult r;
  if (!bem_memo().find(shape, target, &r)) {
    const TriangleMesh mesh = tessellate(shape, target);
    // tensor about the volume centroid of the shape (analytic shapes: the origin)
    const Vec3 reference =
        shape.type == ShapeType::Mesh ? mass_properties(shape).centroid : Vec3::Zero();
    r = bem_added_mass(mesh, reference);
    bem_memo().add(shape, target, r);
  }
  AddedMass am;
  am.tensor = fluid_density * r.tensor;
  am.method = "bem";
  am.panels = r.panels;
  return am;
}

AddedMass added_mass(const Shape& shape, double fluid_density, int panels) {
  check_density(fluid_density);
  resolve_panels(panels);
  switch (shape.type) {
    case ShapeType::Sphere:
    case ShapeType::Ellipsoid: {
      AddedMass am;
      am.tensor = fluid_density * lamb_ellipsoid(shape.half_extents);
      am.method = "analytic";
      return am;
    }
    case ShapeType::Box: {
      // a box's three mirror planes make its tensor diagonal in the box axes; the panel
      // solution leaves off-diagonal round-off (up to ~3e-9 of the diagonal on a 1000:1 sheet)
      // that would only cost the step the general 6x6 algebra
      AddedMass am = added_mass_bem(shape, fluid_density, panels);
      am.tensor = Mat6(am.tensor.diagonal().asDiagonal());
      return am;
    }
    case ShapeType::Mesh:
      return added_mass_bem(shape, fluid_density, panels);
  }
  return {};
}

}  // namespace lrigid
