// SLAB's CPU model (slab.hpp): shaders/slab/layers.glsl and resolve.frag in C++, the merge's colour
// in float and rounded to 8 bits as packUnorm4x8 rounds, so only the resolve's float sums differ.
#include <algorithm>
#include <bit>
#include <cmath>

#include "core/parallel_rows.hpp"
#include "oit/reference/reference.hpp"
#include "oit/slab/slab.hpp"

namespace oitbench::oit {

namespace {
uint32_t pcg(uint32_t v) {  // PCG-RXS-M-XS, as shaders/stochastic/hash.glsl
  uint32_t state = v * 747796405u + 2891336453u;
  uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}
uint32_t unorm8(float v) { return static_cast<uint32_t>(std::nearbyint(std::clamp(v, 0.0f, 1.0f) * 255.0f)); }

SlabLayer merge(const SlabLayer& a, const SlabLayer& b) {
  const float na = static_cast<float>(std::popcount(a.mask)), nb = static_cast<float>(std::popcount(b.mask));
  glm::vec4 ca = unpack_rgba8(a.colour), cb = unpack_rgba8(b.colour);
  uint32_t c = 0;
  for (int k = 0; k < 3; ++k) c |= unorm8((ca[k] * na + cb[k] * nb) / (na + nb)) << (8 * k);
  return {a.depth, a.mask | b.mask, c};
}
}  // namespace

uint32_t slab_mask(uint32_t frame_seed, uint32_t x, uint32_t y, uint32_t primitive, uint32_t alpha_byte,
                   uint32_t samples) {
  uint32_t h = pcg(pcg(pcg(pcg(x) + y) + primitive) ^ frame_seed);
  // k = floor(alpha * samples + u), u uniform in [0, 1): each sample covered with probability alpha.
  uint32_t k = (alpha_byte * samples * 65536u / 255u + (h & 0xFFFFu)) >> 16;
  uint32_t r = (h >> 16) % samples;
  uint64_t all = (uint64_t{1} << samples) - 1u, run = (uint64_t{1} << k) - 1u;
  return static_cast<uint32_t>(((run << r) | (run >> (samples - r))) & all);
}

void slab_insert(std::vector<SlabLayer>& layers, int max_layers, SlabLayer f) {
  size_t pos = 0;
  while (pos < layers.size() && layers[pos].depth <= f.depth) f.mask &= ~layers[pos++].mask;
  if (f.mask == 0) return;
  std::vector<SlabLayer> out(layers.begin(), layers.begin() + static_cast<std::ptrdiff_t>(pos));
  out.push_back(f);
  for (size_t j = pos; j < layers.size(); ++j) {
    SlabLayer l = layers[j];
    l.mask &= ~f.mask;
    if (l.mask) out.push_back(l);
  }
  if (static_cast<int>(out.size()) > max_layers) {
    out[max_layers - 1] = merge(out[max_layers - 1], out[max_layers]);
    out.resize(static_cast<size_t>(max_layers));
  }
  layers = std::move(out);
}

std::vector<double> slab_model(const std::vector<CoverageFragment>& fragments, const Backdrop& bg, const SlabSetup& s) {
  const size_t pixels = static_cast<size_t>(s.width) * s.height;
  // Each pixel's fragments in the record's order (the order they reached it); pixels are independent, so
  // their rows are spread over the cores, each pixel's insertions made in that order.
  std::vector<std::vector<const CoverageFragment*>> by_pixel(pixels);
  for (const auto& f : fragments)
    if (f.pixel < pixels) by_pixel[f.pixel].push_back(&f);
  std::vector<double> out(pixels * 3);
  const size_t row = static_cast<size_t>(std::max(1, s.width));
  std::vector<std::vector<SlabLayer>> scratch(parallel_row_threads((pixels + row - 1) / row, s.threads));
  parallel_rows(pixels, row, s.threads, [&](unsigned thread, size_t px) {
    std::vector<SlabLayer>& layers = scratch[thread];
    layers.clear();
    const uint32_t x = static_cast<uint32_t>(px % static_cast<size_t>(s.width)),
                   y = static_cast<uint32_t>(px / static_cast<size_t>(s.width));
    for (const CoverageFragment* f : by_pixel[px])
      slab_insert(
          layers, s.layers,
          {f->depth, slab_mask(s.frame_seed, x, y, f->primitive, f->colour >> 24, s.samples), f->colour & 0xFFFFFFu});
    glm::dvec3 c(0.0);
    int covered = 0;
    for (const auto& l : layers) {
      const int n = std::popcount(l.mask);
      c += glm::dvec3(unpack_rgba8(l.colour)) * static_cast<double>(n);
      covered += n;
    }
    c = (c + glm::dvec3(bg.at(px)) * static_cast<double>(s.samples - covered)) / static_cast<double>(s.samples);
    for (int k = 0; k < 3; ++k) out[px * 3 + k] = c[k];
  });
  return out;
}

}  // namespace oitbench::oit
