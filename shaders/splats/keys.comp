// The global sort's keys (GLOBAL-SORT, Kerbl et al. 2023's per-frame sort of the splats by their
// centres' view depth): splat i's key is the float bits of its mean's clip w (positive floats order as
// their bits), complemented so that the radix sort's ascending order (micro/oit/scene/radix_sort.hpp)
// is far to near: back to front, what "over" blending needs. Equal depths keep the submission order
// (the sort is stable). A splat behind the eye (w <= 0, culled by the rasteriser) sorts last.
// SPLAT_KEYS_NEAR_FIRST (WINDOW-SORT, and GLOBAL-SORT with early_stop: both blend front to back): the bits
// themselves, near to far.
#include "../common/oitbench.glsl"
#include "splats.glsl"
layout(local_size_x = 256) in;
layout(std430, binding = SPLAT_KEYS_BINDING) writeonly buffer Keys { uint keys[]; };
layout(std430, binding = SPLAT_KEY_INDICES_BINDING) writeonly buffer Indices { uint indices[]; };
uniform mat4 viewProj;
uniform uint count;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= count) return;
  float w = (viewProj * vec4(load_splat(i).position, 1.0)).w;
#if defined(SPLAT_KEYS_NEAR_FIRST)
  uint key = floatBitsToUint(max(w, 0.0));
#else
  uint key = ~floatBitsToUint(max(w, 0.0));
#endif
#ifdef OITBENCH_FAULT_WRONG_RESULT
  if (i == 0u) key = ~key;  // the first splat sorts to the wrong end
#endif
  keys[i] = key;
  indices[i] = i;
}
