// Stochastic transparency's coverage (Enderton et al. 2010, section 3): a fragment of alpha a covers
// k = floor(a S + u) of the S samples, u uniform in [0, 1), as a run of k consecutive samples rotated
// by a random offset, so each sample is covered with probability a (integer arithmetic on the alpha
// byte, so micro/oit/moments/moment_model.cpp's stochastic_mask computes the same masks bit for bit).
#ifndef STOCHASTIC_HASH_GLSL
#define STOCHASTIC_HASH_GLSL

uint pcg_hash(uint v) {  // PCG-RXS-M-XS (Jarzynski & Olano 2020, "Hash Functions for GPU Rendering")
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

uint stochastic_mask(uint frame_seed, uint pass_index, uvec2 pixel, uint primitive, uint alpha_byte, uint samples) {
  uint h = pcg_hash(pcg_hash(pcg_hash(pcg_hash(pixel.x) + pixel.y) + primitive) ^ (frame_seed + pass_index * 0x9E3779B9u));
  uint k = (alpha_byte * samples * 65536u / 255u + (h & 0xFFFFu)) >> 16;
  uint r = (h >> 16) % samples;
  uint all = (1u << samples) - 1u, run = (1u << k) - 1u;
  return ((run << r) | (run >> (samples - r))) & all;
}

#endif
