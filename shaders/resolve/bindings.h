// Binding points of the exact techniques' resolve passes beside the captured fragments'
// (shaders/capture/bindings.h). Only #defines: valid C++ and GLSL.
#ifndef OITBENCH_RESOLVE_BINDINGS_H
#define OITBENCH_RESOLVE_BINDINGS_H

#define OIT_RESOLVED_IMAGE_UNIT 4  // image: the compute resolve's output (resolve.comp)
#define BMA_HISTOGRAM_BINDING 0    // SSBO: pixels per depth interval (bma_count.comp)

#endif
