// Binding points of SLAB's passes (shaders/slab/). Only #defines: valid C++ and GLSL.
#ifndef OITBENCH_SLAB_BINDINGS_H
#define OITBENCH_SLAB_BINDINGS_H

#define SLAB_LAYERS_BINDING 0   // SSBO: SLAB_LAYERS layers a pixel, SLAB_LAYER_WORDS words a layer
#define SLAB_LAYER_WORDS 3      // depth bits, coverage mask (0: empty), colour (packUnorm4x8 RGB)
#define SLAB_STATS_BINDING 1    // SSBO: insertions that gave up on the spinlock
#define SLAB_LOCK_IMAGE_UNIT 2  // r32ui per-pixel spinlocks
#define SLAB_SAMPLES_MAX 32     // coverage samples a mask holds at most (one uint)

#endif
