#include "contact/pair_geometry.h"

#include <ccd/ccd.h>
#include <ccd/vec3.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <utility>

#include "contact/hull.h"
#include "util/error.h"

namespace lrigid {

namespace {

using Kind = PairShape::Kind;

// ---- building the shapes ------------------------------------------------------------------

// A polytope from its vertices (shape coordinates) and faces (loops into `verts`): keeps the
// vertices the faces use, relative to the centre of mass, and finds the edges (each between the
// two faces that share it).
void set_polytope(PairShape* s, const std::vector<Vec3>& verts,
                  const std::vector<ConvexHull::Facet>& facets, const Vec3& com) {
  s->kind = Kind::Polytope;
  std::vector<int> index(verts.size(), -1);
  for (const ConvexHull::Facet& f : facets)
    for (int v : f.loop)
      if (index[size_t(v)] < 0) {
        index[size_t(v)] = int(s->vertices.size());
        s->vertices.push_back(verts[size_t(v)] - com);
      }
  std::map<std::pair<int, int>, size_t> open;  // an edge seen in one face: (v0, v1) -> edge
  for (const ConvexHull::Facet& f : facets) {
    const int fi = int(s->faces.size());
    s->faces.push_back({f.normal, f.offset - f.normal.dot(com), int(s->loops.size()),
                        int(f.loop.size())});
    for (size_t k = 0; k < f.loop.size(); ++k) {
      const int v0 = index[size_t(f.loop[k])], v1 = index[size_t(f.loop[(k + 1) % f.loop.size()])];
      s->loops.push_back(v0);
      const auto twin = open.find({v1, v0});
      if (twin != open.end()) {
        s->edges[twin->second].f1 = fi;
        open.erase(twin);
      } else {
        open[{v0, v1}] = s->edges.size();
        s->edges.push_back({v0, v1, fi, fi});
      }
    }
  }
  Vec3 mean = Vec3::Zero();
  for (const Vec3& v : s->vertices) {
    mean += v;
    s->radius = std::max(s->radius, v.norm());
  }
  s->interior = mean / double(s->vertices.size());
}

// The faces of the box of half extents h: face (axis a, side +-) has the corners with
// coordinate a at +-h[a], counter-clockwise about its outward normal.
std::vector<ConvexHull::Facet> box_faces(const Vec3& h) {
  std::vector<ConvexHull::Facet> faces;
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      const int b1 = (a + 1) % 3, b2 = (a + 2) % 3;
      ConvexHull::Facet f;
      f.normal = Vec3::Zero();
      f.normal[a] = side ? 1 : -1;
      f.offset = h[a];
      // (b1, b2) = (-,-), (+,-), (+,+), (-,+) turns about +e_a (e_b1 x e_b2 = e_a)
      const int quad[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
      for (int k = 0; k < 4; ++k) {
        const int q = side ? k : 3 - k;
        f.loop.push_back((side << a) | (quad[q][0] << b1) | (quad[q][1] << b2));
      }
      faces.push_back(std::move(f));
    }
  return faces;
}

// ---- small geometry -------------------------------------------------------------------------

// Keeps the part of polygon `in` with m . x >= c (Sutherland-Hodgman, one plane).
void clip(const std::vector<Vec3>& in, const Vec3& m, double c, std::vector<Vec3>* out) {
  out->clear();
  const size_t n = in.size();
  for (size_t k = 0; k < n; ++k) {
    const Vec3& p = in[k];
    const Vec3& q = in[(k + 1) % n];
    const double sp = m.dot(p) - c, sq = m.dot(q) - c;
    if (sp >= 0) out->push_back(p);
    if ((sp >= 0) != (sq >= 0)) out->push_back(p + (q - p) * (sp / (sp - sq)));
  }
}

// The closest points c1 on segment [p1, q1] and c2 on [p2, q2] (Ericson, Real-Time Collision
// Detection, 5.1.9).
void closest_on_segments(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2,
                         Vec3* c1, Vec3* c2) {
  const Vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  const double c = d1.dot(r), b = d1.dot(d2), den = a * e - b * b;
  double s = den > 1e-14 * a * e ? std::clamp((b * f - c * e) / den, 0.0, 1.0) : 0.0;
  double t = (b * s + f) / e;
  if (t < 0) {
    t = 0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1) {
    t = 1;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
  *c1 = p1 + d1 * s;
  *c2 = p2 + d2 * t;
}

// The closest point to x of the convex polygon `loop` (counter-clockwise about n).
Vec3 closest_on_polygon(const std::vector<Vec3>& loop, const Vec3& n, const Vec3& x) {
  const Vec3 in_plane = x - n * n.dot(x - loop[0]);
  bool inside = true;
  for (size_t k = 0; k < loop.size() && inside; ++k)
    inside = n.cross(loop[(k + 1) % loop.size()] - loop[k]).dot(in_plane - loop[k]) >= 0;
  if (inside) return in_plane;
  Vec3 best = loop[0];
  double best_d2 = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < loop.size(); ++k) {
    const Vec3 p = loop[k], e = loop[(k + 1) % loop.size()] - p;
    const double t = std::clamp(e.dot(x - p) / e.squaredNorm(), 0.0, 1.0);
    const Vec3 c = p + e * t;
    if ((x - c).squaredNorm() < best_d2) best_d2 = (x - c).squaredNorm(), best = c;
  }
  return best;
}

// support point of an ellipsoid (centre c, semi-axes k) along d, shape frame
inline Vec3 ellipsoid_support(const PairShape& s, const Vec3& d) {
  const Vec3 a2d = s.semi_axes.cwiseProduct(s.semi_axes).cwiseProduct(d);
  const double len = std::sqrt(a2d.dot(d));
  return len > 0 ? Vec3(s.centre + a2d / len) : s.centre;
}

// support point of a polytope along d, body frame
inline Vec3 polytope_support(const PairShape& s, const Vec3& d) {
  if (s.box) {
    Vec3 p;
    for (int a = 0; a < 3; ++a) p[a] = d[a] >= 0 ? s.semi_axes[a] : -s.semi_axes[a];
    return s.centre + p;
  }
  size_t best = 0;
  double best_h = -std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < s.vertices.size(); ++i) {
    const double h = s.vertices[i].dot(d);
    if (h > best_h) best_h = h, best = i;
  }
  return s.vertices[best];
}

inline Vec3 support(const PairShape& s, const Vec3& d) {
  return s.kind == Kind::Polytope ? polytope_support(s, d) : ellipsoid_support(s, d);
}

void add_point(PairManifold* out, const Vec3& p, const Vec3& n, double depth) {
  if (out->count < kPairMaxPoints) out->pts[out->count++] = {p, n, depth};
}

// At most kPairMaxPoints of `pts`: the deepest, the farthest from it, the farthest from the line
// of those two, then each time the point farthest from those kept.
void reduce(std::vector<PairPoint>* pts) {
  if (pts->size() <= size_t(kPairMaxPoints)) return;
  std::vector<PairPoint>& p = *pts;
  std::vector<PairPoint> kept;
  std::vector<bool> used(p.size(), false);
  const auto take = [&](size_t i) {
    kept.push_back(p[i]);
    used[i] = true;
  };
  const auto pick = [&](auto score) {
    size_t best = 0;
    double best_s = -1;
    for (size_t i = 0; i < p.size(); ++i)
      if (!used[i] && score(p[i]) > best_s) best_s = score(p[i]), best = i;
    take(best);
  };
  pick([](const PairPoint& q) { return q.depth + 1e300; });  // deepest (every score > -1)
  pick([&](const PairPoint& q) { return (q.p - kept[0].p).squaredNorm(); });
  pick([&](const PairPoint& q) {
    return (q.p - kept[0].p).cross(kept[1].p - kept[0].p).squaredNorm();
  });
  while (kept.size() < size_t(kPairMaxPoints))
    pick([&](const PairPoint& q) {
      double d2 = std::numeric_limits<double>::infinity();
      for (const PairPoint& k : kept) d2 = std::min(d2, (q.p - k.p).squaredNorm());
      return d2;
    });
  p = std::move(kept);
}

// ---- sphere-sphere, sphere-polytope -------------------------------------------------------

int sphere_sphere(const PairShape& a, const PairPose& pa, const PairShape& b, const PairPose& pb,
                  double margin, PairManifold* out) {
  const Vec3 ca = pa.x + pa.R * a.centre, cb = pb.x + pb.R * b.centre;
  const double ra = a.semi_axes.x(), rb = b.semi_axes.x();
  const Vec3 d = ca - cb;
  const double dist = d.norm();
  const double depth = ra + rb - dist;
  if (-depth >= margin) return 0;
  const Vec3 n = dist > 0 ? Vec3(d / dist) : Vec3::UnitZ();  // concentric: any direction
  add_point(out, 0.5 * ((ca - n * ra) + (cb + n * rb)), n, depth);
  return out->count;
}

// sphere A against polytope B: the closest point of the polytope to the sphere's centre
int sphere_polytope(const PairShape& a, const PairPose& pa, const PairShape& b,
                    const PairPose& pb, double margin, PairManifold* out) {
  const double r = a.semi_axes.x();
  const Vec3 cw = pa.x + pa.R * a.centre;
  const Vec3 c = pb.R.transpose() * (cw - pb.x);  // sphere's centre, B's frame
  // the face whose plane the centre is farthest above
  int top = 0;
  double top_s = -std::numeric_limits<double>::infinity();
  for (size_t f = 0; f < b.faces.size(); ++f) {
    const double s = b.faces[f].n.dot(c) - b.faces[f].d;
    if (s > top_s) top_s = s, top = int(f);
  }
  if (top_s - r >= margin) return 0;
  Vec3 q = Vec3::Zero(), n = Vec3::UnitZ();  // closest point of B and normal from B towards the centre, B's frame
  double dist;
  if (top_s <= 0) {  // centre inside: out through the nearest face
    n = b.faces[size_t(top)].n;
    q = c - n * top_s;
    dist = top_s;
  } else {
    if (b.box) {
      const Vec3 l = c - b.centre;
      q = b.centre + l.cwiseMax(-b.semi_axes).cwiseMin(b.semi_axes);
    } else {  // the closest point lies on a face the centre is above
      thread_local std::vector<Vec3> loop;
      double best = std::numeric_limits<double>::infinity();
      for (const PairShape::Face& f : b.faces) {
        if (f.n.dot(c) - f.d <= 0) continue;
        loop.clear();
        for (int k = 0; k < f.count; ++k) loop.push_back(b.vertices[size_t(b.loops[size_t(f.first + k)])]);
        const Vec3 p = closest_on_polygon(loop, f.n, c);
        if ((c - p).squaredNorm() < best) best = (c - p).squaredNorm(), q = p;
      }
    }
    dist = (c - q).norm();
    n = dist > 0 ? Vec3((c - q) / dist) : b.faces[size_t(top)].n;
  }
  const double depth = r - dist;
  if (-depth >= margin) return 0;
  const Vec3 nw = pb.R * n;
  const Vec3 qw = pb.x + pb.R * q;
  add_point(out, 0.5 * (qw + (cw - nw * r)), nw, depth);
  return out->count;
}

// ---- pairs with an ellipsoid: libccd's GJK/EPA and Newton's method ------------------------

// The overlap of A and B along the unit normal n (from B towards A): g(n) = h_B(n) + h_A(-n),
// h the support functions, with A's point farthest along -n (sa) and B's along n (sb), world.
// Its minimum over n is the depth (negative: minus the distance: the separating-plane duality),
// so every n gives an upper bound on the depth, and the normal is where it is least.
struct Overlap {
  double g;
  Vec3 sa, sb;
};
Overlap overlap(const PairShape& a, const PairPose& pa, const PairShape& b, const PairPose& pb,
                const Vec3& n) {
  Overlap o;
  o.sa = pa.x + pa.R * support(a, pa.R.transpose() * -n);
  o.sb = pb.x + pb.R * support(b, pb.R.transpose() * n);
  o.g = n.dot(o.sb - o.sa);
  return o;
}

// the Hessian of an ellipsoid's support function at world direction d (unit): for
// h(d) = c . d + |A R^T d|, R (A^2 / |A l| - A^2 l l^T A^2 / |A l|^3) R^T, l = R^T d; a
// polytope's is 0 (its support point is locally constant)
Mat3 support_hessian(const PairShape& s, const PairPose& p, const Vec3& d) {
  if (s.kind == Kind::Polytope) return Mat3::Zero();
  const Vec3 a2 = s.semi_axes.cwiseProduct(s.semi_axes);
  const Vec3 l = p.R.transpose() * d;
  const Vec3 a2l = a2.cwiseProduct(l);
  const double len = std::sqrt(a2l.dot(l));
  const Mat3 h = Mat3(a2.asDiagonal()) / len - a2l * a2l.transpose() / (len * len * len);
  return p.R * h * p.R.transpose();
}

// Newton's method for the least g on the unit sphere from n (Riemannian: gradient P (sb - sa),
// Hessian P H P - g P with H = H_B(n) + H_A(-n)), each step halved until g decreases.
void minimise_overlap(const PairShape& a, const PairPose& pa, const PairShape& b,
                      const PairPose& pb, double scale, Vec3* n, Overlap* o) {
  for (int it = 0; it < 30; ++it) {
    const Vec3 t1 = n->unitOrthogonal(), t2 = n->cross(t1);
    const Vec3 w = o->sb - o->sa;
    const Eigen::Vector2d grad(t1.dot(w), t2.dot(w));
    if (grad.norm() < 1e-13 * scale) return;
    const Mat3 H = support_hessian(b, pb, *n) + support_hessian(a, pa, -*n);
    Eigen::Matrix2d M;
    M << t1.dot(H * t1) - o->g, t1.dot(H * t2), t2.dot(H * t1), t2.dot(H * t2) - o->g;
    // made positive definite where it is not (away from the minimum, deep in)
    const double tr = M.trace(), det = M.determinant();
    const double low = 0.5 * tr - std::sqrt(std::max(0.0, 0.25 * tr * tr - det));
    const double floor = 1e-3 * std::max(std::abs(tr), std::abs(o->g) + 1e-300);
    if (low < floor) M += Eigen::Matrix2d::Identity() * (floor - low);
    Eigen::Vector2d step = -M.ldlt().solve(grad);
    bool moved = false;
    for (int half = 0; half < 20 && !moved; ++half, step *= 0.5) {
      const Vec3 m = (*n + t1 * step.x() + t2 * step.y()).normalized();
      const Overlap om = overlap(a, pa, b, pb, m);
      if (om.g < o->g) *n = m, *o = om, moved = true;
    }
    if (!moved) return;
  }
}

// The least overlap with the contact normal on one edge's arc of the polytope's Gauss map (its
// outward normals from face f0's to face f1's; `sign` turns them into contact normals, world):
// Newton's method in the arc's angle, g'' = n'^T H n' - g, kept on the arc.
void minimise_on_arc(const PairShape& a, const PairPose& pa, const PairShape& b,
                     const PairPose& pb, const Vec3& n0, const Vec3& n1, Vec3* n, Overlap* o) {
  const double end = std::acos(std::clamp(n0.dot(n1), -1.0, 1.0));
  if (!(end > 1e-12)) return;
  const Vec3 u = (n1 - n0 * n0.dot(n1)).normalized();
  const auto on_arc = [&](double th) { return Vec3(n0 * std::cos(th) + u * std::sin(th)); };
  double th = 0.5 * end;
  Vec3 m = on_arc(th);
  Overlap om = overlap(a, pa, b, pb, m);
  for (int it = 0; it < 20; ++it) {
    const Vec3 dm = u * std::cos(th) - n0 * std::sin(th);
    const double d1 = dm.dot(om.sb - om.sa);
    const Mat3 H = support_hessian(b, pb, m) + support_hessian(a, pa, -m);
    const double d2 = dm.dot(H * dm) - om.g;
    double step = d2 > 0 ? -d1 / d2 : (d1 > 0 ? -0.25 * end : 0.25 * end);
    bool moved = false;
    for (int half = 0; half < 20 && !moved; ++half, step *= 0.5) {
      const double t = std::clamp(th + step, 0.0, end);
      if (t == th) break;
      const Vec3 mt = on_arc(t);
      const Overlap ot = overlap(a, pa, b, pb, mt);
      if (ot.g < om.g) th = t, m = mt, om = ot, moved = true;
    }
    if (!moved || std::abs(step) < 1e-14) break;
  }
  if (om.g < o->g) *n = m, *o = om;
}

// A polytope's faces (exact for an ellipsoid on a face) and the edges at the best vertex and
// around the best face (exact for an ellipsoid across an edge): each gives an upper bound on the
// depth, the least is kept
void polytope_candidates(const PairShape& a, const PairPose& pa, const PairShape& b,
                         const PairPose& pb, Vec3* n, Overlap* o) {
  const bool b_poly = b.kind == Kind::Polytope;
  const PairShape& s = b_poly ? b : a;
  const PairPose& p = b_poly ? pb : pa;
  const double sign = b_poly ? 1 : -1;  // P's outward normal -> contact normal
  int best_face = -1;
  for (size_t f = 0; f < s.faces.size(); ++f) {
    const Vec3 m = p.R * s.faces[f].n * sign;
    const Overlap om = overlap(a, pa, b, pb, m);
    if (om.g < o->g) *n = m, *o = om, best_face = int(f);
  }
  const Vec3 d = p.R.transpose() * *n * sign;
  const Vec3 v = polytope_support(s, d);
  for (const PairShape::Edge& e : s.edges) {
    const bool at_vertex = s.vertices[size_t(e.v0)] == v || s.vertices[size_t(e.v1)] == v;
    if (!at_vertex && e.f0 != best_face && e.f1 != best_face) continue;
    minimise_on_arc(a, pa, b, pb, p.R * s.faces[size_t(e.f0)].n * sign,
                    p.R * s.faces[size_t(e.f1)].n * sign, n, o);
  }
  // then the vertex nearest the least found: Newton with its point fixed
  minimise_overlap(a, pa, b, pb, std::min(a.radius, b.radius), n, o);
}

void ccd_support(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out);
void ccd_center(const void* obj, ccd_vec3_t* out);

struct CcdBody {
  const PairShape* s;
  const PairPose* p;
  double inflate;  // the margin added to the shape (a Minkowski sum with a ball), m
};

// relative tolerance of libccd's EPA on the size of the smaller shape
constexpr double kEpaTolerance = 1e-6;

// A and B, at least one an ellipsoid: one point. libccd's GJK/EPA finds the normal roughly
// (its EPA stops on a polytope inside the curved Minkowski difference); Newton's method on the
// overlap g(n) finishes it to rounding, and a polytope's face normals are tried as well (exact
// for an ellipsoid on a face). The Minkowski sum of A with a ball of radius `margin` penetrates B
// by depth + margin along the same normal, so one query also finds the points apart by less
// than the margin.
int convex_pair(const PairShape& a, const PairPose& pa, const PairShape& b, const PairPose& pb,
                double margin, PairManifold* out) {
  const CcdBody ba{&a, &pa, margin}, bb{&b, &pb, 0};
  const double scale = std::min(a.radius, b.radius);
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = ccd_support;
  ccd.support2 = ccd_support;
  ccd.center1 = ccd_center;
  ccd.center2 = ccd_center;
  ccd.max_iterations = 100;
  ccd.epa_tolerance = kEpaTolerance * scale;
  ccd.dist_tolerance = ccd.epa_tolerance;
  ccd_real_t ccd_depth;
  ccd_vec3_t dir, pos;
  if (ccdGJKPenetration(&ba, &bb, &ccd, &ccd_depth, &dir, &pos) != 0) return 0;
  // B moves along dir to separate: A along -dir
  Vec3 n = -Vec3(ccdVec3X(&dir), ccdVec3Y(&dir), ccdVec3Z(&dir)).normalized();
  Overlap o = overlap(a, pa, b, pb, n);
  minimise_overlap(a, pa, b, pb, scale, &n, &o);
  if (a.kind == Kind::Polytope || b.kind == Kind::Polytope) polytope_candidates(a, pa, b, pb, &n, &o);
  const double depth = o.g;
  if (-depth >= margin) return 0;
  // the contact point from the smooth shapes' support points (unique, unlike a polytope's)
  Vec3 p;
  if (a.kind != Kind::Polytope && b.kind != Kind::Polytope)
    p = 0.5 * (o.sa + o.sb);
  else if (a.kind != Kind::Polytope)
    p = o.sa + n * (0.5 * depth);
  else
    p = o.sb - n * (0.5 * depth);
  add_point(out, p, n, depth);
  return out->count;
}

void ccd_support(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const CcdBody& b = *static_cast<const CcdBody*>(obj);
  const Vec3 d(ccdVec3X(dir), ccdVec3Y(dir), ccdVec3Z(dir));
  Vec3 w = b.p->x + b.p->R * support(*b.s, b.p->R.transpose() * d);
  if (b.inflate > 0) w += d * (b.inflate / d.norm());
  ccdVec3Set(out, w.x(), w.y(), w.z());
}

void ccd_center(const void* obj, ccd_vec3_t* out) {
  const CcdBody& b = *static_cast<const CcdBody*>(obj);
  const Vec3 c =
      b.p->x + b.p->R * (b.s->kind == Kind::Polytope ? b.s->interior : b.s->centre);
  ccdVec3Set(out, c.x(), c.y(), c.z());
}

// ---- polytope pairs: the separating-axis test and face clipping ------------------------------

// The edges of A and B (in A's frame) whose Gauss-map arcs cross form a face of the Minkowski
// difference, and only those give edge-edge axes (Gregorius, "The separating axis test between
// convex polyhedra", GDC 2013). a, b: A's face normals at the edge; c, d: B's.
// bxa = b x a, dxc = d x c.
inline bool minkowski_face(const Vec3& a, const Vec3& b, const Vec3& bxa, const Vec3& c,
                           const Vec3& d, const Vec3& dxc) {
  const double cba = c.dot(bxa), dba = d.dot(bxa), adc = a.dot(dxc), bdc = b.dot(dxc);
  return cba * dba < 0 && adc * bdc < 0 && cba * bdc > 0;
}

struct Scratch {
  std::vector<Vec3> vb, nb;  // B's vertices and face normals in A's frame
  std::vector<double> db;    // B's face offsets in A's frame
  std::vector<Vec3> poly, tmp;
  std::vector<Vec3> ec, ed, edxc;  // B's edges: -(face normals), their cross product, A's frame
  std::vector<PairPoint> pts;
};

// the largest separation of the vertices ov from the faces face(0 .. nf - 1) (normal, offset)
template <typename FaceAt>
inline void face_query(size_t nf, FaceAt face, const std::vector<Vec3>& ov, double* best,
                       int* best_face) {
  *best = -std::numeric_limits<double>::infinity();
  *best_face = 0;
  for (size_t f = 0; f < nf; ++f) {
    const auto [n, d] = face(f);
    double lo = std::numeric_limits<double>::infinity();
    for (const Vec3& v : ov) lo = std::min(lo, n.dot(v));
    if (lo - d > *best) *best = lo - d, *best_face = int(f);
  }
}

// Face-face and face-edge preference: an edge-edge axis or the other shape's face is taken only
// when it separates more by this much (relative to the depth, and to the smaller shape's size),
// so that resting faces keep their normal under rounding.
constexpr double kAxisRelTolerance = 0.02;
constexpr double kAxisAbsTolerance = 1e-6;

// The separating axes of two polytopes in A's frame (B's vertices at R v + t): A's and B's
// faces (the largest separation of the other's vertices from each face, and the face), and the
// edge pairs whose Gauss-map arcs cross (the largest separation, its unit axis from A towards B
// and the two edges as segments, B's in A's frame); false when some axis separates them by at
// least the margin.
struct Separation {
  double sep_a = 0, sep_b = 0, sep_e = -std::numeric_limits<double>::infinity();
  int face_a = 0, face_b = 0;
  bool edge = false;
  Vec3 axis_e = Vec3::Zero();
  Vec3 ea0 = Vec3::Zero(), ea1 = Vec3::Zero(), eb0 = Vec3::Zero(), eb1 = Vec3::Zero();
};

// B's vertices, face normals and offsets in A's frame (Scratch vb, nb, db)
void place_b(const PairShape& b, const Mat3& R, const Vec3& t, Scratch* s) {
  s->vb.resize(b.vertices.size());
  for (size_t i = 0; i < b.vertices.size(); ++i) s->vb[i] = R * b.vertices[i] + t;
  s->nb.resize(b.faces.size());
  s->db.resize(b.faces.size());
  for (size_t f = 0; f < b.faces.size(); ++f) {
    s->nb[f] = R * b.faces[f].n;
    s->db[f] = b.faces[f].d + s->nb[f].dot(t);
  }
}

bool polytope_separation(const PairShape& a, const PairShape& b, double margin, Scratch& s,
                         Separation* o) {
  face_query(
      a.faces.size(), [&](size_t f) { return std::pair(a.faces[f].n, a.faces[f].d); }, s.vb,
      &o->sep_a, &o->face_a);
  if (o->sep_a >= margin) return false;
  face_query(
      b.faces.size(), [&](size_t f) { return std::pair(s.nb[f], s.db[f]); }, a.vertices,
      &o->sep_b, &o->face_b);
  if (o->sep_b >= margin) return false;
  // edge-edge axes
  const Vec3 ca = a.interior;
  s.ec.resize(b.edges.size());
  s.ed.resize(b.edges.size());
  s.edxc.resize(b.edges.size());
  for (size_t j = 0; j < b.edges.size(); ++j) {
    s.ec[j] = -s.nb[size_t(b.edges[j].f0)];
    s.ed[j] = -s.nb[size_t(b.edges[j].f1)];
    s.edxc[j] = s.ed[j].cross(s.ec[j]);
  }
  int edge_a = -1, edge_b = -1;
  for (size_t i = 0; i < a.edges.size(); ++i) {
    const PairShape::Edge& ea = a.edges[i];
    const Vec3& n1 = a.faces[size_t(ea.f0)].n;
    const Vec3& n2 = a.faces[size_t(ea.f1)].n;
    const Vec3& p1 = a.vertices[size_t(ea.v0)];
    const Vec3 e1 = a.vertices[size_t(ea.v1)] - p1;
    const Vec3 n2xn1 = n2.cross(n1);
    for (size_t j = 0; j < b.edges.size(); ++j) {
      if (!minkowski_face(n1, n2, n2xn1, s.ec[j], s.ed[j], s.edxc[j])) continue;
      const PairShape::Edge& eb = b.edges[j];
      const Vec3& p2 = s.vb[size_t(eb.v0)];
      const Vec3 e2 = s.vb[size_t(eb.v1)] - p2;
      Vec3 axis = e1.cross(e2);
      const double len = axis.norm();
      if (len < 1e-9 * e1.norm() * e2.norm()) continue;  // parallel: a face axis covers it
      axis /= len;
      if (axis.dot(p1 - ca) < 0) axis = -axis;  // from A towards B
      const double sep = axis.dot(p2 - p1);
      if (sep > o->sep_e) o->sep_e = sep, edge_a = int(i), edge_b = int(j), o->axis_e = axis;
    }
  }
  if (o->sep_e >= margin) return false;
  if (edge_a >= 0) {
    o->edge = true;
    o->ea0 = a.vertices[size_t(a.edges[size_t(edge_a)].v0)];
    o->ea1 = a.vertices[size_t(a.edges[size_t(edge_a)].v1)];
    o->eb0 = s.vb[size_t(b.edges[size_t(edge_b)].v0)];
    o->eb1 = s.vb[size_t(b.edges[size_t(edge_b)].v1)];
  }
  return true;
}

// The same for two boxes, in closed form (the 15 axes of two oriented boxes: Gottschalk's
// projections of the half extents): B's axes are R's columns, its centre R c_B + t. A face's
// separation is the least distance of the other box's vertices above it; the faces are the
// boxes' (box_faces: face 2k + 1 the +e_k one, 2k the -e_k one; the first of equals is kept, as
// in polytope_separation); an edge pair's separation is along e_i x R_j, the two boxes' edges
// along e_i and R_j farthest towards each other.
bool box_separation(const PairShape& a, const PairShape& b, const Mat3& R, const Vec3& t,
                    double margin, Separation* o) {
  const Vec3& ha = a.semi_axes;
  const Vec3& hb = b.semi_axes;
  const Vec3 cb = R * b.centre + t;
  const Vec3 d = cb - a.centre;  // A's centre to B's, A's frame
  Mat3 absR;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) absR(i, j) = std::abs(R(i, j));
  // A's faces
  o->sep_a = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    const double rb = absR.row(i).dot(hb);
    const double sep = std::abs(d[i]) - rb - ha[i];
    if (sep > o->sep_a) o->sep_a = sep, o->face_a = 2 * i + (d[i] > 0 ? 1 : 0);
  }
  if (o->sep_a >= margin) return false;
  // B's faces: along R_j, d.R_j < 0 (B's +R_j face towards A) or along -R_j
  const Vec3 dB = R.transpose() * d;
  o->sep_b = -std::numeric_limits<double>::infinity();
  for (int j = 0; j < 3; ++j) {
    const double ra = absR.col(j).dot(ha);
    const double sep = std::abs(dB[j]) - ra - hb[j];
    if (sep > o->sep_b) o->sep_b = sep, o->face_b = 2 * j + (dB[j] < 0 ? 1 : 0);
  }
  if (o->sep_b >= margin) return false;
  // edge pairs
  int best_i = -1, best_j = -1;
  double best_s = 1;
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      // L = e_i x R_j: (0, -R_i2j, R_i1j) rotated into place
      Vec3 L = Vec3::Zero();
      L[i1] = -R(i2, j);
      L[i2] = R(i1, j);
      const double len = L.norm();
      if (len < 1e-9) continue;  // parallel: a face axis covers it
      const Vec3 LB = R.transpose() * L;
      const double ra = std::abs(L[i1]) * ha[i1] + std::abs(L[i2]) * ha[i2];
      const double rb = std::abs(LB[0]) * hb[0] + std::abs(LB[1]) * hb[1] + std::abs(LB[2]) * hb[2];
      const double dl = d.dot(L);
      const double sep = (std::abs(dl) - ra - rb) / len;
      if (sep > o->sep_e) {
        o->sep_e = sep, best_i = i, best_j = j, best_s = dl < 0 ? -1.0 : 1.0;
        o->axis_e = L * (best_s / len);
      }
    }
  }
  if (o->sep_e >= margin) return false;
  if (best_i >= 0) {
    o->edge = true;
    // A's edge along e_i farthest along the axis, B's along R_j farthest against it
    const Vec3& L = o->axis_e;
    Vec3 pa = a.centre;
    for (int k = 0; k < 3; ++k)
      if (k != best_i) pa[k] += L[k] < 0 ? -ha[k] : ha[k];
    o->ea0 = pa, o->ea1 = pa;
    o->ea0[best_i] -= ha[best_i];
    o->ea1[best_i] += ha[best_i];
    const Vec3 LB = R.transpose() * L;
    Vec3 qb = cb;
    for (int k = 0; k < 3; ++k)
      if (k != best_j) qb -= R.col(k) * (LB[k] < 0 ? -hb[k] : hb[k]);
    o->eb0 = qb - R.col(best_j) * hb[best_j];
    o->eb1 = qb + R.col(best_j) * hb[best_j];
  }
  return true;
}

int polytope_pair(const PairShape& a, const PairPose& pa, const PairShape& b,
                  const PairPose& pb, double margin, PairManifold* out) {
  thread_local Scratch s;
  // everything in A's frame
  const Mat3 R = pa.R.transpose() * pb.R;
  const Vec3 t = pa.R.transpose() * (pb.x - pa.x);
  Separation sep;
  if (a.box && b.box) {
    if (!box_separation(a, b, R, t, margin, &sep)) return 0;
  } else {
    place_b(b, R, t, &s);
    if (!polytope_separation(a, b, margin, s, &sep)) return 0;
  }
  const double sep_a = sep.sep_a, sep_b = sep.sep_b, sep_e = sep.sep_e;
  const int face_a = sep.face_a, face_b = sep.face_b;
  const Vec3& axis_e = sep.axis_e;

  const double tol_scale = kAxisAbsTolerance * std::min(a.radius, b.radius);
  const bool b_face = sep_b > sep_a + kAxisRelTolerance * std::abs(sep_a) + tol_scale;
  const double sep_f = b_face ? sep_b : sep_a;
  if (sep.edge && sep_e > sep_f + kAxisRelTolerance * std::abs(sep_f) + tol_scale) {
    Vec3 c1, c2;
    closest_on_segments(sep.ea0, sep.ea1, sep.eb0, sep.eb1, &c1, &c2);
    add_point(out, pa.x + pa.R * (0.5 * (c1 + c2)), pa.R * -axis_e, -sep_e);
    return out->count;
  }
  if (a.box && b.box) place_b(b, R, t, &s);  // (the faces' vertices and planes below)

  // face contact: the reference face and the incident face of the other shape, most against it
  Vec3 nr;
  double dr;
  s.poly.clear();
  s.tmp.clear();
  std::vector<Vec3>& ref_loop = s.tmp;
  if (!b_face) {
    const PairShape::Face& f = a.faces[size_t(face_a)];
    nr = f.n, dr = f.d;
    for (int k = 0; k < f.count; ++k) ref_loop.push_back(a.vertices[size_t(a.loops[size_t(f.first + k)])]);
    size_t inc = 0;
    double lo = std::numeric_limits<double>::infinity();
    for (size_t g = 0; g < b.faces.size(); ++g)
      if (s.nb[g].dot(nr) < lo) lo = s.nb[g].dot(nr), inc = g;
    const PairShape::Face& fi = b.faces[inc];
    for (int k = 0; k < fi.count; ++k) s.poly.push_back(s.vb[size_t(b.loops[size_t(fi.first + k)])]);
  } else {
    const PairShape::Face& f = b.faces[size_t(face_b)];
    nr = s.nb[size_t(face_b)], dr = s.db[size_t(face_b)];
    for (int k = 0; k < f.count; ++k) ref_loop.push_back(s.vb[size_t(b.loops[size_t(f.first + k)])]);
    size_t inc = 0;
    double lo = std::numeric_limits<double>::infinity();
    for (size_t g = 0; g < a.faces.size(); ++g)
      if (a.faces[g].n.dot(nr) < lo) lo = a.faces[g].n.dot(nr), inc = g;
    const PairShape::Face& fi = a.faces[inc];
    for (int k = 0; k < fi.count; ++k) s.poly.push_back(a.vertices[size_t(a.loops[size_t(fi.first + k)])]);
  }
  // clip the incident face by the reference face's side planes (inward normals nr x edge)
  const std::vector<Vec3>& ref = ref_loop;
  thread_local std::vector<Vec3> work, clipped;
  work = s.poly;
  for (size_t k = 0; k < ref.size() && !work.empty(); ++k) {
    const Vec3 e = ref[(k + 1) % ref.size()] - ref[k];
    const Vec3 m = nr.cross(e);
    clip(work, m, m.dot(ref[k]), &clipped);
    std::swap(work, clipped);
  }
  // A's normal from B towards A: against A's reference face, along B's
  const Vec3 n_world = pa.R * (b_face ? nr : Vec3(-nr));
  s.pts.clear();
  for (const Vec3& q : work) {
    const double sep = nr.dot(q) - dr;
    if (sep < margin) s.pts.push_back({pa.x + pa.R * (q - nr * (0.5 * sep)), n_world, -sep});
  }
  if (s.pts.empty()) {
    // rounding clipped everything away: the incident shape's deepest point
    const Vec3 q = b_face ? polytope_support(a, -nr) : Vec3(R * polytope_support(b, R.transpose() * -nr) + t);
    const double sep = nr.dot(q) - dr;
    if (sep >= margin) return 0;
    s.pts.push_back({pa.x + pa.R * (q - nr * (0.5 * sep)), n_world, -sep});
  }
  reduce(&s.pts);
  for (const PairPoint& p : s.pts) add_point(out, p.p, p.n, p.depth);
  return out->count;
}

// The order the pair is computed in, whatever order it is given in: by kind, then by pose, so
// that collide(B, A) repeats the arithmetic of collide(A, B).
bool goes_first(const PairShape& a, const PairPose& pa, const PairShape& b, const PairPose& pb) {
  if (a.kind != b.kind) return a.kind < b.kind;
  for (int i = 0; i < 3; ++i)
    if (pa.x[i] != pb.x[i]) return pa.x[i] < pb.x[i];
  for (int i = 0; i < 9; ++i)
    if (pa.R.data()[i] != pb.R.data()[i]) return pa.R.data()[i] < pb.R.data()[i];
  return true;
}

}  // namespace

std::shared_ptr<const PairShape> pair_shape(const Shape& shape, const Vec3& com) {
  auto s = std::make_shared<PairShape>();
  const Vec3 h = shape.half_extents;
  switch (shape.type) {
    case ShapeType::Sphere:
    case ShapeType::Ellipsoid:
      s->kind = shape.type == ShapeType::Sphere || (h.x() == h.y() && h.y() == h.z())
                    ? Kind::Sphere
                    : Kind::Ellipsoid;
      s->semi_axes = h;
      s->centre = -com;
      s->radius = s->centre.norm() + h.maxCoeff();
      break;
    case ShapeType::Box: {
      std::vector<Vec3> corners;
      for (int c = 0; c < 8; ++c)
        corners.emplace_back(c & 1 ? h.x() : -h.x(), c & 2 ? h.y() : -h.y(), c & 4 ? h.z() : -h.z());
      set_polytope(s.get(), corners, box_faces(h), com);
      s->box = true;
      s->semi_axes = h;
      s->centre = -com;
      break;
    }
    case ShapeType::Mesh: {
      std::vector<Vec3> v = shape.mesh->vertices;
      ConvexHull hull = convex_hull(v);
      if (hull.empty() && v.size() >= 3) {
        // flat: a plate kPairFlatThickness times its size thick about its plane
        Vec3 mean = Vec3::Zero();
        for (const Vec3& p : v) mean += p;
        mean /= double(v.size());
        Mat3 cov = Mat3::Zero();
        for (const Vec3& p : v) cov += (p - mean) * (p - mean).transpose();
        const Eigen::SelfAdjointEigenSolver<Mat3> eig(cov);
        const Vec3 n = eig.eigenvectors().col(0);
        double size = 0;
        for (const Vec3& p : v) size = std::max(size, (p - mean).norm());
        s->flat_thickness = kPairFlatThickness * 2 * size;
        std::vector<Vec3> thick;
        for (const Vec3& p : v) {
          thick.push_back(p + n * (0.5 * s->flat_thickness));
          thick.push_back(p - n * (0.5 * s->flat_thickness));
        }
        v = std::move(thick);
        hull = convex_hull(v);
      }
      if (hull.empty()) {
        std::ostringstream m;
        m << "mesh " << shape.source << ": its vertices span no polygon, no contact shape";
        throw Error(ExitCode::BadInput, m.str());
      }
      set_polytope(s.get(), v, hull.facets, com);
      break;
    }
  }
  return s;
}

void pair_aabb(const PairShape& s, const PairPose& p, Vec3* lo, Vec3* hi) {
  if (s.kind != Kind::Polytope || s.box) {
    // |R| h for a box; for an ellipsoid x^T (R A^2 R^T)^-1 x = 1 reaches sqrt(sum_j (R_ij a_j)^2)
    const Vec3 c = p.x + p.R * s.centre;
    Vec3 e;
    for (int i = 0; i < 3; ++i)
      e[i] = s.kind == Kind::Polytope ? p.R.row(i).cwiseAbs().dot(s.semi_axes)
                                      : p.R.row(i).cwiseProduct(s.semi_axes.transpose()).norm();
    *lo = c - e;
    *hi = c + e;
    return;
  }
  *lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  *hi = -*lo;
  for (const Vec3& v : s.vertices) {
    const Vec3 w = p.x + p.R * v;
    *lo = lo->cwiseMin(w);
    *hi = hi->cwiseMax(w);
  }
}

double pair_overlap(const PairShape& a, const PairPose& pa, const PairShape& b, const PairPose& pb,
                    const Vec3& n) {
  return overlap(a, pa, b, pb, n).g;
}

int collide(const PairShape& a, const PairPose& pa, const PairShape& b, const PairPose& pb,
            double margin, PairManifold* out) {
  out->count = 0;
  const bool swap = !goes_first(a, pa, b, pb);
  const PairShape& s1 = swap ? b : a;
  const PairShape& s2 = swap ? a : b;
  const PairPose& p1 = swap ? pb : pa;
  const PairPose& p2 = swap ? pa : pb;
  // quick rejection on the bounding spheres
  if ((p1.x - p2.x).norm() - s1.radius - s2.radius >= margin) return 0;
  if (s1.kind == Kind::Sphere && s2.kind == Kind::Sphere)
    sphere_sphere(s1, p1, s2, p2, margin, out);
  else if (s1.kind == Kind::Sphere && s2.kind == Kind::Polytope)
    sphere_polytope(s1, p1, s2, p2, margin, out);
  else if (s1.kind == Kind::Polytope && s2.kind == Kind::Polytope)
    polytope_pair(s1, p1, s2, p2, margin, out);
  else
    convex_pair(s1, p1, s2, p2, margin, out);
  if (swap)
    for (int i = 0; i < out->count; ++i) out->pts[i].n = -out->pts[i].n;
  return out->count;
}

}  // namespace lrigid
