// The splat path of shaders/scene/scene.vert (SPLATS): one instance a splat, four vertices a quad (a
// triangle strip) in window space bounding its 3 sigma (project.glsl), drawn at the mean's depth.
// Instances draw in submission order, or in the order of SPLAT_ORDER_BINDING (SPLAT_ORDERED: the
// global sort's). The fragment stage (fragment.glsl) evaluates the Gaussian at each pixel centre.
#include "splats.glsl"
#if defined(SPLAT_ORDERED)
layout(std430, binding = SPLAT_ORDER_BINDING) readonly buffer SplatOrder { uint splatOrder[]; };
#endif
uniform mat4 viewProj;
uniform vec2 splatViewport;  // pixels
flat out vec4 vSplatColour;  // (colour, opacity)
flat out vec3 vSplatConic;
flat out vec2 vSplatCentre;
flat out float vSplatViewDepth;
flat out uint vSplatPrimitive;  // 2 x splat + the quad's triangle (gl_PrimitiveID restarts every instance)
flat out vec3 vSplatMean;
#if defined(SPLAT_DEPTH_RAY_MAX)
flat out mat3 vSplatPrecision;  // Sigma^-1 in world space
flat out mat4 vSplatInverseViewProj;
#endif

void main() {
#if defined(SPLAT_ORDERED)
  uint index = splatOrder[gl_InstanceID];
#else
  uint index = uint(gl_InstanceID);
#endif
  Splat s = load_splat(index);
  SplatProjection p = project_splat(s.position, splat_covariance(s.scale, s.rotation), viewProj, splatViewport);
  vSplatColour = vec4(s.colour, s.opacity);
  vSplatConic = p.conic;
  vSplatCentre = p.centre;
  vSplatViewDepth = p.view_depth;
  vSplatPrimitive = 2u * index;
  vSplatMean = s.position;
#if defined(SPLAT_DEPTH_RAY_MAX)
  mat3 r = splat_rotation(s.rotation);
  vec3 inv = 1.0 / (s.scale * s.scale);
  vSplatPrecision = r * mat3(inv.x, 0.0, 0.0, 0.0, inv.y, 0.0, 0.0, 0.0, inv.z) * transpose(r);
  vSplatInverseViewProj = inverse(viewProj);
#endif
  vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
  vec2 window = p.centre + corner * p.radius;
  // a culled splat's four vertices coincide outside the clip volume: no fragment
  gl_Position = p.visible ? vec4(window / splatViewport * 2.0 - 1.0, p.ndc_depth, 1.0) : vec4(2.0, 2.0, 2.0, 1.0);
}
