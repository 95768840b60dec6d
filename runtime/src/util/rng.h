// Counter-based random numbers: a normal variate is a pure function of (seed, body, step, slot),
// so results do not depend on thread count or on the order in which bodies are processed.
// Philox4x32-10 (Salmon et al., SC'11, Random123) turns a 128-bit counter into 4 random words;
// Box-Muller turns pairs of words into pairs of standard normals. The normal transform is our own
// so results are identical across standard libraries.
#pragma once
#include <Random123/philox.h>

#include <cmath>
#include <cstdint>

namespace lrigid {

class NormalStream {
 public:
  NormalStream(uint64_t seed, uint32_t body, uint64_t step) {
    key_ = {{static_cast<uint32_t>(seed), static_cast<uint32_t>(seed >> 32)}};
    body_ = body;
    step_lo_ = static_cast<uint32_t>(step);
    step_hi_ = static_cast<uint32_t>(step >> 32);
  }

  // Fills out[0..n) with independent N(0,1) draws; slots never repeat within one stream.
  template <int N>
  void normals(double (&out)[N]) {
    for (int i = 0; i < N; i += 4) {
      r123::Philox4x32::ctr_type ctr = {{body_, step_lo_, step_hi_, 0x6c720000u | block_++}};
      const auto r = gen_(ctr, key_);
      double z[4];
      box_muller(r[0], r[1], z[0], z[1]);
      box_muller(r[2], r[3], z[2], z[3]);
      for (int j = 0; j < 4 && i + j < N; ++j) out[i + j] = z[j];
    }
  }

 private:
  // uniform in (0, 1], never 0 so log() is finite
  static double open_uniform(uint32_t w) { return (static_cast<double>(w) + 1.0) * 0x1p-32; }

  static void box_muller(uint32_t a, uint32_t b, double& z0, double& z1) {
    const double r = std::sqrt(-2.0 * std::log(open_uniform(a)));
    const double phi = 2.0 * M_PI * (static_cast<double>(b) * 0x1p-32);
    z0 = r * std::cos(phi);
    z1 = r * std::sin(phi);
  }

  r123::Philox4x32 gen_;
  r123::Philox4x32::key_type key_;
  uint32_t body_, step_lo_, step_hi_, block_ = 0;
};

}  // namespace lrigid
