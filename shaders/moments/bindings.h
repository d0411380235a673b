// Texture units of MBOIT's passes (shaders/moments/). Only #defines: valid C++ and GLSL.
#ifndef OITBENCH_MOMENTS_BINDINGS_H
#define OITBENCH_MOMENTS_BINDINGS_H

#define MOMENTS_B0_UNIT 0     // the zeroth moment (total absorbance), R32F / R16F
#define MOMENTS_LOW_UNIT 1    // b1..b4, RGBA32F / RGBA16F
#define MOMENTS_HIGH_UNIT 2   // b5..b6 (RG) or b5..b8 (RGBA), 6 and 8 moments only
#define MOMENTS_ACCUM_UNIT 3  // the weighted colour pass's sum, RGBA32F

#endif
