// Counter-based random numbers: a normal variate is a pure function of (seed, body, step, slot),
// so results do not depend on thread count or on the order in which bodies are processed.
// Philox4x32-10 (Salmon et al., SC'11, Random123) turns a 128-bit counter into 4 random words;
// Box-Muller turns pairs of words into pairs of standard normals. The normal transform is our own
// (util/fast_math.h: polynomial log and sin/cos, no library calls, vectorizable), so results are
// identical across standard libraries.
#pragma once
#include <Random123/philox.h>

#include <cstdint>

#include "util/fast_math.h"

namespace lrigid {

// Philox4x32-10 on one counter, written for loops across many counters: plain 32 x 32 -> 64-bit
// products and xors, which the compiler vectorizes (Random123's generator takes one counter per
// call). Bit-for-bit Random123's r123::Philox4x32 (tests/runtime/util/rng_test.cpp).
inline void philox4x32_10(uint32_t& c0, uint32_t& c1, uint32_t& c2, uint32_t& c3, uint32_t k0,
                          uint32_t k1) {
#pragma GCC unroll 10
  for (int r = 0; r < 10; ++r) {
    const uint64_t p0 = uint64_t(0xD2511F53u) * c0;
    const uint64_t p1 = uint64_t(0xCD9E8D57u) * c2;
    c0 = uint32_t(p1 >> 32) ^ c1 ^ k0;
    c1 = uint32_t(p1);
    c2 = uint32_t(p0 >> 32) ^ c3 ^ k1;
    c3 = uint32_t(p0);
    k0 += 0x9E3779B9u;
    k1 += 0xBB67AE85u;
  }
}

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
    constexpr int kBlocks = (N + 3) / 4;
    uint32_t w[4 * kBlocks];
    for (int k = 0; k < kBlocks; ++k) {
      r123::Philox4x32::ctr_type ctr = {{body_, step_lo_, step_hi_, 0x6c720000u | block_++}};
      const auto r = gen_(ctr, key_);
      for (int j = 0; j < 4; ++j) w[4 * k + j] = r[j];
    }
    // pairs (w[4k], w[4k+1]) and (w[4k+2], w[4k+3]) as before; radii and angles in two passes
    // so the compiler can vectorize each
    double z[4 * kBlocks];
    for (int p = 0; p < 2 * kBlocks; ++p) {
      double c, s;
      const double r = box_muller_radius(w[2 * p]);
      sincos_of_turn(w[2 * p + 1], &c, &s);
      z[2 * p] = r * c;
      z[2 * p + 1] = r * s;
    }
    for (int i = 0; i < N; ++i) out[i] = z[i];
  }

  // sqrt(-2 ln u), u = (a + 1) 2^-32 in (0, 1]
  static double box_muller_radius(uint32_t a) {
    return std::sqrt(-2.0 * log_fast((static_cast<double>(a) + 1.0) * 0x1p-32));
  }

 private:
  r123::Philox4x32 gen_;
  r123::Philox4x32::key_type key_;
  uint32_t body_, step_lo_, step_hi_, block_ = 0;
};

}  // namespace lrigid
