// The shadow-map pass's draws from the sorted slice keys (shaders/lines/slice_keys.comp: key
// SLICES - 1 - slice, ascending): each slice's primitives are one contiguous range of the sorted
// element buffer, drawn by one indirect command.
//   PHASE_BOUNDS:   where each key's run starts and ends (its first and last element say so)
//   PHASE_COMMANDS: command `slice` = DrawElementsIndirectCommand over that run (count 0 if empty)
#include "../common/oitbench.glsl"
#include "bindings.h"
layout(std430, binding = SLICE_RANGES_SORTED_KEYS_BINDING) readonly buffer SortedKeys { uint sortedKeys[]; };
layout(std430, binding = SLICE_RANGES_BOUNDS_BINDING) buffer Bounds { uint bounds[]; };  // [2 key] first, [2 key + 1] end; zeroed
layout(std430, binding = SLICE_RANGES_COMMANDS_BINDING) writeonly buffer Commands { uint commands[]; };  // 5 uints per slice
uniform uint count;

#if defined(PHASE_BOUNDS)
layout(local_size_x = 256) in;
void main() {
  uint j = gl_GlobalInvocationID.x;
  if (j >= count) return;
  uint k = sortedKeys[j];
  if (j == 0u || sortedKeys[j - 1u] != k) bounds[2u * k] = j;
  if (j + 1u == count || sortedKeys[j + 1u] != k) bounds[2u * k + 1u] = j + 1u;
}
#elif defined(PHASE_COMMANDS)
layout(local_size_x = 64) in;
void main() {
  uint slice = gl_GlobalInvocationID.x;
  if (slice >= uint(SLICES)) return;
  uint k = uint(SLICES) - 1u - slice;
  uint first = bounds[2u * k], end = bounds[2u * k + 1u];
  commands[5u * slice] = uint(PRIMITIVE_VERTICES) * (end - first);  // count
  commands[5u * slice + 1u] = 1u;                                    // instanceCount
  commands[5u * slice + 2u] = uint(PRIMITIVE_VERTICES) * first;      // firstIndex
  commands[5u * slice + 3u] = 0u;                                    // baseVertex
  commands[5u * slice + 4u] = 0u;                                    // baseInstance
}
#endif
