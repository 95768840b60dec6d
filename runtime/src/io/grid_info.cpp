#include "io/grid_info.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "fluid/solid_surface.h"
#include "io/grid_reader.h"
#include "util/quantile.h"

namespace lrigid {

namespace {

struct Solid {
  size_t points = 0;
  int lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};  // point indices
  std::vector<size_t> around;                 // fluid points next to it, then kShell out
};

}  // namespace

nlohmann::json grid_info(const std::string& path, size_t max_solids) {
  RawGridFrame f;
  const GridSeries series = open_grid_series(path, &f);
  const GridGeometry& g = series.geometry;
  const int nx = g.n[0], ny = g.n[1], nz = g.n[2];
  const size_t n = g.points();
  auto index = [&](int i, int j, int k) { return size_t(i) + size_t(nx) * (size_t(j) + size_t(ny) * k); };
  // the point indices (i, j, k) of point p (x fastest)
  auto indices = [&](size_t p, int* c) { grid_point_indices(g, p, c); };
  // calls fn(r) for each neighbour r of point p along the axes, within the grid
  auto for_each_neighbour = [&](size_t p, auto&& fn) {
    int c[3];
    indices(p, c);
    for (int a = 0; a < 3; ++a)
      for (int d = -1; d <= 1; d += 2) {
        int q[3] = {c[0], c[1], c[2]};
        q[a] += d;
        if (q[a] >= 0 && q[a] < g.n[a]) fn(index(q[0], q[1], q[2]));
      }
  };
  auto speed = [&](size_t p) {
    return std::sqrt(double(f.U[3 * p]) * f.U[3 * p] + double(f.U[3 * p + 1]) * f.U[3 * p + 1] +
                     double(f.U[3 * p + 2]) * f.U[3 * p + 2]);
  };

  std::vector<double> fluid_speed, fluid_k;
  double u_max = 0;
  for (size_t p = 0; p < n; ++p)
    if (f.valid[p]) {
      fluid_speed.push_back(speed(p));
      fluid_k.push_back(f.k[p]);
      u_max = std::max(u_max, fluid_speed.back());
    }

  // the solids: connected sets of points without flow, by a flood fill along the axes
  std::vector<int32_t> label(n, -1);
  std::vector<uint32_t> seen_by(n, UINT32_MAX);  // which solid last counted a fluid neighbour
  std::vector<Solid> solids;
  std::vector<size_t> stack;
  for (size_t start = 0; start < n; ++start) {
    if (f.valid[start] || label[start] >= 0) continue;
    const int id = static_cast<int>(solids.size());
    solids.emplace_back();
    Solid& s = solids.back();
    indices(start, s.lo);
    indices(start, s.hi);
    label[start] = id;
    stack.assign(1, start);
    while (!stack.empty()) {
      const size_t p = stack.back();
      stack.pop_back();
      ++s.points;
      int c[3];
      indices(p, c);
      for (int a = 0; a < 3; ++a) {
        s.lo[a] = std::min(s.lo[a], c[a]);
        s.hi[a] = std::max(s.hi[a], c[a]);
      }
      for_each_neighbour(p, [&](size_t r) {
        if (f.valid[r]) {
          if (seen_by[r] != uint32_t(id)) {
            seen_by[r] = uint32_t(id);
            s.around.push_back(r);
          }
        } else if (label[r] < 0) {
          label[r] = id;
          stack.push_back(r);
        }
      });
    }
  }
  // the flow around each solid: at the fluid points kShell steps out from it (along the axes,
  // through the fluid), past the no-slip layer next to its walls
  constexpr int kShell = 3;
  for (size_t id = 0; id < solids.size(); ++id) {
    std::vector<size_t> frontier = std::move(solids[id].around), next;
    for (int depth = 1; depth < kShell; ++depth) {
      next.clear();
      for (size_t p : frontier)
        for_each_neighbour(p, [&](size_t r) {
          if (f.valid[r] && seen_by[r] != uint32_t(id)) {
            seen_by[r] = uint32_t(id);
            next.push_back(r);
          }
        });
      if (next.empty()) break;  // the fluid ends before: keep the farthest points reached
      frontier.swap(next);
    }
    solids[id].around = std::move(frontier);
  }
  std::sort(solids.begin(), solids.end(),
            [](const Solid& a, const Solid& b) { return a.points > b.points; });

  // the box of a solid's points widened by half a spacing (within the grid): its surface lies
  // between its points and the fluid's, so within half a spacing of this box
  const Vec3 up = g.upper();
  auto corner = [&](const int* c, double side) {
    std::vector<double> x(3);
    for (int a = 0; a < 3; ++a)
      x[a] = std::clamp(g.origin[a] + (c[a] + 0.5 * side) * g.spacing[a], g.origin[a], up[a]);
    return x;
  };
  nlohmann::json list = nlohmann::json::array();
  for (size_t s = 0; s < solids.size() && s < max_solids; ++s) {
    const Solid& d = solids[s];
    std::vector<double> u, k;
    for (size_t p : d.around) {
      u.push_back(speed(p));
      k.push_back(f.k[p]);
    }
    list.push_back({{"points", d.points},
                    {"lo", corner(d.lo, -1)},
                    {"hi", corner(d.hi, +1)},
                    {"around", {{"points", d.around.size()},
                                {"U_median", median(u)},
                                {"k_median", median(k)}}}});
  }
  return {{"file", path},
          {"points", {nx, ny, nz}},
          {"origin", {g.origin[0], g.origin[1], g.origin[2]}},
          {"spacing", {g.spacing[0], g.spacing[1], g.spacing[2]}},
          {"upper", {up[0], up[1], up[2]}},
          {"times", series.times.empty() ? std::vector<double>{f.time} : series.times},
          {"kinematic_viscosity", series.kinematic_viscosity},
          {"has_wall_distance", series.has_wall_distance},
          {"fluid_points", fluid_speed.size()},
          {"flow", {{"U_median", median(fluid_speed)}, {"U_max", u_max},
                    {"k_median", median(fluid_k)}}},
          {"solids", list},
          {"solids_total", solids.size()}};
}

}  // namespace lrigid
