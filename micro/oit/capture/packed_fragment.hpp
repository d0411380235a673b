#pragma once
// The papers' 64-bit fragment as the shaders see it (uvec2): x = the float depth's bits,
// y = RGBA8 colour. Shared by every experiment that uploads or validates fragments.
#include <bit>
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/registry.hpp"

namespace oitbench {

struct PackedFragment {
  uint32_t key_bits;
  uint32_t rgba;
};

inline float key_of(const PackedFragment& f) { return std::bit_cast<float>(f.key_bits); }
inline uint32_t bits_of(float k) { return std::bit_cast<uint32_t>(k); }

// IEEE binary16 <-> float, as packHalf2x16 / unpackHalf2x16 do (round to nearest even; the
// reference quantises what an rgba16f fragment can hold with the same rounding).
inline float half_to_float(uint16_t h) {
  uint32_t sign = (h & 0x8000u) << 16, exp = (h >> 10) & 0x1fu, man = h & 0x3ffu;
  if (exp == 0) {  // zero or subnormal: man * 2^-24
    float v = static_cast<float>(man) * (1.0f / 16777216.0f);
    return sign ? -v : v;
  }
  if (exp == 31) return std::bit_cast<float>(sign | 0x7f800000u | (man << 13));
  return std::bit_cast<float>(sign | ((exp + 112) << 23) | (man << 13));
}
inline uint16_t float_to_half(float f) {
  uint32_t x = std::bit_cast<uint32_t>(f), sign = (x >> 16) & 0x8000u;
  uint32_t ax = x & 0x7fffffffu;
  if (ax >= 0x7f800000u) return static_cast<uint16_t>(sign | 0x7c00u | (ax > 0x7f800000u ? 0x200u : 0));
  if (ax >= 0x477ff000u) return static_cast<uint16_t>(sign | 0x7c00u);  // rounds past 65504: infinity
  if (ax < 0x38800000u) {                                               // subnormal half (or zero)
    float v = std::bit_cast<float>(ax) * 16777216.0f;                   // in units of 2^-24
    uint32_t m = static_cast<uint32_t>(v), r = 0;
    float frac = v - static_cast<float>(m);
    if (frac > 0.5f || (frac == 0.5f && (m & 1u))) r = 1;
    return static_cast<uint16_t>(sign | (m + r));
  }
  uint32_t e = (ax >> 23) - 112, man = ax & 0x7fffffu;
  uint32_t h = (e << 10) | (man >> 13), rest = man & 0x1fffu;
  if (rest > 0x1000u || (rest == 0x1000u && (h & 1u))) ++h;  // may carry into the exponent: still right
  return static_cast<uint16_t>(sign | h);
}

// The bytes of `count` fragments in one shader storage block; Unsupported where they exceed
// GL_MAX_SHADER_STORAGE_BLOCK_SIZE ("EXPERIMENT: N bytes of fragments exceed GL_MAX_SHADER_STORAGE_BLOCK_SIZE
// (M); use a smaller --resolution").
inline std::size_t require_fragment_block(std::size_t count, const std::string& experiment) {
  std::size_t bytes = count * sizeof(PackedFragment);
  GLint64 max_block = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
  if (static_cast<GLint64>(bytes) > max_block)
    throw Unsupported(experiment + ": " + std::to_string(bytes) +
                      " bytes of fragments exceed GL_MAX_SHADER_STORAGE_BLOCK_SIZE (" + std::to_string(max_block) +
                      "); use a smaller --resolution");
  return bytes;
}

inline int ceil_log2(int n) {
  int l = 0;
  while ((1 << l) < n) ++l;
  return l;
}

}  // namespace oitbench
