// Binding points of the depth peeling passes (micro/oit/peel/peel_case.cpp, shaders/peel/). Only
// #defines: valid C++ and GLSL.
#ifndef OITBENCH_PEEL_BINDINGS_H
#define OITBENCH_PEEL_BINDINGS_H

#define PEEL_PREV_MINMAX_UNIT 0  // texture unit: the layers peeled last time, (-front depth, back depth)
#define PEEL_NEXT_MINMAX_UNIT 1  // texture unit: the depths of the layers this iteration peels
#define PEEL_FRONT_ACCUM_UNIT 2  // texture unit: front-to-back composite (premultiplied rgb, transmittance)
#define PEEL_BACK_ACCUM_UNIT 3   // texture unit: back-to-front composite (premultiplied rgb, coverage)
#define PEEL_PREV_FRONT_IMAGE 0  // r32ui image units: the colour key of each peeled layer
#define PEEL_NEXT_FRONT_IMAGE 1
#define PEEL_PREV_BACK_IMAGE 2
#define PEEL_NEXT_BACK_IMAGE 3

#endif
