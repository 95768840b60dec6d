#include "fluid/solid_surface.h"

namespace lrigid {

void grid_point_indices(const GridGeometry& g, size_t p, int c[3]) {
  c[0] = int(p % size_t(g.n[0]));
  c[1] = int(p / size_t(g.n[0]) % size_t(g.n[1]));
  c[2] = int(p / (size_t(g.n[0]) * size_t(g.n[1])));
}

namespace {

constexpr int kValid = 6;  // GridRecord::valid among the 8 floats of a point

}  // namespace

std::vector<SurfaceSite> solid_surface_sites(const FluidField& field, const Vec3& lo,
                                             const Vec3& hi) {
  std::vector<SurfaceSite> sites;
  if (field.is_uniform()) return sites;
  const GridGeometry& g = field.geometry();
  const float* rec = field.frame_records(0);
  auto valid = [&](size_t p) { return rec[8 * p + kValid] != 0.f; };
  const size_t stride[3] = {1, size_t(g.n[0]), size_t(g.n[0]) * size_t(g.n[1])};
  for (size_t p = 0; p < g.points(); ++p) {
    if (!valid(p)) continue;
    int c[3];
    grid_point_indices(g, p, c);
    Vec3 x;
    for (int a = 0; a < 3; ++a) x[a] = g.origin[a] + c[a] * g.spacing[a];
    if (!((x.array() >= lo.array()).all() && (x.array() <= hi.array()).all())) continue;
    for (int a = 0; a < 3; ++a)
      for (int side : {-1, 1}) {
        const int q = c[a] + side;
        if (q < 0 || q >= g.n[a]) continue;
        if (!valid(side > 0 ? p + stride[a] : p - stride[a]))
          sites.push_back({uint32_t(p), uint8_t(a), int8_t(side)});
      }
  }
  return sites;
}

Vec3 surface_site_position(const GridGeometry& g, const SurfaceSite& site, double offset,
                           double a, double b) {
  int c[3];
  grid_point_indices(g, site.point, c);
  Vec3 x;
  for (int k = 0; k < 3; ++k) x[k] = g.origin[k] + c[k] * g.spacing[k];
  const int ax = site.axis, t1 = (ax + 1) % 3, t2 = (ax + 2) % 3;
  x[ax] += site.side * (0.5 * g.spacing[ax] - offset);
  x[t1] += (a - 0.5) * g.spacing[t1];
  x[t2] += (b - 0.5) * g.spacing[t2];
  return x;
}

}  // namespace lrigid
