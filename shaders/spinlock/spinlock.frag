// Per-pixel mutual exclusion for fragment insertion (Brüll 2018, section 4.2): every fragment
// appends (value, layer) to its pixel's array and bumps the pixel's count inside a critical
// section guarded by
//   VARIANT_NAIVE         Listing 4.1: spin until the lock is taken, then insert (can deadlock a
//                         SIMT GPU: the lanes that lost wait for the lane that won, forever)
//   VARIANT_LOOP          Listing 4.2: the critical section inside the spin loop
//   VARIANT_HELPER_GUARD  Listing 4.3: Listing 4.2 skipped by helper invocations
//   VARIANT_INTERLOCK_ARB / _NV / _INTEL   the hardware's fragment shader interlock (ordering)
//   VARIANT_NO_RELEASE    deliberately broken: Listing 4.2 that never releases the lock
// Every spin loop gives up after SPIN_CAP attempts, so no variant can hang a real GPU; a
// fragment that gives up counts itself in cappedUpdates and its insertion is lost.
#if defined(VARIANT_INTERLOCK_ARB)
#extension GL_ARB_fragment_shader_interlock : require
#elif defined(VARIANT_INTERLOCK_NV)
#extension GL_NV_fragment_shader_interlock : require
#elif defined(VARIANT_INTERLOCK_INTEL)
#extension GL_INTEL_fragment_shader_ordering : require
#endif
#include "../common/oitbench.glsl"
#include "../storage/storage.glsl"
#include "bindings.h"

#if defined(VARIANT_INTERLOCK_ARB) || defined(VARIANT_INTERLOCK_NV)
layout(pixel_interlock_ordered) in;
#endif

uniform int zero;       // always 0; unknown to the compiler
uniform int layerBase;  // layers of earlier draws
flat in int layer;

layout(r32ui, binding = SPINLOCK_LOCK_IMAGE_UNIT) coherent uniform uimage2D locks;
layout(r32ui, binding = SPINLOCK_COUNT_IMAGE_UNIT) coherent uniform uimage2D counts;
layout(std430, binding = SPINLOCK_STATS_BINDING) buffer SpinStats { uint cappedUpdates; };

// The same function as spin_value() in micro/experiments/spinlock.cpp.
uint spin_value(ivec2 p, int l) { return (uint(p.x) * 2654435761u) ^ (uint(p.y) * 40503u) ^ (uint(l) * 2246822519u); }

// The critical section: a plain (non-atomic) read-modify-write of the count and the array.
void insert(ivec2 p, uvec2 node) {
  uint c = imageLoad(counts, p).x;
  if (c < uint(STORAGE_NODES)) STORAGE_STORE(p, int(c), node);
  imageStore(counts, p, uvec4(c + 1u));
}

// Helper invocations' atomics have no effect, so only real fragments are counted.
void record_capped() { atomicAdd(cappedUpdates, 1u); }

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  int l = layerBase + layer;
  uvec2 node = uvec2(spin_value(p, l) + uint(oitbench_fault_hang(zero)), uint(l));
#ifdef OITBENCH_FAULT_WRONG_RESULT
  if (p == ivec2(1, 1) && l == 0) node.x += 1u;  // one entry off by one: the validator must notice
#endif

#if defined(VARIANT_NAIVE)
  uint spins = 0u;
  while (imageAtomicCompSwap(locks, p, 0u, 1u) != 0u && ++spins < uint(SPIN_CAP)) {}
  if (spins < uint(SPIN_CAP)) {
    insert(p, node);
    memoryBarrier();
    imageAtomicExchange(locks, p, 0u);
  } else {
    record_capped();
  }

#elif defined(VARIANT_LOOP) || defined(VARIANT_HELPER_GUARD) || defined(VARIANT_NO_RELEASE)
#if defined(VARIANT_HELPER_GUARD)
  if (!gl_HelperInvocation) {
#endif
    bool keepWaiting = true;
    for (uint spins = 0u; keepWaiting && spins < uint(SPIN_CAP); ++spins) {
      if (imageAtomicCompSwap(locks, p, 0u, 1u) == 0u) {
        insert(p, node);
        memoryBarrier();
#if !defined(VARIANT_NO_RELEASE)
        imageAtomicExchange(locks, p, 0u);
#endif
        keepWaiting = false;
      }
    }
    if (keepWaiting) record_capped();
#if defined(VARIANT_HELPER_GUARD)
  }
#endif

#elif defined(VARIANT_INTERLOCK_ARB)
  beginInvocationInterlockARB();
  insert(p, node);
  endInvocationInterlockARB();
#elif defined(VARIANT_INTERLOCK_NV)
  beginInvocationInterlockNV();
  insert(p, node);
  endInvocationInterlockNV();
#elif defined(VARIANT_INTERLOCK_INTEL)
  beginFragmentShaderOrderingINTEL();  // orders everything after it; there is no end
  insert(p, node);
#else
#error "define one VARIANT_* (see the header of this file)"
#endif
}
