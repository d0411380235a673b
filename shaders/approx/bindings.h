// Binding points of the approximate techniques beside the storage include's (shaders/storage/
// bindings.h uses buffer binding 0 and image unit 0). Only #defines: valid C++ and GLSL.
#ifndef OITBENCH_APPROX_BINDINGS_H
#define OITBENCH_APPROX_BINDINGS_H

#define APPROX_LOCK_IMAGE_UNIT 1  // r32ui per-pixel spinlocks
#define APPROX_STATS_BINDING 1    // SSBO: capped (lost) insertions
#define APPROX_ACCUM_UNIT 2       // texture unit: the AT blend pass's or WBOIT's accumulation
#define APPROX_REVEAL_UNIT 3      // texture unit: WBOIT's revealage (GLOBAL-SORT's early stop: its transmittance)
#define APPROX_TRANSMITTANCE_IMAGE_UNIT 2  // r32f: GLOBAL-SORT's early stop, each pixel's transmittance

#endif
