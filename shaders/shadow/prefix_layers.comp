// The shadow-map pass's last step: an inclusive prefix over the map's layers per texel, so that
// layer k holds the optical depth of everything in front of slice k's near boundary (layer 0 stays
// 0: nothing lies in front of the first slice; layer SLICES holds the whole column).
#include "../common/oitbench.glsl"
#include "bindings.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = SHADOW_PREFIX_IMAGE_UNIT, r32f) uniform coherent image3D shadowLayers;
void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec3 size = imageSize(shadowLayers);
  if (any(greaterThanEqual(p, size.xy))) return;
  float running = 0.0;
  for (int k = 0; k < size.z; ++k) {
    running += imageLoad(shadowLayers, ivec3(p, k)).r;
    imageStore(shadowLayers, ivec3(p, k), vec4(running));
  }
}
