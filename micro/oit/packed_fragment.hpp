#pragma once
// The papers' 64-bit fragment as the shaders see it (uvec2): x = the float depth's bits,
// y = RGBA8 colour. Shared by every experiment that uploads or validates fragments.
#include <bit>
#include <cstdint>

namespace oitbench {

struct PackedFragment {
  uint32_t key_bits;
  uint32_t rgba;
};

inline float key_of(const PackedFragment& f) { return std::bit_cast<float>(f.key_bits); }
inline uint32_t bits_of(float k) { return std::bit_cast<uint32_t>(k); }

inline int ceil_log2(int n) {
  int l = 0;
  while ((1 << l) < n) ++l;
  return l;
}

}  // namespace oitbench
