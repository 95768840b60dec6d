// Least-squares slope of log(y) against log(x): the observed order of a convergence study
// (error against step size), shared by the accuracy tests and the accuracy study.
#pragma once
#include <cmath>
#include <vector>

namespace lrigid {

// NaN for fewer than two points; x and y positive, of equal length
inline double log_log_slope(const std::vector<double>& x, const std::vector<double>& y) {
  const size_t n = x.size();
  if (n < 2 || y.size() != n) return std::nan("");
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < n; ++i) {
    const double a = std::log(x[i]), b = std::log(y[i]);
    sx += a;
    sy += b;
    sxx += a * a;
    sxy += a * b;
  }
  const double m = double(n);
  return (m * sxy - sx * sy) / (m * sxx - sx * sx);
}

}  // namespace lrigid
