// Langevin coefficients from the RANS fields k and epsilon (physics-notes §1-2,
// docs/physics/langevin.md).
//   R_lambda = sqrt(20/3 * k^2 / (nu eps))            Taylor-scale Reynolds number
//   C0 = 6.5 (1 + 140 R_lambda^(-4/3))^(-1)            Sawford's fit, clamped below by c0_min
//   beta = sqrt(C0 eps)                                noise amplitude, m/s^(3/2)
//   alpha = (1/2 + 3/4 C0) eps/k   ("original" drift, Pope's SLM: decaying turbulence)
//   alpha = 3/4 C0 eps/k           ("stationary" drift: reproduces <u_i^2> = 2k/3 in a frozen
//                                   field)
//   sigma2 = beta^2 / (2 alpha)    stationary per-component variance of the OU process, m^2/s^2
// Guards: k >= k_min, eps >= eps_min, and alpha <= sqrt(eps/nu) (the Lagrangian time scale is not
// shorter than the Kolmogorov time tau_eta = sqrt(nu/eps)); where that cap acts, beta is lowered so
// sigma2 is kept. Nothing divides by zero near walls.
#pragma once

namespace lrigid {

enum class Drift { Original, Stationary };

struct TurbulenceLimits {
  double k_min = 1e-10;    // m^2/s^2
  double eps_min = 1e-12;  // m^2/s^3
  double c0_min = 1.0;     // C0 collapses at low R_lambda; keep the noise on near walls
};

struct LangevinCoefficients {
  double c0 = 0;      // -
  double alpha = 0;   // 1/s
  double beta = 0;    // m/s^(3/2)
  double sigma2 = 0;  // m^2/s^2
};

double taylor_reynolds(double k, double eps, double nu);
double c0_of_reynolds(double r_lambda);
LangevinCoefficients langevin_coefficients(double k, double eps, double nu, Drift drift,
                                           const TurbulenceLimits& limits = {});

}  // namespace lrigid
