// The shading every captured scene fragment goes through (capture.frag and the approximate
// techniques' fragment shaders), so that an effect that changes a fragment's colour is written once:
// SELF_SHADOWING scales the colour by the light's transmittance at the fragment (the opacity shadow
// map, shaders/shadow/transmittance.glsl) down to the light's ambient floor; otherwise the identity.
#ifndef OIT_SHADE_GLSL
#define OIT_SHADE_GLSL
#ifdef SELF_SHADOWING
#include "../shadow/transmittance.glsl"
uniform float shadowAmbient;
#endif

vec4 shade_fragment(vec4 colour, vec3 world) {
#ifdef SELF_SHADOWING
  colour.rgb *= mix(shadowAmbient, 1.0, shadow_transmittance(world));
#endif
  return colour;
}

#endif
