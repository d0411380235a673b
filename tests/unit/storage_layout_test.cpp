// The CPU side of the storage layouts: Eq. 4.1 and Eq. 4.2 as printed, and every layout a
// bijection from (pixel, node) onto its allocation (no two nodes share a slot).
#include "oit/storage/storage_layout.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace oitbench {

TEST(StorageLayout, NamesRoundTrip) {
  for (const auto& name : StorageLayout::names()) EXPECT_EQ(StorageLayout::parse(name).name(), name);
  EXPECT_THROW(StorageLayout::parse("interleaved-2x4"), std::invalid_argument);
  EXPECT_THROW(StorageLayout::parse("linked-list"), std::invalid_argument);
}

TEST(StorageLayout, Eq41AndEq42AsPrinted) {
  const int w = 32, n = 4;
  EXPECT_EQ(StorageLayout::parse("ssbo").index(3, 2, 1, w, n), static_cast<std::size_t>((2 * w + 3) * n + 1));
  // Eq. 4.2 with gx = 2, gy = 4: gID = y/gy * w/gx + x/gx, index = gID*n*gx*gy + localID + gx*gy*i.
  auto l = StorageLayout::parse("interleaved-2x4-a1");
  for (int y : {0, 5, 7})
    for (int x : {0, 3, 31})
      for (int i = 0; i < n; ++i) {
        std::size_t gID = static_cast<std::size_t>(y / 4) * (w / 2) + x / 2;
        std::size_t localID = static_cast<std::size_t>(y % 4) * 2 + x % 2;
        EXPECT_EQ(l.index(x, y, i, w, n), gID * n * 8 + localID + 8 * i) << x << "," << y << "," << i;
      }
}

TEST(StorageLayout, EveryLayoutIsABijection) {
  for (const auto& name : StorageLayout::names()) {
    auto l = StorageLayout::parse(name);
    for (auto [w, h] : {std::pair{16, 16}, std::pair{13, 7}}) {
      const int n = 8;
      std::vector<int> hits(l.node_capacity(w, h, n), 0);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          for (int i = 0; i < n; ++i) {
            auto idx = l.index(x, y, i, w, n);
            ASSERT_LT(idx, hits.size()) << name;
            EXPECT_EQ(hits[idx]++, 0) << name << " slot " << idx << " used twice";
          }
    }
  }
}

TEST(StorageLayout, AlignmentKeepsRunsOfNodesTogether) {
  auto l = StorageLayout::parse("interleaved-2x2-a4");
  // Nodes 0..3 of a pixel are adjacent (one 32-byte chunk of 8-byte nodes); node 4 starts the next run.
  for (int i = 1; i < 4; ++i) EXPECT_EQ(l.index(1, 1, i, 8, 8), l.index(1, 1, 0, 8, 8) + i);
  EXPECT_EQ(l.index(1, 1, 4, 8, 8), l.index(1, 1, 0, 8, 8) + 4 * 4);
}

}  // namespace oitbench
