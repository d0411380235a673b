// What lies behind the transparent layers, for every resolve and composite: the scene's constant
// `background`, or with the opaque effect (OPAQUE_BACKDROP, micro/oit/scene/scene_passes.cpp) the
// opaque pass's colour at the pixel, the opaque objects drawn over the background.
//   backdrop_colour(pixel)        the colour the transparent layers are composited over
//   opaque_hides(pixel, depth)    whether the opaque surface at the pixel hides a fragment at this
//                                 window depth (false without the effect), for a technique that
//                                 cannot use the opaque depth buffer's early depth test; it needs
//                                 OPAQUE_DEPTH_SAMPLER (ScenePasses::depth_sampler_defines) and must
//                                 not run where that depth is attached to the framebuffer
#include "bindings.h"
uniform vec3 background;
#ifdef OPAQUE_BACKDROP
layout(binding = OIT_BACKDROP_UNIT) uniform sampler2D opaqueColour;
vec3 backdrop_colour(ivec2 pixel) { return texelFetch(opaqueColour, pixel, 0).rgb; }
#else
vec3 backdrop_colour(ivec2 pixel) { return background; }
#endif
#if defined(OPAQUE_BACKDROP) && defined(OPAQUE_DEPTH_SAMPLER)
layout(binding = OIT_OPAQUE_DEPTH_UNIT) uniform sampler2D opaqueDepth;
bool opaque_hides(ivec2 pixel, float depth) { return !(depth < texelFetch(opaqueDepth, pixel, 0).r); }
#else
bool opaque_hides(ivec2 pixel, float depth) { return false; }
#endif
