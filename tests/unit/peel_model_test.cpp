// Depth peeling's CPU model on hand-made lists: layers are (depth, colour) pairs in that order,
// equal pairs one layer; depth alone keeps one colour per depth; run long enough the model is the
// exact reference; stopped early DP keeps the front layers and DDP the front and the back ones.
#include <gtest/gtest.h>

#include <bit>

#include "oit/peel/peel.hpp"
#include "oit/reference/reference.hpp"

namespace oitbench::oit {
namespace {

unsigned rgba8(int r, int g, int b, int a) { return r | (g << 8) | (b << 16) | (static_cast<unsigned>(a) << 24); }

// One pixel holding `frags` (head first).
HostLists lists(const std::vector<std::pair<float, unsigned>>& frags) {
  HostLists h;
  h.width = 1;
  h.height = 1;
  h.heads = {frags.empty() ? kListEnd : 0u};
  for (size_t i = 0; i < frags.size(); ++i) {
    h.nodes.push_back({frags[i].second, std::bit_cast<unsigned>(frags[i].first)});
    h.next.push_back(i + 1 < frags.size() ? static_cast<unsigned>(i + 1) : kListEnd);
  }
  return h;
}

const unsigned kRed = rgba8(255, 0, 0, 128), kGreen = rgba8(0, 255, 0, 128), kBlue = rgba8(0, 0, 255, 200);

TEST(PeelModel, LayersAreDepthColourPairsAndEqualPairsAreOneLayer) {
  auto h = lists({{0.5f, kGreen}, {0.5f, kRed}, {0.2f, kBlue}, {0.5f, kRed}});
  auto layers = peel_layers(h, 0, false);
  ASSERT_EQ(layers.size(), 3u);
  EXPECT_EQ(layers[0].colour, kBlue);
  EXPECT_EQ(layers[1].colour, std::min(kRed, kGreen));  // ties by colour bits, as the reference
  EXPECT_EQ(layers[1].count + layers[2].count, 3u);
  auto by_depth = peel_layers(h, 0, true);  // classic peeling: one colour per depth survives
  ASSERT_EQ(by_depth.size(), 2u);
  EXPECT_EQ(by_depth[1].colour, std::min(kRed, kGreen));
}

TEST(PeelModel, EnoughIterationsGiveTheExactReference) {
  auto h = lists({{0.5f, kGreen}, {0.5f, kRed}, {0.2f, kBlue}, {0.5f, kRed}, {0.9f, kGreen}});
  auto ref = composite_reference(h, glm::vec3(1.0f));
  for (bool dual : {false, true}) {
    PeelSettings s;
    s.dual = dual;
    s.iterations = dual ? 2 : 4;  // 4 layers
    auto m = peel_model(h, glm::vec3(1.0f), s);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(m[k], ref[k], 1e-12) << dual;
  }
}

TEST(PeelModel, StoppedEarlyDpKeepsTheFrontAndDdpBothEnds) {
  auto h = lists({{0.1f, kRed}, {0.4f, kGreen}, {0.6f, kBlue}, {0.8f, kGreen}});
  const glm::vec3 bg(1.0f);
  PeelSettings dp;
  dp.iterations = 1;
  auto front = peel_model(h, bg, dp);
  auto only_red = composite_reference(lists({{0.1f, kRed}}), bg);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(front[k], only_red[k], 1e-12);
  PeelSettings ddp;
  ddp.dual = true;
  ddp.iterations = 1;
  auto ends = peel_model(h, bg, ddp);
  auto red_and_last = composite_reference(lists({{0.1f, kRed}, {0.8f, kGreen}}), bg);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(ends[k], red_and_last[k], 1e-12);
}

}  // namespace
}  // namespace oitbench::oit
