// Binding points and constants of the self-shadowing opacity map (micro/oit/scene/shadow_map.cpp), beside
// the fragment storage's (image units 0-3) and the approximate techniques' (texture units 2-3).
// Only #defines: valid C++ and GLSL.
#ifndef OITBENCH_SHADOW_BINDINGS_H
#define OITBENCH_SHADOW_BINDINGS_H

#define SHADOW_MAP_UNIT 8           // texture unit: the opacity map (sampler3D) every shaded fragment reads
#define SHADOW_PREFIX_IMAGE_UNIT 4  // image unit: the map during the prefix over its layers
// Alpha is capped here so that a fully opaque primitive's optical depth -log(1 - alpha) stays finite
// (transmittance behind it exp(-6.9) = 0.001).
#define SHADOW_MAX_ALPHA 0.999

#endif
