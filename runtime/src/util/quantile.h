// The q-quantile of a sample by partial sort: the element at index floor(q n) (the upper median
// for q = 1/2), 0 for an empty sample. Used for the representative flow of a grid and where
// bodies start (compile/, io/).
#pragma once
#include <algorithm>
#include <utility>
#include <vector>

namespace lrigid {

inline double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  const size_t at = std::min(v.size() - 1, static_cast<size_t>(q * double(v.size())));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(at), v.end());
  return v[at];
}

inline double median(std::vector<double> v) { return quantile(std::move(v), 0.5); }

}  // namespace lrigid
