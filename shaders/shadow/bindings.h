// Binding points and constants of the self-shadowing opacity map (micro/oit/scene/shadow_map.cpp), beside
// the fragment storage's (image units 0-3) and the approximate techniques' (texture units 2-3).
// Only #defines: valid C++ and GLSL.
#ifndef OITBENCH_SHADOW_BINDINGS_H
#define OITBENCH_SHADOW_BINDINGS_H

#define SHADOW_MAP_UNIT 8           // texture unit: the opacity map (sampler3D) every shaded fragment reads
#define SHADOW_PREFIX_IMAGE_UNIT 4  // image unit: the map during the prefix over its layers
// slice_ranges.comp: the map pass's indirect draws from the sorted slice keys (the primitives' sort is
// shaders/lines/, with its own points in shaders/lines/bindings.h)
#define SLICE_RANGES_SORTED_KEYS_BINDING 0  // SSBO: the sorted slice keys
#define SLICE_RANGES_BOUNDS_BINDING 1       // SSBO: [2 key] first, [2 key + 1] end of each key's run; zeroed
#define SLICE_RANGES_COMMANDS_BINDING 2     // SSBO: out, one DrawElementsIndirectCommand (5 uints) per slice
// Alpha is capped here so that a fully opaque primitive's optical depth -log(1 - alpha) stays finite
// (transmittance behind it exp(-6.9) = 0.001).
#define SHADOW_MAX_ALPHA 0.999

#endif
