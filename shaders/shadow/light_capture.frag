// The self-shadowing validation's capture from the light (micro/oit/scene/shadow_map.cpp, untimed): every
// fragment the map pass rasterises, stored with its primitive's number (primitiveBase, where the
// draw's primitive set starts, plus gl_PrimitiveID; 24 bits in the colour's r, g, b bytes) and its alpha byte in place of the colour, so that the CPU finds each fragment's
// slice (the GPU's own slice key of its primitive) and rebuilds the map from the same slices.
#include "../common/oitbench.glsl"
#define STORAGE_CAPTURE
#include "../capture/fragment_storage.glsl"
#include "opacity.glsl"
layout(early_fragment_tests) in;
in vec4 vColour;
in vec2 vUv;
in float vSoft;
uniform uint primitiveBase;
void main() {
  uint id = primitiveBase + uint(gl_PrimitiveID);
  vec4 coded = vec4(float(id & 255u), float((id >> 8) & 255u), float((id >> 16) & 255u), 0.0) / 255.0;
  coded.a = shadow_alpha(vColour, vUv, vSoft);
  store_fragment(ivec2(gl_FragCoord.xy), coded, gl_FragCoord.z);
}
