// SLAB's per-pixel layers (Wyman, HPG 2016, section 5): up to SLAB_LAYERS (depth, coverage mask,
// colour) in depth order, front first; the masks are disjoint, each holding the samples where its
// layer is the nearest surface, so an empty mask is an empty slot and a layer never lies behind
// samples a nearer one covers. micro/oit/slab/slab_model.cpp does the same on the CPU.
//   slab_mask    a fragment's hashed coverage of SLAB_SAMPLES samples: stochastic transparency's
//                (shaders/stochastic/hash.glsl, first pass), written so that 32 samples shift safely
//   slab_insert  one fragment: it loses the samples nearer layers hold (depth less or equal: the
//                earlier arrival wins a tie), and is dropped when none is left; the layers behind it
//                lose the samples it takes, and those left with none are dropped; when SLAB_LAYERS + 1
//                remain, the two farthest merge (the union of their samples, the nearer one's depth,
//                the colours averaged by their sample counts)
#ifndef SLAB_LAYERS_GLSL
#define SLAB_LAYERS_GLSL
#include "../stochastic/hash.glsl"

uint slab_mask(uint frame_seed, uvec2 pixel, uint primitive, uint alpha_byte) {
  uint s = uint(SLAB_SAMPLES);
  uint h = pcg_hash(pcg_hash(pcg_hash(pcg_hash(pixel.x) + pixel.y) + primitive) ^ frame_seed);
  uint k = (alpha_byte * s * 65536u / 255u + (h & 0xFFFFu)) >> 16;
  uint r = (h >> 16) % s;
  uint all = s >= 32u ? 0xFFFFFFFFu : (1u << s) - 1u;
  uint run = k >= 32u ? 0xFFFFFFFFu : (1u << k) - 1u;
  return r == 0u ? run : ((run << r) | (run >> (s - r))) & all;
}

struct SlabLayer {
  float depth;
  uint mask;
  uint colour;
};

// The two layers' samples as one, the nearer's depth, the colours weighted by their sample counts.
SlabLayer slab_merge(SlabLayer a, SlabLayer b) {
  float na = float(bitCount(a.mask)), nb = float(bitCount(b.mask));
  vec3 c = (unpackUnorm4x8(a.colour).rgb * na + unpackUnorm4x8(b.colour).rgb * nb) / (na + nb);
  return SlabLayer(a.depth, a.mask | b.mask, packUnorm4x8(vec4(c, 0.0)));
}

// `layers` holds `count` (at most SLAB_LAYERS) layers; afterwards it holds the new count.
void slab_insert(inout SlabLayer layers[SLAB_LAYERS + 1], inout int count, SlabLayer f) {
  int pos = 0;
  while (pos < count && layers[pos].depth <= f.depth) f.mask &= ~layers[pos++].mask;
  if (f.mask == 0u) return;
  SlabLayer out_layers[SLAB_LAYERS + 1] = layers;
  int n = pos;
  out_layers[n++] = f;
  for (int j = pos; j < count; ++j) {
    SlabLayer l = layers[j];
    l.mask &= ~f.mask;
    if (l.mask != 0u) out_layers[n++] = l;
  }
  if (n > SLAB_LAYERS) {
    out_layers[SLAB_LAYERS - 1] = slab_merge(out_layers[SLAB_LAYERS - 1], out_layers[SLAB_LAYERS]);
    n = SLAB_LAYERS;
  }
  layers = out_layers;
  count = n;
}

#endif
