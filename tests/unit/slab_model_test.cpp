// SLAB's CPU model (micro/oit/slab/slab.hpp): the masks hold floor(alpha S + u) samples and reach 32
// samples without an undefined shift; an insertion keeps the layers' masks disjoint in depth order,
// drops what nearer layers cover, and merges the two farthest when the layers overflow.
#include <gtest/gtest.h>

#include <bit>

#include "oit/slab/slab.hpp"

namespace oitbench::oit {

namespace {
SlabLayer layer(float depth, uint32_t mask, uint32_t colour) { return {depth, mask, colour}; }
}  // namespace

TEST(SlabModel, MasksHoldAlphaTimesSamplesAndReachThirtyTwo) {
  for (uint32_t s : {4u, 8u, 16u, 32u}) {
    const uint64_t all = (uint64_t{1} << s) - 1;
    EXPECT_EQ(slab_mask(7, 3, 5, 11, 255, s), all) << s;
    EXPECT_EQ(slab_mask(7, 3, 5, 11, 0, s), 0u) << s;
    for (uint32_t prim = 0; prim < 64; ++prim) {
      const int bits = std::popcount(slab_mask(1234, 9, 2, prim, 128, s));
      EXPECT_TRUE(bits == static_cast<int>(s / 2) || bits == static_cast<int>(s / 2) + 1) << s << " " << bits;
    }
  }
}

TEST(SlabModel, NearerLayersTakeTheirSamplesAndEmptyLayersGo) {
  std::vector<SlabLayer> l;
  slab_insert(l, 4, layer(0.5f, 0b0011, 1));
  slab_insert(l, 4, layer(0.7f, 0b0110, 2));  // behind: keeps only sample 2
  ASSERT_EQ(l.size(), 2u);
  EXPECT_EQ(l[1].mask, 0b0100u);
  slab_insert(l, 4, layer(0.9f, 0b0111, 3));  // entirely behind nearer samples: dropped
  EXPECT_EQ(l.size(), 2u);
  slab_insert(l, 4, layer(0.1f, 0b0111, 4));  // in front of both: they are left with nothing
  ASSERT_EQ(l.size(), 1u);
  EXPECT_EQ(l[0].colour, 4u);
}

TEST(SlabModel, OverflowMergesTheTwoFarthestWeightedBySamples) {
  std::vector<SlabLayer> l;
  slab_insert(l, 1, layer(0.2f, 0b0001, 0x0000FF));  // red, one sample
  slab_insert(l, 1, layer(0.4f, 0b1110, 0x00FF00));  // green, three samples behind: merged
  ASSERT_EQ(l.size(), 1u);
  EXPECT_EQ(l[0].mask, 0b1111u);
  EXPECT_FLOAT_EQ(l[0].depth, 0.2f);
  EXPECT_EQ(l[0].colour & 0xFFu, 64u);          // 255 / 4
  EXPECT_EQ((l[0].colour >> 8) & 0xFFu, 191u);  // 255 * 3 / 4
}

}  // namespace oitbench::oit
