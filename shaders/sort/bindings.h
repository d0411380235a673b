// Binding points of the per-pixel fragment arrays (frags.glsl) the sort and insert experiments
// (micro/experiments/sort.cpp, insert.cpp) fill and read back. Only #defines: valid C++ and GLSL.
#ifndef OITBENCH_SORT_BINDINGS_H
#define OITBENCH_SORT_BINDINGS_H

#define SORT_BENCH_IN_BINDING 0   // SSBO: each pixel's SORT_N input fragments
#define SORT_BENCH_OUT_BINDING 1  // SSBO: out, each pixel's sorted (or inserted) fragments

#endif
