// Every technique's geometry passes: transforms the scene mesh (micro/oit/scene/gpu_mesh.cpp's vertex
// layout); vWorld is the world position the shading (shaders/scene/shade.glsl) needs. With SPLATS the
// scene is Gaussian splats, and this is the splat rasteriser's vertex stage (shaders/splats/vertex.glsl).
// What the fragment stage reads of either: shaders/scene/fragment.glsl.
#include "../common/oitbench.glsl"
#if defined(SPLATS)
#include "../splats/vertex.glsl"
#else
layout(location = 0) in vec3 position;
layout(location = 1) in vec4 colour;
layout(location = 2) in vec2 uv;
layout(location = 3) in float soft;
uniform mat4 viewProj;
out vec4 vColour;
out vec2 vUv;
out float vSoft;
out vec3 vWorld;
out float vViewDepth;  // clip w: -z in view space for a perspective projection (frag_depth=view)
void main() {
  vColour = colour;
  vUv = uv;
  vSoft = soft;
  vWorld = position;
  gl_Position = viewProj * vec4(position, 1.0);
  vViewDepth = gl_Position.w;
}
#endif
