// The transparent fragment of layer l at pixel p, shared by capture.frag and the CPU reference
// (stencil_fragment() in micro/experiments/stencil.cpp): RGBA8 colour packed in x (alpha in the
// top byte) and a depth key in y that is a per-pixel permutation of the layers, so the resolve
// that sorts by depth has real work to do.
#ifndef OITBENCH_STENCIL_FRAGMENT_GLSL
#define OITBENCH_STENCIL_FRAGMENT_GLSL

uvec2 stencil_fragment(ivec2 p, int l, int layers) {
  uint h = (uint(p.x) * 2654435761u) ^ (uint(p.y) * 40503u) ^ (uint(l) * 2246822519u);
  uint alpha = 32u + (h >> 25);  // 32..159 of 255: every layer shows through
  uint colour = (h & 0x00ffffffu) | (alpha << 24);
  uint depth = uint((l + 3 * p.x + 7 * p.y) % layers);
  return uvec2(colour, depth);
}

#endif
