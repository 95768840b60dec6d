#include "foam_case.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <future>
#include <regex>

#include "error.h"
#include "foam_file.h"

namespace fs = std::filesystem;

namespace foam2grid {
namespace {

bool parse_time(const std::string& name, double* value) {
  const char* b = name.data();
  const char* e = b + name.size();
  auto r = std::from_chars(b, e, *value);
  return r.ec == std::errc() && r.ptr == e && std::isfinite(*value);
}

// written times in dir (directories named by a number), ascending
void list_times(const std::string& dir, std::vector<std::string>* names,
                std::vector<double>* values) {
  std::vector<std::pair<double, std::string>> t;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    double v;
    const std::string n = e.path().filename().string();
    if (e.is_directory() && parse_time(n, &v)) t.emplace_back(v, n);
  }
  std::sort(t.begin(), t.end());
  names->clear();
  values->clear();
  for (auto& [v, n] : t) {
    values->push_back(v);
    names->push_back(n);
  }
}

std::string mesh_dir(const std::string& part) { return part + "/constant/polyMesh"; }

// checks 0 <= l < n for a list of labels read from path
void check_range(const std::vector<Label>& l, Label n, const std::string& path) {
  for (std::size_t i = 0; i < l.size(); ++i) {
    if (l[i] < 0 || l[i] >= n) {
      fail_input(path + ": entry " + std::to_string(i) + " = " + std::to_string(l[i]) +
                 " is out of range [0, " + std::to_string(n) + ")");
    }
  }
}

}  // namespace

bool Patch::gives_point_values() const {
  return type != "empty" && type.find("processor") == std::string::npos &&
         type.rfind("cyclic", 0) != 0;
}

bool Patch::is_symmetry() const {
  return type == "symmetry" || type == "symmetryPlane" || type == "wedge";
}

FoamCase open_case(const std::string& dir, CaseSource source) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) fail_input("case directory '" + dir + "' not found");
  FoamCase fc;
  fc.dir = fs::absolute(dir).lexically_normal().string();
  while (fc.dir.size() > 1 && fc.dir.back() == '/') fc.dir.pop_back();
  fc.name = fs::path(fc.dir).filename().string();

  // processor directories, by number
  std::vector<std::pair<long, std::string>> procs;
  for (const auto& e : fs::directory_iterator(fc.dir, ec)) {
    const std::string n = e.path().filename().string();
    if (e.is_directory() && n.rfind("processor", 0) == 0 && n.size() > 9 &&
        std::all_of(n.begin() + 9, n.end(), [](char c) { return std::isdigit(c) != 0; })) {
      procs.emplace_back(std::stol(n.substr(9)), e.path().string());
    }
  }
  std::sort(procs.begin(), procs.end());
  const bool has_recon = FoamFile::exists(mesh_dir(fc.dir) + "/faces");
  const bool has_decomp = !procs.empty() && FoamFile::exists(mesh_dir(procs[0].second) + "/faces");

  bool decomposed = false;
  if (source == CaseSource::kReconstructed) {
    if (!has_recon) {
      fail_input("case '" + fc.dir + "': no mesh (" + mesh_dir(fc.dir) +
                 "/faces not found; run blockMesh, or reconstructPar for a decomposed case)");
    }
  } else if (source == CaseSource::kDecomposed) {
    if (!has_decomp) {
      fail_input("case '" + fc.dir + "': no decomposed mesh (processor*/constant/polyMesh/faces" +
                 " not found; run decomposePar)");
    }
    decomposed = true;
  } else if (!has_recon && !has_decomp) {
    fail_input("case '" + fc.dir + "': no mesh (" + mesh_dir(fc.dir) +
               "/faces not found; run blockMesh)");
  } else if (!has_recon) {
    decomposed = true;
  } else if (has_decomp) {
    // both: the processors win when they hold later times than the reconstructed case
    std::vector<std::string> n0, n1;
    std::vector<double> v0, v1;
    list_times(fc.dir, &n0, &v0);
    list_times(procs[0].second, &n1, &v1);
    decomposed = !v1.empty() && (v0.empty() || v1.back() > v0.back());
  }

  fc.decomposed = decomposed;
  if (decomposed) {
    for (auto& p : procs) fc.part_dirs.push_back(p.second);
  } else {
    fc.part_dirs.push_back(fc.dir);
  }
  list_times(fc.part_dirs[0], &fc.time_names, &fc.time_values);
  if (fc.time_names.empty()) {
    fail_input("case '" + fc.dir + "': no time directories in " + fc.part_dirs[0]);
  }
  return fc;
}

void read_points(const FoamCase& fc, std::vector<MeshPart>* parts) {
  parts->clear();
  parts->resize(fc.part_dirs.size());
  for (std::size_t i = 0; i < fc.part_dirs.size(); ++i) {
    MeshPart& m = (*parts)[i];
    m.dir = fc.part_dirs[i];
    FoamFile f(mesh_dir(m.dir) + "/points");
    Cursor c(f, f.body());
    c.scalar_list(3, &m.points);
    for (double v : m.points) {
      if (!std::isfinite(v)) fail_input(f.path() + ": non-finite point coordinate");
    }
  }
}

void read_topology(const FoamCase& fc, std::vector<MeshPart>* parts) {
  Label n_global_points = 0;
  for (MeshPart& m : *parts) {
    const std::string md = mesh_dir(m.dir);
    std::vector<Label> tmp;
    // the faces (the largest file) in a second thread while owner and neighbour are read
    std::future<void> faces = std::async(std::launch::async, [&m, &md]() {
      FoamFile f(md + "/faces");
      Cursor c(f, f.body());
      c.face_list(&m.face_offsets, &m.face_points);
      check_range(m.face_points, m.n_points(), f.path());
    });
    {
      FoamFile f(md + "/owner");
      Cursor c(f, f.body());
      c.label_list(&tmp);
      m.owner.swap(tmp);
    }
    {
      FoamFile f(md + "/neighbour");
      Cursor c(f, f.body());
      c.label_list(&tmp);
      m.neighbour.swap(tmp);
      if (m.neighbour.size() > m.owner.size())
        fail_input(f.path() + ": more neighbours than faces");
    }
    faces.get();
    {
      const std::string f = md + "/owner";
      if (m.owner.size() + 1 != m.face_offsets.size()) {
        fail_input(f + ": " + std::to_string(m.owner.size()) + " owners for " +
                   std::to_string(m.face_offsets.size() - 1) + " faces");
      }
    }
    Label nc = 0;
    for (Label o : m.owner) nc = std::max(nc, o + 1);
    for (Label o : m.neighbour) nc = std::max(nc, o + 1);
    m.n_cells = nc;
    check_range(m.owner, nc, md + "/owner");
    {
      FoamFile f(md + "/boundary");
      Cursor c(f, f.body());
      if (std::isdigit(static_cast<unsigned char>(c.peek()))) c.label();
      c.expect('(', "'(' opening the patch list");
      while (c.peek() != ')') {
        Patch p;
        p.name = c.token();
        c.expect('{', "'{' after patch " + p.name);
        const std::vector<DictEntry> d = c.dict(false);
        const DictEntry* type = find_entry(d, "type");
        const DictEntry* n = find_entry(d, "nFaces");
        const DictEntry* s = find_entry(d, "startFace");
        if (!type || !n || !s) {
          fail_input(f.path() + ": patch " + p.name + " lacks type, nFaces or startFace");
        }
        p.type = Cursor(f, type->begin).token();
        p.size = Cursor(f, n->begin).label();
        p.start = Cursor(f, s->begin).label();
        if (p.start < m.n_internal_faces() || p.start + p.size > m.n_faces()) {
          fail_input(f.path() + ": patch " + p.name + " faces [" + std::to_string(p.start) + ", " +
                     std::to_string(p.start + p.size) + ") outside the boundary faces");
        }
        m.patches.push_back(p);
      }
    }
    if (fc.decomposed) {
      FoamFile f(md + "/pointProcAddressing");
      Cursor c(f, f.body());
      c.label_list(&m.point_global);
      if (static_cast<Label>(m.point_global.size()) != m.n_points()) {
        fail_input(f.path() + ": " + std::to_string(m.point_global.size()) + " entries for " +
                   std::to_string(m.n_points()) + " points");
      }
      for (Label g : m.point_global) n_global_points = std::max(n_global_points, g + 1);
    }
    compute_geometry(&m);
  }
}

namespace {

// face centre and area vector as OpenFOAM computes them: triangles fanned from the point
// average (a triangle directly)
void face_geometry(const double* p, const Label* fp, Label n, double* fc, double* fa) {
  if (n == 3) {
    const double* a = p + 3 * fp[0];
    const double* b = p + 3 * fp[1];
    const double* c = p + 3 * fp[2];
    double e1[3], e2[3];
    for (int k = 0; k < 3; ++k) {
      fc[k] = (1.0 / 3.0) * (a[k] + b[k] + c[k]);
      e1[k] = b[k] - a[k];
      e2[k] = c[k] - a[k];
    }
    fa[0] = 0.5 * (e1[1] * e2[2] - e1[2] * e2[1]);
    fa[1] = 0.5 * (e1[2] * e2[0] - e1[0] * e2[2]);
    fa[2] = 0.5 * (e1[0] * e2[1] - e1[1] * e2[0]);
    return;
  }
  double centre[3] = {p[3 * fp[0]], p[3 * fp[0] + 1], p[3 * fp[0] + 2]};
  for (Label i = 1; i < n; ++i) {
    for (int k = 0; k < 3; ++k) centre[k] += p[3 * fp[i] + k];
  }
  for (int k = 0; k < 3; ++k) centre[k] /= static_cast<double>(n);
  double sum_n[3] = {0, 0, 0}, sum_ac[3] = {0, 0, 0}, sum_a = 0;
  for (Label i = 0; i < n; ++i) {
    const double* x = p + 3 * fp[i];
    const double* y = p + 3 * fp[(i + 1) % n];
    double c[3], e1[3], e2[3], nn[3];
    for (int k = 0; k < 3; ++k) {
      c[k] = x[k] + y[k] + centre[k];
      e1[k] = y[k] - x[k];
      e2[k] = centre[k] - x[k];
    }
    nn[0] = e1[1] * e2[2] - e1[2] * e2[1];
    nn[1] = e1[2] * e2[0] - e1[0] * e2[2];
    nn[2] = e1[0] * e2[1] - e1[1] * e2[0];
    const double a = std::sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
    for (int k = 0; k < 3; ++k) {
      sum_n[k] += nn[k];
      sum_ac[k] += a * c[k];
    }
    sum_a += a;
  }
  if (sum_a < 1e-150) {
    for (int k = 0; k < 3; ++k) {
      fc[k] = centre[k];
      fa[k] = 0;
    }
  } else {
    for (int k = 0; k < 3; ++k) {
      fc[k] = (1.0 / 3.0) * sum_ac[k] / sum_a;
      fa[k] = 0.5 * sum_n[k];
    }
  }
}

}  // namespace

void compute_geometry(MeshPart* mp) {
  MeshPart& m = *mp;
  const Label nf = m.n_faces();
  const Label ni = m.n_internal_faces();
  const Label nc = m.n_cells;
  const double* p = m.points.data();

  // boundary faces: centres and area vectors kept (patch values, symmetry normals)
  m.boundary_face_centres.assign(3 * (nf - ni), 0.0);
  m.boundary_face_areas.assign(3 * (nf - ni), 0.0);
#pragma omp parallel for schedule(static)
  for (Label f = ni; f < nf; ++f) {
    face_geometry(p, m.face_points.data() + m.face_offsets[f],
                  m.face_offsets[f + 1] - m.face_offsets[f], &m.boundary_face_centres[3 * (f - ni)],
                  &m.boundary_face_areas[3 * (f - ni)]);
  }

  // cell-face lists
  m.cell_face_offsets.assign(nc + 1, 0);
  for (Label f = 0; f < nf; ++f) ++m.cell_face_offsets[m.owner[f] + 1];
  for (Label f = 0; f < ni; ++f) ++m.cell_face_offsets[m.neighbour[f] + 1];
  for (Label c = 0; c < nc; ++c) m.cell_face_offsets[c + 1] += m.cell_face_offsets[c];
  m.cell_faces.assign(m.cell_face_offsets[nc], 0);
  {
    std::vector<Label> fill(m.cell_face_offsets.begin(), m.cell_face_offsets.end() - 1);
    for (Label f = 0; f < nf; ++f) m.cell_faces[fill[m.owner[f]]++] = f;
    for (Label f = 0; f < ni; ++f) m.cell_faces[fill[m.neighbour[f]]++] = f;
  }

  // cell centres and volumes: face pyramids on the average of the face centres, owner faces
  // first then neighbour faces, as OpenFOAM sums them (face geometry recomputed per cell)
  m.cell_centres.assign(3 * nc, 0.0);
  m.cell_volumes.assign(nc, 0.0);
#pragma omp parallel
  {
    std::vector<double> geo;
#pragma omp for schedule(static)
    for (Label c = 0; c < nc; ++c) {
      const Label b = m.cell_face_offsets[c], e = m.cell_face_offsets[c + 1];
      geo.resize(static_cast<std::size_t>(6 * (e - b)));
      double est[3] = {0, 0, 0};
      for (Label i = b; i < e; ++i) {
        const Label f = m.cell_faces[i];
        double* g = &geo[static_cast<std::size_t>(6 * (i - b))];
        face_geometry(p, m.face_points.data() + m.face_offsets[f],
                      m.face_offsets[f + 1] - m.face_offsets[f], g, g + 3);
        for (int k = 0; k < 3; ++k) est[k] += g[k];
      }
      for (int k = 0; k < 3; ++k) est[k] /= static_cast<double>(std::max<Label>(e - b, 1));
      double* cc = &m.cell_centres[3 * c];
      double vol = 0;
      for (int pass = 0; pass < 2; ++pass) {
        for (Label i = b; i < e; ++i) {
          const Label f = m.cell_faces[i];
          const bool own = m.owner[f] == c;
          if (own != (pass == 0)) continue;
          const double* fc = &geo[static_cast<std::size_t>(6 * (i - b))];
          const double* fa = fc + 3;
          const double vol3 =
              (own ? 1.0 : -1.0) *
              (fa[0] * (fc[0] - est[0]) + fa[1] * (fc[1] - est[1]) + fa[2] * (fc[2] - est[2]));
          for (int k = 0; k < 3; ++k) cc[k] += vol3 * ((3.0 / 4.0) * fc[k] + (1.0 / 4.0) * est[k]);
          vol += vol3;
        }
      }
      if (std::fabs(vol) > 1e-300) {
        for (int k = 0; k < 3; ++k) cc[k] /= vol;
      } else {
        for (int k = 0; k < 3; ++k) cc[k] = est[k];
      }
      m.cell_volumes[c] = vol / 3.0;
    }
  }

  // base point of each face's triangle fan: the first whose tets have positive volume seen
  // from the owner centre and negative volume from the neighbour centre
  m.tet_base.assign(nf, 0);
  auto tet_vol = [&](const double* a, const double* b, const double* c, const double* d) {
    double u[3], v[3], w[3];
    for (int k = 0; k < 3; ++k) {
      u[k] = b[k] - a[k];
      v[k] = c[k] - a[k];
      w[k] = d[k] - a[k];
    }
    return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
            u[2] * (v[0] * w[1] - v[1] * w[0])) /
           6.0;
  };
#pragma omp parallel for schedule(static)
  for (Label f = 0; f < nf; ++f) {
    const Label b = m.face_offsets[f];
    const Label n = m.face_offsets[f + 1] - b;
    if (n <= 3) continue;
    const Label* fp = m.face_points.data() + b;
    const double* co = &m.cell_centres[3 * m.owner[f]];
    const double* cn = f < m.n_internal_faces() ? &m.cell_centres[3 * m.neighbour[f]] : nullptr;
    const double tol = 1e-12 * std::fabs(m.cell_volumes[m.owner[f]]);
    for (Label base = 0; base < n; ++base) {
      bool ok = true;
      for (Label t = 1; t < n - 1 && ok; ++t) {
        const double* pa = p + 3 * fp[base];
        const double* pb = p + 3 * fp[(base + t) % n];
        const double* pc = p + 3 * fp[(base + t + 1) % n];
        // the face normal points out of the owner: the owner centre lies behind the face
        if (tet_vol(pa, pb, pc, co) > -tol) ok = false;
        if (cn && tet_vol(pa, pb, pc, cn) < tol) ok = false;
      }
      if (ok) {
        m.tet_base[f] = static_cast<int>(base);
        break;
      }
    }
  }
}

namespace {

// a field value entry, resolving "$name" and "uniform $name" against the file's top entries
void entry_value(const FoamFile& f, const std::vector<DictEntry>& top, const DictEntry& e,
                 int ncomp, std::size_t n, std::vector<double>* out, int depth = 0) {
  if (depth > 8) fail_input(f.path() + ": '$' references nested too deeply");
  Cursor c(f, e.begin);
  auto lookup = [&](const std::string& ref) -> const DictEntry& {
    const DictEntry* r = find_entry(top, ref.substr(1));
    if (!r || r->is_dict) c.fail("'" + ref + "' does not name a value in this file");
    return *r;
  };
  if (c.peek() == '$') {
    entry_value(f, top, lookup(c.token()), ncomp, n, out, depth + 1);
    return;
  }
  const std::size_t start = c.pos();
  if (c.token() == "uniform" && c.peek() == '$') {
    const DictEntry& r = lookup(c.token());
    Cursor v(f, r.begin);
    std::vector<double> one(static_cast<std::size_t>(ncomp));
    if (ncomp > 1) v.expect('(', "'(' of a vector");
    for (double& x : one) x = v.scalar();
    out->clear();
    for (std::size_t i = 0; i < n; ++i) out->insert(out->end(), one.begin(), one.end());
    return;
  }
  Cursor c2(f, start);
  c2.field_value(ncomp, n, out);
}

const DictEntry* find_patch_entry(const std::vector<DictEntry>& bf, const std::string& name) {
  if (const DictEntry* e = find_entry(bf, name)) return e;
  for (const DictEntry& e : bf) {  // quoted regular expressions such as "(top|sides)"
    if (e.key.find_first_of("()|.*[]") == std::string::npos) continue;
    try {
      if (std::regex_match(name, std::regex(e.key, std::regex::extended))) return &e;
    } catch (const std::regex_error&) {
    }
  }
  return nullptr;
}

}  // namespace

void read_fields(const MeshPart& m, const std::string& time_name,
                 const std::vector<FieldSpec>& fields, PartFields* out) {
  int ncomp = 0;
  for (const FieldSpec& s : fields) ncomp = std::max(ncomp, s.offset + s.ncomp);
  const Label nc = m.n_cells;
  const Label nb = m.n_faces() - m.n_internal_faces();
  out->ncomp = ncomp;
  out->cells.assign(static_cast<std::size_t>(nc * ncomp), 0.0);
  out->boundary.assign(static_cast<std::size_t>(nb * ncomp), 0.0);
  // one thread per field (each fills its own components)
  auto read_one = [&](const FieldSpec& s) {
    std::vector<double> vals;
    const std::string path = m.dir + "/" + time_name + "/" + s.name;
    if (!FoamFile::exists(path)) {
      fail_input("field '" + s.name + "' not found at time " + time_name + ": " + path +
                 " does not exist");
    }
    FoamFile f(path);
    const std::string want = s.ncomp == 3 ? "volVectorField" : "volScalarField";
    if (f.class_name() != want) {
      fail_input(f.path() + ": field '" + s.name + "' is a " + f.class_name() + ", expected " +
                 want);
    }
    Cursor c(f, f.body());
    const std::vector<DictEntry> top = c.dict(true);
    const DictEntry* internal = find_entry(top, "internalField");
    if (!internal) fail_input(f.path() + ": no internalField");
    entry_value(f, top, *internal, s.ncomp, static_cast<std::size_t>(nc), &vals);
    for (Label i = 0; i < nc; ++i) {
      for (int k = 0; k < s.ncomp; ++k) {
        const double v = vals[static_cast<std::size_t>(i * s.ncomp + k)];
        if (!std::isfinite(v)) {
          fail_input(f.path() + ": internalField of '" + s.name + "' has a non-finite value (" +
                     std::to_string(v) + ") in cell " + std::to_string(i));
        }
        out->cells[static_cast<std::size_t>(i * ncomp + s.offset + k)] = v;
      }
    }
    const DictEntry* bf = find_entry(top, "boundaryField");
    if (!bf || !bf->is_dict) fail_input(f.path() + ": no boundaryField dictionary");
    for (const Patch& p : m.patches) {
      if (!p.gives_point_values()) continue;
      const DictEntry* pe = find_patch_entry(bf->sub, p.name);
      if (!pe || !pe->is_dict) {
        fail_input(f.path() + ": boundaryField has no entry for patch '" + p.name + "'");
      }
      const DictEntry* te = find_entry(pe->sub, "type");
      const std::string type = te ? Cursor(f, te->begin).token() : "";
      const DictEntry* ve = find_entry(pe->sub, "value");
      const std::size_t n = static_cast<std::size_t>(p.size);
      if (ve) {
        entry_value(f, top, *ve, s.ncomp, n, &vals);
      } else {
        // evaluated as OpenFOAM does on reading: from the adjacent cells
        vals.assign(n * static_cast<std::size_t>(s.ncomp), 0.0);
        const bool no_slip = type == "noSlip";
        const bool symmetric =
            type == "symmetry" || type == "symmetryPlane" || type == "slip" || type == "wedge";
        for (std::size_t i = 0; i < n; ++i) {
          const Label face = p.start + static_cast<Label>(i);
          const Label cell = m.owner[face];
          if (no_slip) continue;
          double* v = &vals[i * static_cast<std::size_t>(s.ncomp)];
          for (int k = 0; k < s.ncomp; ++k) {
            v[k] = out->cells[static_cast<std::size_t>(cell * ncomp + s.offset + k)];
          }
          if (symmetric && s.ncomp == 3) {
            // (v + reflected v)/2 = v - (n.v) n
            const double* a = &m.boundary_face_areas[3 * (face - m.n_internal_faces())];
            const double mag = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
            if (mag > 0) {
              const double nn[3] = {a[0] / mag, a[1] / mag, a[2] / mag};
              const double dot = v[0] * nn[0] + v[1] * nn[1] + v[2] * nn[2];
              for (int k = 0; k < 3; ++k) v[k] -= dot * nn[k];
            }
          }
        }
      }
      for (std::size_t i = 0; i < n; ++i) {
        const Label bface = p.start - m.n_internal_faces() + static_cast<Label>(i);
        for (int k = 0; k < s.ncomp; ++k) {
          const double v =
              vals[i * static_cast<std::size_t>(s.ncomp) + static_cast<std::size_t>(k)];
          if (!std::isfinite(v)) {
            fail_input(f.path() + ": boundaryField " + p.name + " of '" + s.name +
                       "' has a non-finite value in face " + std::to_string(i));
          }
          out->boundary[static_cast<std::size_t>(bface * ncomp + s.offset + k)] = v;
        }
      }
    }
  };
  std::vector<std::future<void>> pending;
  for (std::size_t i = 1; i < fields.size(); ++i) {
    pending.push_back(std::async(std::launch::async, read_one, std::cref(fields[i])));
  }
  std::exception_ptr first_error;
  try {
    read_one(fields[0]);
  } catch (...) {
    first_error = std::current_exception();
  }
  for (std::future<void>& f : pending) {
    try {
      f.get();
    } catch (...) {
      if (!first_error) first_error = std::current_exception();
    }
  }
  if (first_error) std::rethrow_exception(first_error);
}

double read_viscosity(const std::string& case_dir) {
  const std::string path = case_dir + "/constant/transportProperties";
  if (!FoamFile::exists(path)) fail_input(path + " not found (needed for kinematic_viscosity)");
  FoamFile f(path);
  Cursor c(f, f.body());
  const std::vector<DictEntry> top = c.dict(true);
  const DictEntry* e = find_entry(top, "nu");
  if (!e || e->is_dict) fail_input(f.path() + ": no entry 'nu' (kinematic viscosity, m^2/s)");
  Cursor v(f, e->begin);
  // forms: "nu [dims] value", "[dims] value", "value"
  if (v.peek() == 'n') v.token();
  if (v.accept('[')) {
    while (!v.accept(']')) v.token();
  }
  const double nu = v.scalar();
  if (!std::isfinite(nu) || nu <= 0) {
    fail_input(f.path() + ": nu = " + std::to_string(nu) + " must be a positive number");
  }
  return nu;
}

}  // namespace foam2grid
