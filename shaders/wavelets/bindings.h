// Texture units of WOIT's passes (shaders/wavelets/). Only #defines: valid C++ and GLSL.
#ifndef OITBENCH_WAVELETS_BINDINGS_H
#define OITBENCH_WAVELETS_BINDINGS_H

#define WAVELETS_COEFFS_UNIT 0  // the coefficients, 4 per layer of an RGBA32F / RGBA16F 2D array
#define WAVELETS_ACCUM_UNIT 1   // the weighted colour pass's sum, RGBA32F

#endif
