#include "model/release.h"

#include <cmath>

namespace lrigid {

double release_time(const BodySpec& spec, int k) {
  if (spec.release_rate > 0) return spec.release_start + double(k) / spec.release_rate;
  const int n = static_cast<int>(spec.release_times.size());
  if (n == 0) return 0;
  // bursts of q + 1 bodies for the first r times, of q for the others
  const int q = spec.count / n, r = spec.count % n;
  const int big = r * (q + 1);
  const int burst = k < big ? k / (q + 1) : r + (k - big) / q;
  return spec.release_times[size_t(burst)];
}

uint64_t first_step_at(double t, double dt) {
  const double s = std::ceil(t / dt - 1e-6);
  return s > 0 ? static_cast<uint64_t>(s) : 0;
}

}  // namespace lrigid
