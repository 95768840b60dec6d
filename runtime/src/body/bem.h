// Boundary element (panel) method for the fluid Kirchhoff tensor of a closed body.
//
// Six exterior Neumann problems for potentials phi_k, harmonic outside the body and decaying:
//   dphi_k/dn = n_k (k = 1..3, unit translations), (x x n)_{k-3} (k = 4..6, unit rotations),
// n the outward normal, x measured from the reference point. Green's identity on the surface
// (G = 1/(4 pi r)) gives  1/2 phi - D phi = -S q  with D the double layer and S the single layer
// operator. Discretization: constant panels (the mesh triangles), collocation at centroids; D is
// the exact solid angle of each flat panel (so a constant field satisfies sum_j D_ij = -1/2; the
// diagonal is set from that identity); S by the analytic integral of 1/r over the own panel and
// adaptive subdivision with a 7-point rule nearby. Dense LU (Eigen PartialPivLU), assembly in
// parallel with OpenMP. Then  K_kl = -rho int phi_k dphi_l/dn dA, symmetrized.
// Error ~ panel area (second order): a sphere with 1280 panels is 0.5 % low.
#pragma once
#include "body/shape.h"

namespace lrigid {

// Largest panel count accepted (the dense matrix needs 8 N^2 bytes: 800 MB at 10000).
constexpr int kMaxBemPanels = 10000;

struct BemResult {
  Mat6 tensor = Mat6::Zero();  // per unit fluid density: m^3 | m^4 | m^5 blocks, symmetrized
  int panels = 0;
  double asymmetry = 0;       // |K - K^T|_max / |K|_max before symmetrization
  double min_eigenvalue = 0;  // smallest eigenvalue of the symmetrized tensor / largest
};

// Kirchhoff tensor of the closed, outward-oriented surface `mesh` (one panel per triangle),
// about `reference` (usually the volume centroid), in the mesh axes, per unit fluid density.
// Throws lrigid::Error(ExitCode::Resource) above kMaxBemPanels and ExitCode::Runtime if the
// result is not positive semi-definite (badly shaped or self-intersecting mesh).
BemResult bem_added_mass(const TriangleMesh& mesh, const Vec3& reference);

}  // namespace lrigid
