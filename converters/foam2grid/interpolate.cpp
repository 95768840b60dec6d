#include "interpolate.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>

namespace foam2grid {
namespace {

double dist(const double* a, const double* b) {
  const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

// distinct points of a cell, from its faces
void cell_points(const MeshPart& m, Label c, std::vector<Label>* pts) {
  pts->clear();
  for (Label i = m.cell_face_offsets[c]; i < m.cell_face_offsets[c + 1]; ++i) {
    const Label f = m.cell_faces[i];
    for (Label j = m.face_offsets[f]; j < m.face_offsets[f + 1]; ++j) {
      pts->push_back(m.face_points[j]);
    }
  }
  std::sort(pts->begin(), pts->end());
  pts->erase(std::unique(pts->begin(), pts->end()), pts->end());
}

// pointConstraint as OpenFOAM accumulates it: 0 free, 1 plane (normal n), 2 line (direction
// n), 3 fixed
struct Constraint {
  int kind = 0;
  double n[3] = {0, 0, 0};
  void apply(const double* cd) {
    if (kind == 0) {
      kind = 1;
      std::copy(cd, cd + 3, n);
    } else if (kind == 1) {
      const double c[3] = {cd[1] * n[2] - cd[2] * n[1], cd[2] * n[0] - cd[0] * n[2],
                           cd[0] * n[1] - cd[1] * n[0]};
      const double mag = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
      if (mag > 1e-3) {
        kind = 2;
        for (int k = 0; k < 3; ++k) n[k] = c[k] / mag;
      }
    } else if (kind == 2) {
      if (std::fabs(cd[0] * n[0] + cd[1] * n[1] + cd[2] * n[2]) > 1e-3) kind = 3;
    }
  }
  void constrain(double* v) const {
    const double d = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
    for (int k = 0; k < 3; ++k) {
      if (kind == 1) v[k] -= d * n[k];
      if (kind == 2) v[k] = d * n[k];
      if (kind == 3) v[k] = 0;
    }
  }
};

}  // namespace

Label count_global_points(const std::vector<MeshPart>& parts) {
  Label n = 0;
  for (const MeshPart& m : parts) {
    if (m.point_global.empty()) {
      n = std::max(n, m.n_points());
    } else {
      for (Label g : m.point_global) n = std::max(n, g + 1);
    }
  }
  return n;
}

std::array<double, 6> mesh_bounds(const std::vector<MeshPart>& parts) {
  const double inf = std::numeric_limits<double>::infinity();
  std::array<double, 6> b = {inf, -inf, inf, -inf, inf, -inf};
  for (const MeshPart& m : parts) {
    for (std::size_t i = 0; i < m.points.size(); i += 3) {
      for (int k = 0; k < 3; ++k) {
        b[2 * k] = std::min(b[2 * k], m.points[i + k]);
        b[2 * k + 1] = std::max(b[2 * k + 1], m.points[i + k]);
      }
    }
  }
  return b;
}

std::vector<double> point_values(const std::vector<MeshPart>& parts,
                                 const std::vector<PartFields>& fields,
                                 const std::vector<FieldSpec>& specs) {
  const Label ng = count_global_points(parts);
  const int nc = fields.empty() ? 0 : fields[0].ncomp;
  // patch points take only patch face contributions, the others only cell contributions:
  // one accumulator serves both
  std::vector<double> sum_w(ng, 0.0), acc(static_cast<std::size_t>(ng * nc), 0.0);
  std::vector<char> on_patch(ng, 0);
  for (const MeshPart& m : parts) {
    for (const Patch& patch : m.patches) {
      if (!patch.gives_point_values()) continue;
      for (Label j = m.face_offsets[patch.start]; j < m.face_offsets[patch.start + patch.size];
           ++j) {
        on_patch[m.global(m.face_points[j])] = 1;
      }
    }
  }
  // symmetry normals per point: (point, patch id, unit face normal)
  struct SymNormal {
    Label point;
    int patch;
    double n[3];
  };
  std::vector<SymNormal> sym;
  int patch_id = 0;
  std::vector<Label> pts;
  for (std::size_t part = 0; part < parts.size(); ++part) {
    const MeshPart& m = parts[part];
    const PartFields& pf = fields[part];
    // internal points: inverse distance from the cell centres
    for (Label c = 0; c < m.n_cells; ++c) {
      cell_points(m, c, &pts);
      const double* cc = &m.cell_centres[3 * c];
      const double* cv = &pf.cells[static_cast<std::size_t>(c * nc)];
      for (Label p : pts) {
        const Label g = m.global(p);
        if (on_patch[g]) continue;
        const double w = 1.0 / dist(&m.points[3 * p], cc);
        sum_w[g] += w;
        double* a = &acc[static_cast<std::size_t>(g * nc)];
        for (int k = 0; k < nc; ++k) a[k] += w * cv[k];
      }
    }
    // patch points: inverse distance from the patch face centres, patch face values
    for (const Patch& patch : m.patches) {
      if (!patch.gives_point_values()) continue;
      for (Label f = patch.start; f < patch.start + patch.size; ++f) {
        const double* fc = &m.boundary_face_centres[3 * (f - m.n_internal_faces())];
        const double* fv = &pf.boundary[static_cast<std::size_t>((f - m.n_internal_faces()) * nc)];
        for (Label j = m.face_offsets[f]; j < m.face_offsets[f + 1]; ++j) {
          const Label p = m.face_points[j];
          const double w = 1.0 / dist(&m.points[3 * p], fc);
          const Label g = m.global(p);
          sum_w[g] += w;
          double* a = &acc[static_cast<std::size_t>(g * nc)];
          for (int k = 0; k < nc; ++k) a[k] += w * fv[k];
        }
      }
    }
    // symmetry patches: point normals (sum of the unit normals of the faces at the point)
    for (const Patch& patch : m.patches) {
      if (!patch.is_symmetry()) continue;
      for (Label f = patch.start; f < patch.start + patch.size; ++f) {
        const double* a = &m.boundary_face_areas[3 * (f - m.n_internal_faces())];
        const double mag = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        if (mag <= 0) continue;
        for (Label j = m.face_offsets[f]; j < m.face_offsets[f + 1]; ++j) {
          sym.push_back(
              {m.global(m.face_points[j]), patch_id, {a[0] / mag, a[1] / mag, a[2] / mag}});
        }
      }
      ++patch_id;
    }
  }
  std::vector<double>& out = acc;
  for (Label g = 0; g < ng; ++g) {
    if (sum_w[g] <= 0) continue;
    const double inv = 1.0 / sum_w[g];
    for (int k = 0; k < nc; ++k) out[static_cast<std::size_t>(g * nc + k)] *= inv;
  }

  // constraints: per point, one normal per symmetry patch, applied in patch order
  if (!sym.empty()) {
    std::sort(sym.begin(), sym.end(), [](const SymNormal& a, const SymNormal& b) {
      return a.point != b.point ? a.point < b.point : a.patch < b.patch;
    });
    std::size_t i = 0;
    while (i < sym.size()) {
      const Label g = sym[i].point;
      Constraint con;
      while (i < sym.size() && sym[i].point == g) {
        const int patch = sym[i].patch;
        double n[3] = {0, 0, 0};
        while (i < sym.size() && sym[i].point == g && sym[i].patch == patch) {
          for (int k = 0; k < 3; ++k) n[k] += sym[i].n[k];
          ++i;
        }
        const double mag = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (mag > 0) {
          for (double& x : n) x /= mag;
          con.apply(n);
        }
      }
      for (const FieldSpec& s : specs) {
        if (s.ncomp == 3) con.constrain(&out[static_cast<std::size_t>(g * nc + s.offset)]);
      }
    }
  }
  return acc;
}

void resample(const std::vector<MeshPart>& parts, const std::vector<PartFields>& fields,
              const std::vector<double>& point_vals, const std::vector<FieldSpec>& specs,
              const GridSpec& grid, Scheme scheme, GridFields* out,
              const ResampleProgress& on_progress) {
  const std::size_t np = grid.n_points();
  const int nc = fields.empty() ? 0 : fields[0].ncomp;
  out->arrays.resize(specs.size());
  for (std::size_t s = 0; s < specs.size(); ++s) {
    out->arrays[s].assign(np * static_cast<std::size_t>(specs[s].ncomp), 0.0f);
  }
  out->valid.assign(np, 0);
  std::unique_ptr<std::atomic<std::uint8_t>[]> claimed(new std::atomic<std::uint8_t>[np]);
  for (std::size_t i = 0; i < np; ++i) claimed[i].store(0, std::memory_order_relaxed);

  const double* o = grid.origin.data();
  const double* h = grid.spacing.data();
  const long* dims = grid.dims.data();
  constexpr double kTol = 1e-10;  // barycentric tolerance (points on faces and edges)

  // progress: cells done and points resampled per thread (each counter written by its own
  // thread only, so no contention); thread 0 adds them up and reports every kReport cells
  struct alignas(64) Counts {
    std::atomic<std::size_t> cells{0}, points{0};
  };
  std::vector<Counts> counts(static_cast<std::size_t>(std::max(1, omp_get_max_threads())));
  double total_cells = 0;
  for (const MeshPart& m : parts) total_cells += static_cast<double>(m.n_cells);
  auto report = [&] {
    std::size_t cells = 0, points = 0;
    for (const Counts& n : counts) {
      cells += n.cells.load(std::memory_order_relaxed);
      points += n.points.load(std::memory_order_relaxed);
    }
    on_progress(static_cast<double>(cells) / std::max(total_cells, 1.0), points);
  };
  constexpr std::size_t kReport = 4096;
  auto bump = [](std::atomic<std::size_t>& a) {
    a.store(a.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
  };

  for (std::size_t part = 0; part < parts.size(); ++part) {
    const MeshPart& m = parts[part];
    const PartFields& pf = fields[part];
    const Label ncell = m.n_cells;
#pragma omp parallel for schedule(dynamic, 1024)
    for (Label c = 0; c < ncell; ++c) {
      const int tid = omp_get_thread_num();
      Counts& mine = counts[static_cast<std::size_t>(tid)];
      bump(mine.cells);
      if (tid == 0 && on_progress && mine.cells.load(std::memory_order_relaxed) % kReport == 0) {
        report();
      }
      // grid index range of the cell's bounding box
      double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
      for (Label i = m.cell_face_offsets[c]; i < m.cell_face_offsets[c + 1]; ++i) {
        const Label f = m.cell_faces[i];
        for (Label j = m.face_offsets[f]; j < m.face_offsets[f + 1]; ++j) {
          const double* x = &m.points[3 * m.face_points[j]];
          for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], x[k]);
            hi[k] = std::max(hi[k], x[k]);
          }
        }
      }
      long i0[3], i1[3];
      bool empty = false;
      for (int k = 0; k < 3; ++k) {
        const double a = (lo[k] - o[k]) / h[k], b = (hi[k] - o[k]) / h[k];
        i0[k] = std::max(0L, static_cast<long>(std::ceil(a - 1e-9)));
        i1[k] = std::min(dims[k] - 1, static_cast<long>(std::floor(b + 1e-9)));
        if (i0[k] > i1[k]) empty = true;
      }
      if (empty) continue;
      const double* cc = &m.cell_centres[3 * c];
      const double* cv = &pf.cells[static_cast<std::size_t>(c * nc)];
      for (long kz = i0[2]; kz <= i1[2]; ++kz) {
        for (long ky = i0[1]; ky <= i1[1]; ++ky) {
          for (long kx = i0[0]; kx <= i1[0]; ++kx) {
            const std::size_t gi =
                static_cast<std::size_t>(kx) +
                static_cast<std::size_t>(dims[0]) *
                    (static_cast<std::size_t>(ky) +
                     static_cast<std::size_t>(dims[1]) * static_cast<std::size_t>(kz));
            if (claimed[gi].load(std::memory_order_relaxed)) continue;
            const double x[3] = {o[0] + static_cast<double>(kx) * h[0],
                                 o[1] + static_cast<double>(ky) * h[1],
                                 o[2] + static_cast<double>(kz) * h[2]};
            // find the tet (cell centre, face triangle) holding x
            bool found = false;
            double w[4] = {0, 0, 0, 0};
            Label tri[3] = {0, 0, 0};
            for (Label i = m.cell_face_offsets[c]; i < m.cell_face_offsets[c + 1] && !found; ++i) {
              const Label f = m.cell_faces[i];
              const Label fb = m.face_offsets[f];
              const Label fn = m.face_offsets[f + 1] - fb;
              const Label base = m.tet_base[f];
              for (Label t = 1; t < fn - 1; ++t) {
                const Label pa = m.face_points[fb + base];
                const Label pb = m.face_points[fb + (base + t) % fn];
                const Label pc = m.face_points[fb + (base + t + 1) % fn];
                const double* a = &m.points[3 * pa];
                const double* b = &m.points[3 * pb];
                const double* d = &m.points[3 * pc];
                // barycentric coordinates of x in (cc, a, b, d)
                double e0[3], e1[3], e2[3], r[3];
                for (int k = 0; k < 3; ++k) {
                  e0[k] = cc[k] - d[k];
                  e1[k] = a[k] - d[k];
                  e2[k] = b[k] - d[k];
                  r[k] = x[k] - d[k];
                }
                const double c0[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                                      e1[0] * e2[1] - e1[1] * e2[0]};
                const double det = e0[0] * c0[0] + e0[1] * c0[1] + e0[2] * c0[2];
                if (std::fabs(det) < 1e-14 * std::fabs(6.0 * m.cell_volumes[c]) || det == 0.0) {
                  continue;
                }
                const double c1[3] = {e2[1] * e0[2] - e2[2] * e0[1], e2[2] * e0[0] - e2[0] * e0[2],
                                      e2[0] * e0[1] - e2[1] * e0[0]};
                const double c2[3] = {e0[1] * e1[2] - e0[2] * e1[1], e0[2] * e1[0] - e0[0] * e1[2],
                                      e0[0] * e1[1] - e0[1] * e1[0]};
                const double u = (r[0] * c0[0] + r[1] * c0[1] + r[2] * c0[2]) / det;
                const double v = (r[0] * c1[0] + r[1] * c1[1] + r[2] * c1[2]) / det;
                const double s = (r[0] * c2[0] + r[1] * c2[1] + r[2] * c2[2]) / det;
                const double q = 1.0 - u - v - s;
                if (u >= -kTol && v >= -kTol && s >= -kTol && q >= -kTol) {
                  w[0] = u;
                  w[1] = v;
                  w[2] = s;
                  w[3] = q;
                  tri[0] = m.global(pa);
                  tri[1] = m.global(pb);
                  tri[2] = m.global(pc);
                  found = true;
                  break;
                }
              }
            }
            if (!found) continue;
            std::uint8_t expected = 0;
            if (!claimed[gi].compare_exchange_strong(expected, 1)) continue;
            for (std::size_t sidx = 0; sidx < specs.size(); ++sidx) {
              const FieldSpec& spec = specs[sidx];
              float* dst = &out->arrays[sidx][gi * static_cast<std::size_t>(spec.ncomp)];
              for (int k = 0; k < spec.ncomp; ++k) {
                const int comp = spec.offset + k;
                double val;
                if (scheme == Scheme::kCell) {
                  val = cv[comp];
                } else {
                  val = w[0] * cv[comp] +
                        w[1] * point_vals[static_cast<std::size_t>(tri[0] * nc + comp)] +
                        w[2] * point_vals[static_cast<std::size_t>(tri[1] * nc + comp)] +
                        w[3] * point_vals[static_cast<std::size_t>(tri[2] * nc + comp)];
                }
                dst[k] = static_cast<float>(val);
              }
            }
            out->valid[gi] = 1;
            bump(mine.points);
          }
        }
      }
    }
  }
  if (on_progress) report();
}

}  // namespace foam2grid
