// layout on the embedded default: every storage layout gives the CPU reference's nodes, lost
// updates are counted rather than failed where races are allowed, and the validator can fail.
#include "support/test_support.hpp"

namespace oitbench::test {

class Layout : public GlTest {};

TEST_F(Layout, EveryLayoutIsExactWhenRaceFree) {
  for (const char* layout : {"ssbo", "texture3d", "texbuffer", "interleaved-1x1-a1", "interleaved-2x4-a1",
                             "interleaved-4x2-a4", "interleaved-8x8-a4"})
    for (const char* nodes : {"4", "8"}) {
      auto v = run_case("layout", {{"layout", layout}, {"nodes", nodes}, {"layers", "1"}, {"draws", "3"}});
      EXPECT_TRUE(v.valid) << layout << " nodes " << nodes << ": " << v.reason;
      EXPECT_EQ(v.metrics.at("lost_updates"), "0") << layout;
    }
}

TEST_F(Layout, InterleavedGroupsThatDoNotDivideTheScreen) {
  // 60x36 leaves partial 8x8 and 4x4 groups at the right and top edges.
  for (const char* layout : {"interleaved-8x8-a4", "interleaved-4x4-a1", "interleaved-2x4-a4"}) {
    auto v = run_case("layout", {{"layout", layout}, {"nodes", "8"}, {"layers", "1"}, {"draws", "2"}}, {60, 36});
    EXPECT_TRUE(v.valid) << layout << ": " << v.reason;
  }
}

TEST_F(Layout, OverlappingLayersAndScatteredWritesStayConsistent) {
  for (const char* layout : {"ssbo", "texture3d", "interleaved-2x4-a1"})
    for (const char* order : {"sequential", "scattered"}) {
      auto v =
          run_case("layout", {{"layout", layout}, {"nodes", "8"}, {"layers", "4"}, {"draws", "2"}, {"order", order}});
      // Lost updates are allowed here (and counted); inconsistent nodes never are.
      EXPECT_TRUE(v.valid) << layout << " " << order << ": " << v.reason;
      EXPECT_EQ(v.metrics.at("inconsistent_nodes"), "0");
      EXPECT_GE(std::stoll(v.metrics.at("lost_updates")), 0);
    }
}

TEST_F(Layout, ValidatorCatchesAWrongNode) {
  for (const char* layers : {"1", "4"}) {  // race-free, and where lost updates are tolerated
    auto v = run_case("layout", {{"layout", "interleaved-2x4-a4"}, {"layers", layers}, {"fault", "wrong-result"}});
    EXPECT_FALSE(v.valid) << "layers " << layers;
    EXPECT_NE(v.reason.find("pixel (1,1) node 0"), std::string::npos) << v.reason;
    EXPECT_EQ(v.metrics.at("inconsistent_nodes"), "1");
  }
}

}  // namespace oitbench::test
