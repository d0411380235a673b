// SLAB's one geometry pass: every fragment draws its hashed coverage mask from its alpha and is
// inserted into its pixel's layers (layers.glsl) under a per-pixel spinlock, as the approximate
// techniques' insert.frag does (helper invocations skip it; the spin gives up after SPIN_CAP tries
// and counts itself, so a lost insertion is reported, never a hang).
#include "../common/oitbench.glsl"
#include "../approx/nodes.glsl"
#include "bindings.h"
#include "layers.glsl"
// The scene effects: the opaque depth tested here (opaque_hides), the shading (self-shadowing).
#include "../scene/backdrop.glsl"
// a splat fragment without alpha comes back at alpha 0 (mask 0: returns before the lock), not discarded
#define SPLAT_NO_DISCARD
#include "../scene/fragment.glsl"
uniform uint frameSeed;
uniform int width;
uniform int zero;
layout(r32ui, binding = SLAB_LOCK_IMAGE_UNIT) coherent uniform uimage2D locks;
layout(std430, binding = SLAB_LAYERS_BINDING) coherent buffer Layers { uint words[]; };
layout(std430, binding = SLAB_STATS_BINDING) buffer SlabStats { uint cappedUpdates; };

void insert_fragment(ivec2 p, SlabLayer f) {
  uint base = uint(p.y * width + p.x) * uint(SLAB_LAYERS * SLAB_LAYER_WORDS);
  SlabLayer layers[SLAB_LAYERS + 1];
  int count = 0;
  for (int i = 0; i < SLAB_LAYERS; ++i) {
    uint b = base + uint(i * SLAB_LAYER_WORDS);
    layers[i] = SlabLayer(uintBitsToFloat(words[b]), words[b + 1u], words[b + 2u]);
    if (layers[i].mask != 0u) count = i + 1;
  }
  layers[SLAB_LAYERS] = SlabLayer(0.0, 0u, 0u);
  int before = count;
  slab_insert(layers, count, f);
  for (int i = 0; i < max(count, before); ++i) {
    uint b = base + uint(i * SLAB_LAYER_WORDS);
    SlabLayer l = i < count ? layers[i] : SlabLayer(0.0, 0u, 0u);
    words[b] = floatBitsToUint(l.depth);
    words[b + 1u] = l.mask;
    words[b + 2u] = l.colour;
  }
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  SceneFragment frag = scene_fragment();
  float z = clamp(frag.depth, 0.0, 1.0) + oitbench_fault_hang(zero);
  if (opaque_hides(p, z)) return;
  vec4 c = scene_fragment_rgba8(frag);
  uint colour = packUnorm4x8(c);
  SlabLayer f = SlabLayer(z, slab_mask(frameSeed, uvec2(p), frag.primitive, colour >> 24), colour & 0xFFFFFFu);
  if (f.mask == 0u || gl_HelperInvocation) return;
  bool waiting = true;
  for (uint spins = 0u; waiting && spins < uint(SPIN_CAP); ++spins) {
    if (imageAtomicCompSwap(locks, p, 0u, 1u) == 0u) {
      insert_fragment(p, f);
      memoryBarrier();
      imageAtomicExchange(locks, p, 0u);
      waiting = false;
    }
  }
  if (waiting) atomicAdd(cappedUpdates, 1u);
}
