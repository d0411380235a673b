// Binding points of the occupancy experiment (micro/experiments/occupancy.cpp, occupancy.frag).
// Only #defines: valid C++ and GLSL.
#ifndef OITBENCH_OCCUPANCY_BINDINGS_H
#define OITBENCH_OCCUPANCY_BINDINGS_H

#define OCCUPANCY_SLOTS_BINDING 0  // SSBO (OCCUPANCY_MEASURE): out-of-range warps, then one bit per warp slot

#endif
