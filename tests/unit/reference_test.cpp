// The CPU reference compositor and CPU-NATIVE on hand-made lists: order, "over", background,
// tie-breaks, broken lists, and the comparison's tolerance.
#include "oit/reference/reference.hpp"

#include <gtest/gtest.h>

#include <bit>

#include "oit/reference/image_compare.hpp"

namespace oitbench::oit {
namespace {

unsigned rgba8(int r, int g, int b, int a) { return r | (g << 8) | (b << 16) | (static_cast<unsigned>(a) << 24); }

// A 2x1 image: pixel 0 holds `frags` (listed head first), pixel 1 is empty.
HostLists lists(const std::vector<std::pair<float, unsigned>>& frags) {
  HostLists h;
  h.width = 2;
  h.height = 1;
  h.heads = {frags.empty() ? kListEnd : 0u, kListEnd};
  for (size_t i = 0; i < frags.size(); ++i) {
    h.nodes.push_back({frags[i].second, std::bit_cast<unsigned>(frags[i].first)});
    h.next.push_back(i + 1 < frags.size() ? static_cast<unsigned>(i + 1) : kListEnd);
  }
  return h;
}

TEST(Reference, CompositesNearToFarWithOverOntoTheBackground) {
  // Red at alpha 1/2 in front of blue at alpha 1, listed far first: the list order must not matter.
  auto h = lists({{0.8f, rgba8(0, 0, 255, 255)}, {0.2f, rgba8(255, 0, 0, 128)}});
  auto ref = composite_reference(h, glm::vec3(0, 1, 0));
  double a = 128 / 255.0;
  EXPECT_NEAR(ref[0], a, 1e-12);
  EXPECT_NEAR(ref[1], 0.0, 1e-12);
  EXPECT_NEAR(ref[2], 1 - a, 1e-12);
  EXPECT_DOUBLE_EQ(ref[3], 0.0);  // the empty pixel is the background
  EXPECT_DOUBLE_EQ(ref[4], 1.0);
  ListStats s = list_stats(h);
  EXPECT_EQ(s.total_fragments, 2u);
  EXPECT_EQ(s.peak_depth, 2u);
  EXPECT_EQ(s.covered_pixels, 1u);
  EXPECT_TRUE(s.error.empty());
}

TEST(Reference, NativeResolveAgreesAndTheComparisonCatchesADifference) {
  auto h = lists({{0.5f, rgba8(10, 200, 30, 100)}, {0.1f, rgba8(250, 20, 30, 60)}, {0.9f, rgba8(0, 0, 0, 255)}});
  ListStats s = list_stats(h);
  auto ref = composite_reference(h, glm::vec3(1));
  std::vector<float> out;
  resolve_native(h, glm::vec3(1), 2, false, out);
  auto e = compare_with_reference(out, ref, s, glm::vec3(1), 2, 2.0 / 255);
  EXPECT_EQ(e.bad_pixels, 0u);
  EXPECT_EQ(e.visit_errors, 0u);
  EXPECT_LT(e.max_abs_error, 1e-6);
  out[0] += 3.0f / 255;  // just over the tolerance
  e = compare_with_reference(out, ref, s, glm::vec3(1), 2, 2.0 / 255);
  EXPECT_EQ(e.bad_pixels, 1u);
  EXPECT_NE(e.first_bad.find("pixel (0,0)"), std::string::npos) << e.first_bad;
  out[3] = 2.0f;  // resolved twice
  e = compare_with_reference(out, ref, s, glm::vec3(1), 2, 2.0 / 255);
  EXPECT_EQ(e.visit_errors, 1u);
}

TEST(Reference, EqualDepthsAreCountedAndStillCompared) {
  auto h = lists({{0.5f, rgba8(255, 0, 0, 128)}, {0.5f, rgba8(0, 0, 255, 128)}});
  ListStats s = list_stats(h);
  EXPECT_EQ(s.tied_pixels, 1u);
  auto ref = composite_reference(h, glm::vec3(1));
  // The reference's order (ties broken by colour bits) is the one every resolve must produce.
  std::vector<float> out = {float(ref[0]), float(ref[1]), float(ref[2]), 1.0f, 0.0f, 0.0f, 0.0f, 0.0f};
  EXPECT_EQ(compare_with_reference(out, ref, s, glm::vec3(1), 2, 2.0 / 255).bad_pixels, 0u);
  out[0] = 0.0f;  // any other order is wrong
  out[2] = 0.0f;
  EXPECT_EQ(compare_with_reference(out, ref, s, glm::vec3(1), 2, 2.0 / 255).bad_pixels, 1u);
}

TEST(Reference, ABrokenListIsReported) {
  auto h = lists({{0.5f, rgba8(1, 2, 3, 4)}, {0.6f, rgba8(1, 2, 3, 4)}});
  h.next[1] = 0;  // a cycle
  EXPECT_NE(list_stats(h).error.find("pixel (0,0)"), std::string::npos);
  h.next[1] = 7;  // outside the pool
  EXPECT_FALSE(list_stats(h).error.empty());
}

// list_stats and the composite spread rows over the cores: the same numbers, and the first broken pixel
// in pixel order is the one named, whichever thread met it.
TEST(Reference, SpreadOverTheCoresTheFirstBrokenPixelIsNamed) {
  HostLists h;
  h.width = 2;
  h.height = 4;
  for (unsigned p = 0; p < 8; ++p) {
    h.heads.push_back(p);
    h.nodes.push_back({rgba8(255, 0, 0, 128), std::bit_cast<unsigned>(0.5f)});
    h.next.push_back(kListEnd);
  }
  ListStats s = list_stats(h);
  EXPECT_EQ(s.total_fragments, 8u);
  EXPECT_EQ(s.covered_pixels, 8u);
  EXPECT_TRUE(s.error.empty());
  auto ref = composite_reference(h, Backdrop(glm::vec3(0.0f)));
  for (size_t p = 1; p < 8; ++p)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(ref[p * 3 + k], ref[k]);
  h.next[7] = 7;  // pixel (1,3): a cycle
  h.next[5] = 9;  // pixel (1,2): outside the pool
  s = list_stats(h);
  EXPECT_NE(s.error.find("pixel (1,2)"), std::string::npos) << s.error;
  EXPECT_EQ(s.total_fragments, 6u);
}

TEST(Reference, ListDepthsAreListStatsDepthsWithoutTheSort) {
  auto h = lists({{0.5f, rgba8(1, 2, 3, 4)}, {0.6f, rgba8(1, 2, 3, 4)}, {0.7f, rgba8(1, 2, 3, 4)}});
  ListDepths d = list_depths(h);
  EXPECT_EQ(d.depth, list_stats(h).depth);
  EXPECT_EQ(d.depth, (std::vector<unsigned>{3, 0}));
  EXPECT_EQ(d.peak_depth, 3u);
  EXPECT_EQ(d.total_fragments, 3u);
  for (unsigned broken : {0u, 9u}) {  // a cycle, a node outside the pool: 0, as list_stats counts it
    h.next[2] = broken;
    d = list_depths(h);
    EXPECT_EQ(d.depth, list_stats(h).depth);
    EXPECT_EQ(d.peak_depth, 0u);
  }
}

}  // namespace
}  // namespace oitbench::oit
