// Pass 1 of the per-pixel array techniques: every fragment is inserted into its pixel's n nodes
// under the per-pixel spinlock of Listing 4.3 (helper invocations skip it; the spin gives up after
// SPIN_CAP tries and counts itself, so a lost insertion is reported, never a hang).
//   TECH_MLAB   Listing 3.1: one bubble pass, merge the last two nodes, store all n
//   TECH_UMLAB  Listing 5.1 + 5.2: unsorted, merge the two farthest, store at most two nodes
//   TECH_AT     section 3.6: sorted absolute transmittance, rect metric, underestimation
//   TECH_HAT    section 6.3: AT with the height metric (Eq. 6.1)
//   TECH_UAT    section 6.1: unsorted relative transmittance, sorted in registers, rect metric
//   TECH_UHAT   section 6.4, Listing 6.1: unsorted relative transmittance, height metric against an
//               exponential fit of the visibility function
//   TECH_HT     hybrid transparency's core (Maule et al. 2013): a k-buffer of the n nearest
//               fragments whole (RGBA8 colour, depth), in (depth, colour) order; a fragment pushed
//               out goes to the tail, which approx/ht_tail.frag accumulates in a second pass
//   TECH_FIRST_K HTGS's K-only mode (Hahlbohm et al. 2025): HT's core alone, the fragments it pushes out
//               dropped
//   TECH_WINDOW_SORT a StopThePop-style windowed sort (Radl et al. 2024): the splats drawn in the global
//               order, a sorted window of the pending fragments per pixel whose nearest is blended as it
//               fills (window.glsl)
//   TECH_LAAT   section 6.2: UAT's relative nodes linked into a list (a link per node, a head
//               slot), walked instead of sorted; only the changed nodes are written back
// Each technique's insertion is its own file in insert/ (against insert/api.glsl), chosen below.
// SYNC_INTERLOCK replaces the spinlock by ARB_fragment_shader_interlock (ordered: the insertion
// order becomes the submission order on any GPU; llvmpipe lacks it and reports `unsupported`).
// APPROX_UNGUARDED removes the numeric guards (UHAT's divisions and logarithm, HAT's division):
// the hard-case tests prove the guards matter.
#if defined(SYNC_INTERLOCK)
#extension GL_ARB_fragment_shader_interlock : require
#endif
#include "../common/oitbench.glsl"
#include "../storage/storage.glsl"
#include "nodes.glsl"
#include "../scene/fragment.glsl"
#include "bindings.h"
// The opaque effect's depth test must come before the node stores (a hidden fragment is never
// inserted); without a depth attachment this changes nothing.
layout(early_fragment_tests) in;

uniform int zero;
#if defined(SYNC_INTERLOCK)
layout(pixel_interlock_ordered) in;
#endif

layout(r32ui, binding = APPROX_LOCK_IMAGE_UNIT) coherent uniform uimage2D locks;
layout(std430, binding = APPROX_STATS_BINDING) buffer ApproxStats { uint cappedUpdates; };

#if defined(APPROX_UNGUARDED)
#define GUARD(x, lo) (x)
#else
#define GUARD(x, lo) max(x, lo)
#endif

// The technique's insertion: one file per technique against insert/api.glsl.
#include "insert/api.glsl"
// HT's, FIRST-K's and WINDOW-SORT's k-buffer, included here where all three reach it (the assembler emits
// a file once, where first named).
#include "insert/kbuffer.glsl"
#if defined(TECH_MLAB)
#include "insert/mlab.glsl"
#elif defined(TECH_UMLAB)
#include "insert/umlab.glsl"
#elif defined(TECH_AT) || defined(TECH_HAT)
// One sorted insertion, the metric its own file (the assembler emits a file once: at_family.glsl
// is included here, where both techniques reach it).
#include "insert/at_family.glsl"
#if defined(TECH_AT)
#include "insert/at.glsl"
#else
#include "insert/hat.glsl"
#endif
#elif defined(TECH_UAT)
#include "insert/uat.glsl"
#elif defined(TECH_UHAT)
#include "insert/uhat.glsl"
#elif defined(TECH_LAAT)
#include "insert/laat.glsl"
#elif defined(TECH_HT) || defined(TECH_FIRST_K)
#include "insert/ht.glsl"
#elif defined(TECH_WINDOW_SORT)
#include "insert/window.glsl"
#else
#error "define TECH_MLAB, TECH_UMLAB, TECH_AT, TECH_HAT, TECH_UAT, TECH_UHAT, TECH_LAAT, TECH_HT, TECH_FIRST_K or TECH_WINDOW_SORT"
#endif

void main() {
  SceneFragment f = scene_fragment();
  vec4 c = scene_fragment_rgba8(f);
  ivec2 p = ivec2(gl_FragCoord.xy);
  float z = f.depth + oitbench_fault_hang(zero);
  vec4 ct = vec4(c.rgb * c.a, 1.0 - c.a);  // (premultiplied colour C, transmittance T)
#if defined(SYNC_INTERLOCK)
  beginInvocationInterlockARB();
  insert(p, c, ct, z);
  endInvocationInterlockARB();
#else
  if (!gl_HelperInvocation) {
    bool waiting = true;
    for (uint spins = 0u; waiting && spins < uint(SPIN_CAP); ++spins) {
      if (imageAtomicCompSwap(locks, p, 0u, 1u) == 0u) {
        insert(p, c, ct, z);
        memoryBarrier();
        imageAtomicExchange(locks, p, 0u);
        waiting = false;
      }
    }
    if (waiting) atomicAdd(cappedUpdates, 1u);
  }
#endif
}
