// Uniform variates from the same counter-based generator as NormalStream, for initial
// conditions (spawn positions, random orientations). Keyed by (seed, body, purpose).
#pragma once
#include <Random123/philox.h>

#include <cstdint>

namespace lrigid {

inline void uniforms4(uint64_t seed, uint32_t body, uint32_t purpose, double out[4]) {
  r123::Philox4x32 gen;
  r123::Philox4x32::key_type key = {
      {static_cast<uint32_t>(seed), static_cast<uint32_t>(seed >> 32)}};
  r123::Philox4x32::ctr_type ctr = {{body, 0xffffffffu, purpose, 0x696e6974u}};
  const auto r = gen(ctr, key);
  for (int i = 0; i < 4; ++i) out[i] = (static_cast<double>(r[i]) + 0.5) * 0x1p-32;
}

}  // namespace lrigid
