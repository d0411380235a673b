// Back-to-front "over" blending of the sorted segments (fixed-function blending does the over).
#include "../common/oitbench.glsl"
in vec4 vColour;
in vec2 vUv;
in float vSoft;
layout(location = 0) out vec4 fragColour;
void main() { fragColour = vColour; }
