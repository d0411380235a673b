// Binding points of STOCHASTIC's passes (shaders/stochastic/). Only #defines: valid C++ and GLSL.
#ifndef OITBENCH_STOCHASTIC_BINDINGS_H
#define OITBENCH_STOCHASTIC_BINDINGS_H

#define STOCHASTIC_CAPTURE_BINDING 0  // SSBO: the MSAA coverage capture (count, then 5 words a fragment)
#define STOCHASTIC_CAPTURE_WORDS 5    // pixel, gl_PrimitiveID, gl_SampleMaskIn[0], colour, depth bits
#define STOCHASTIC_ACCUM_UNIT 0       // texture unit: the MSAA accumulation (RGBA32F)
#define STOCHASTIC_TOTAL_UNIT 1       // texture unit: the total transmittance (R32F)

#endif
