// The capture-like pass of the stencil experiment: layer l writes its fragment into node l of
// the pixel (one slot per layer: no two fragments share a node, so no lock is needed). In the
// stencil variant the fixed-function stencil op marks every pixel this pass touches.
#include "../common/oitbench.glsl"
#include "../storage/storage.glsl"
#include "fragment.glsl"

uniform int zero;  // always 0; unknown to the compiler
flat in int layer;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  uvec2 node = stencil_fragment(p, layer, LAYERS);
  node.x += uint(oitbench_fault_hang(zero));
  STORAGE_STORE(p, layer, node);
}
