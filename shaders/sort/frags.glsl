// The sort experiment's binding of the sort library's element API (shaders/sorts/api.glsl) to the
// per-pixel fragment array, and the only place that knows where that array lives. It holds no
// sort: algorithms.glsl picks one from shaders/sorts/. A fragment is 64 bits as in Knowles 2014 and
// Brüll 2018: x = the 32-bit depth key (float bits), y = RGBA8 colour packed into 32 bits; the
// order is ascending depth key (SORT_GT: a's key > b's key; equal keys are ties).
// The insert experiment (shaders/insert/) uses the same binding.
//
// Injected defines:
//   SORT_N            elements per pixel (the array's declared size)
//   SORT_N_LOG2       ceil(log2(SORT_N)), for the power-of-two networks
//   MEMORY_REGISTERS  SORT_SIZE is the constant SORT_N: loops unroll, every index becomes a
//                     constant and the compiler may keep `frags` in registers (Knowles 2014 Listing 2, right)
//   MEMORY_LOCAL      SORT_SIZE is the uniform `count` (== SORT_N, unknown to the compiler): loops
//                     stay loops, indices stay dynamic and `frags` must live in indexable local memory
//                     (Listing 2, left) - the way a resolve with a per-pixel fragment count is written
//   SORT_PACKED_KEY64 (the register networks, where GL_ARB_gpu_shader_int64 exists: the entry points
//                     enable it) a fragment read as one 64-bit key, depth key high and payload low,
//                     so the network's compare-exchange is a min and a max (SORT_FIRST, SORT_LAST)
#ifndef SORT_FRAGS_GLSL
#define SORT_FRAGS_GLSL

#if !defined(SORT_N) || !defined(SORT_N_LOG2)
#error "define SORT_N and SORT_N_LOG2"
#endif

#include "../sorts/api.glsl"
#include "bindings.h"

layout(std430, binding = SORT_BENCH_IN_BINDING) readonly buffer InFrags { uvec2 in_frags[]; };
layout(std430, binding = SORT_BENCH_OUT_BINDING) writeonly buffer OutFrags { uvec2 out_frags[]; };

uniform int count;       // == SORT_N
uniform int count_log2;  // == SORT_N_LOG2
uniform int zero;        // == 0
uniform ivec2 image_size;

#define SORT_T uvec2
// A global, never a function argument: GLSL copies array arguments in and out (Knowles 2014, 2.7).
SORT_T frags[SORT_N];

#define SORT_AT(i) frags[i]
#define SORT_KEY(v) uintBitsToFloat((v).x)
#define SORT_GT(a, b) (SORT_KEY(a) > SORT_KEY(b))
#if defined(SORT_PACKED_KEY64)
// Keys are floats >= 0, so their bits order like them; the payload breaks ties (any order of equal
// keys is a sorted order here).
#define SORT_KEY64_(v) packUint2x32((v).yx)
#define SORT_FIRST(a, b) unpackUint2x32(min(SORT_KEY64_(a), SORT_KEY64_(b))).yx
#define SORT_LAST(a, b) unpackUint2x32(max(SORT_KEY64_(a), SORT_KEY64_(b))).yx
#endif

#if defined(MEMORY_REGISTERS)
#define SORT_SIZE SORT_N
#define SORT_SIZE_LOG2 SORT_N_LOG2
#elif defined(MEMORY_LOCAL)
#define SORT_SIZE count
#define SORT_SIZE_LOG2 count_log2
#else
#error "define MEMORY_REGISTERS or MEMORY_LOCAL"
#endif

// After SORT_N, before any sort: SORT_EACH_INDEX for insertion's Table A.1 writes.
#include "../sorts/unroll.glsl"

int frags_pixel_index(ivec2 p) { return p.y * image_size.x + p.x; }

void frags_load(ivec2 p) {
  int base = frags_pixel_index(p) * SORT_N;
  for (int i = 0; i < SORT_SIZE; ++i) SORT_AT(i) = in_frags[base + i];
}

void frags_store(ivec2 p) {
  int base = frags_pixel_index(p) * SORT_N;
  for (int i = 0; i < SORT_SIZE; ++i) out_frags[base + i] = SORT_AT(i);
}

#endif
