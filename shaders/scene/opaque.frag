// The opaque effect's pass: the scene's opaque primitives drawn with an ordinary depth test into
// colour and depth (micro/oit/scene/scene_passes.cpp), shaded like every scene fragment (shade.glsl:
// self-shadowed where the scene has the effect). The transparent fragments are then captured
// against this depth and composited over this colour (shaders/scene/backdrop.glsl).
#include "../common/oitbench.glsl"
#include "shade.glsl"
in vec4 vColour;
in vec2 vUv;
in float vSoft;
in vec3 vWorld;
layout(location = 0) out vec4 fragColour;
// alpha 0: the backdrop is what lies behind; a resolve's alpha counts its own work (exact_case.cpp)
void main() { fragColour = vec4(shade_fragment(vec4(vColour.rgb, 1.0), vWorld).rgb, 0.0); }
