#include "body/bem.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include "util/error.h"

namespace lrigid {

namespace {

struct Panel {
  Vec3 a, b, c;     // vertices (counter-clockwise seen from outside), relative to the reference
  Vec3 centroid;    // collocation point
  Vec3 normal;      // outward unit normal
  double area = 0;  // m^2
};

// far field: a panel seen from further than kFar circumradii uses the 3-point rule, from further
// than kNear the 7-point rule; closer panels are split into 4 (up to kMaxDepth times)
constexpr double kFar = 8.0;
constexpr double kNear = 3.0;
constexpr int kMaxDepth = 12;

// solid angle of triangle (a, b, c) seen from x, positive when x is behind it (on the side
// opposite to its normal); Van Oosterom & Strackee, IEEE Trans. Biomed. Eng. 30 (1983) 125
double solid_angle(const Vec3& x, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ra = a - x, rb = b - x, rc = c - x;
  const double la = ra.norm(), lb = rb.norm(), lc = rc.norm();
  const double num = ra.dot(rb.cross(rc));
  const double den = la * lb * lc + ra.dot(rb) * lc + ra.dot(rc) * lb + rb.dot(rc) * la;
  return 2.0 * std::atan2(num, den);
}

// int over a flat triangle of 1/|x - y| dA(y) for x inside it (in its plane): the sum over the
// three sub-triangles (x, p, q) of h [asinh(t_q / h) - asinh(t_p / h)], h the distance from x
// to the edge line and t the positions of p, q along it from the foot of the perpendicular
double self_integral(const Vec3& x, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3* v[3] = {&a, &b, &c};
  double sum = 0;
  for (int k = 0; k < 3; ++k) {
    const Vec3& p = *v[k];
    const Vec3& q = *v[(k + 1) % 3];
    const Vec3 u = (q - p).normalized();
    const double tp = (p - x).dot(u), tq = (q - x).dot(u);
    const double h = ((p - x) - tp * u).norm();
    sum += h * (std::asinh(tq / h) - std::asinh(tp / h));
  }
  return sum;
}

// int over triangle (a, b, c) of 1/|x - y| dA(y), x off the triangle: quadrature with
// adaptive subdivision near x
double single_layer(const Vec3& x, const Vec3& a, const Vec3& b, const Vec3& c, int depth) {
  const Vec3 g = (a + b + c) / 3.0;
  const double r2 = std::max({(a - g).squaredNorm(), (b - g).squaredNorm(), (c - g).squaredNorm()});
  const double d2 = (x - g).squaredNorm();
  const double area = 0.5 * (b - a).cross(c - a).norm();
  if (d2 > kFar * kFar * r2) {
    // degree 2: barycentric (2/3, 1/6, 1/6) and permutations, equal weights
    const Vec3 p1 = (4.0 * a + b + c) / 6.0, p2 = (a + 4.0 * b + c) / 6.0,
               p3 = (a + b + 4.0 * c) / 6.0;
    return area / 3.0 * (1.0 / (x - p1).norm() + 1.0 / (x - p2).norm() + 1.0 / (x - p3).norm());
  }
  if (d2 > kNear * kNear * r2 || depth >= kMaxDepth) {
    // degree 5 (Radon's 7-point rule)
    static const double s15 = std::sqrt(15.0);
    static const double a1 = (6.0 - s15) / 21.0, b1 = (9.0 + 2.0 * s15) / 21.0;
    static const double a2 = (6.0 + s15) / 21.0, b2 = (9.0 - 2.0 * s15) / 21.0;
    static const double w0 = 9.0 / 40.0, w1 = (155.0 - s15) / 1200.0, w2 = (155.0 + s15) / 1200.0;
    const auto f = [&](double l0, double l1, double l2) {
      return 1.0 / (x - (l0 * a + l1 * b + l2 * c)).norm();
    };
    const double s = w0 * (1.0 / (x - g).norm()) +
                     w1 * (f(b1, a1, a1) + f(a1, b1, a1) + f(a1, a1, b1)) +
                     w2 * (f(b2, a2, a2) + f(a2, b2, a2) + f(a2, a2, b2));
    return area * s;
  }
  const Vec3 ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca = 0.5 * (c + a);
  return single_layer(x, a, ab, ca, depth + 1) + single_layer(x, ab, b, bc, depth + 1) +
         single_layer(x, ca, bc, c, depth + 1) + single_layer(x, ab, bc, ca, depth + 1);
}

}  // namespace

BemResult bem_added_mass(const TriangleMesh& mesh, const Vec3& reference) {
  const int n = static_cast<int>(mesh.faces.size());
  if (n > kMaxBemPanels)
    throw Error(ExitCode::Resource, "boundary element method: " + std::to_string(n) +
                                        " panels exceed the limit of " +
                                        std::to_string(kMaxBemPanels) +
                                        " (dense solve); use a coarser mesh or fewer panels");
  if (n < 4)
    throw Error(ExitCode::BadInput, "boundary element method: mesh has fewer than 4 faces");

  std::vector<Panel> panels(n);
  // q: prescribed normal velocity of each mode, constant per panel (its exact panel average)
  Eigen::Matrix<double, Eigen::Dynamic, 6> q(n, 6);
  for (int i = 0; i < n; ++i) {
    Panel& p = panels[i];
    p.a = mesh.vertices[mesh.faces[i][0]] - reference;
    p.b = mesh.vertices[mesh.faces[i][1]] - reference;
    p.c = mesh.vertices[mesh.faces[i][2]] - reference;
    p.centroid = (p.a + p.b + p.c) / 3.0;
    const Vec3 cr = (p.b - p.a).cross(p.c - p.a);
    p.area = 0.5 * cr.norm();
    if (!(p.area > 0))
      throw Error(ExitCode::BadInput,
                  "boundary element method: face " + std::to_string(i) + " has zero area");
    p.normal = cr / (2.0 * p.area);
    q.block<1, 3>(i, 0) = p.normal.transpose();
    q.block<1, 3>(i, 3) = p.centroid.cross(p.normal).transpose();
  }

  // system (1/2 I - D) phi = -S q, assembled by rows into the transpose (contiguous columns)
  Eigen::MatrixXd at(n, n);
  Eigen::Matrix<double, Eigen::Dynamic, 6> rhs(n, 6);
  const double inv4pi = 1.0 / (4.0 * M_PI);
#pragma omp parallel for schedule(dynamic, 8)
  for (int i = 0; i < n; ++i) {
    const Vec3 x = panels[i].centroid;
    double row_sum = 0;  // sum_{j != i} D_ij
    Vec6 b = Vec6::Zero();
    for (int j = 0; j < n; ++j) {
      const Panel& p = panels[j];
      double s;
      if (j == i) {
        s = self_integral(x, p.a, p.b, p.c) * inv4pi;
        at(j, i) = 0;
      } else {
        const double d = -solid_angle(x, p.a, p.b, p.c) * inv4pi;
        at(j, i) = -d;
        row_sum += d;
        s = single_layer(x, p.a, p.b, p.c, 0) * inv4pi;
      }
      b -= s * q.row(j).transpose();
    }
    // rigid-mode identity sum_j D_ij = -1/2 gives D_ii = -1/2 - row_sum; A_ii = 1/2 - D_ii
    at(i, i) = 1.0 + row_sum;
    rhs.row(i) = b.transpose();
  }
  at.transposeInPlace();
  Eigen::PartialPivLU<Eigen::Ref<Eigen::MatrixXd>> lu(at);
  const Eigen::Matrix<double, Eigen::Dynamic, 6> phi = lu.solve(rhs);

  // K_kl = -int phi_k q_l dA
  Eigen::VectorXd area(n);
  for (int i = 0; i < n; ++i) area[i] = panels[i].area;
  const Mat6 k = -(phi.transpose() * area.asDiagonal() * q);

  BemResult r;
  r.panels = n;
  const double kmax = k.cwiseAbs().maxCoeff();
  if (!std::isfinite(kmax) || !(kmax > 0))
    throw Error(ExitCode::Runtime,
                "boundary element method: no finite solution (degenerate mesh?)");
  r.asymmetry = (k - k.transpose()).cwiseAbs().maxCoeff() / kmax;
  r.tensor = 0.5 * (k + k.transpose());
  const Eigen::SelfAdjointEigenSolver<Mat6> eig(r.tensor, Eigen::EigenvaluesOnly);
  r.min_eigenvalue = eig.eigenvalues()[0] / eig.eigenvalues()[5];
  if (r.min_eigenvalue < -1e-3)
    throw Error(ExitCode::Runtime,
                "boundary element method: tensor is not positive semi-definite (smallest/largest "
                "eigenvalue " +
                    std::to_string(r.min_eigenvalue) +
                    "); the mesh is too coarse, self-intersecting or badly shaped");
  return r;
}

}  // namespace lrigid
