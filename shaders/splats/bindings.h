// Binding points of the splat rasteriser (shaders/splats/, micro/oit/splats/gpu_splats.cpp) and of the
// global sort's passes (shaders/splats/keys.comp). Storage-buffer points no technique's geometry pass
// uses, so a splat draw coexists with every technique's own buffers. Only #defines: valid C++ and GLSL.
#ifndef OITBENCH_SPLATS_BINDINGS_H
#define OITBENCH_SPLATS_BINDINGS_H
#define SPLATS_BINDING 6       // SSBO: the splats, SPLAT_WORDS vec4 each (gpu_splats.cpp's layout)
#define SPLAT_ORDER_BINDING 7  // SSBO (SPLAT_ORDERED): the order the instances draw the splats in
#define SPLAT_WORDS 4          // vec4s per splat: (position, opacity), (scale, 0), rotation (w, x, y, z), (colour, 0)
// keys.comp (its own dispatch): the global sort's input pairs (micro/oit/scene/radix_sort.hpp)
#define SPLAT_KEYS_BINDING 0         // SSBO: out, one key a splat
#define SPLAT_KEY_INDICES_BINDING 1  // SSBO: out, the identity order
#endif
