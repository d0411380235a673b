#include "core/groups.hpp"

#include <gtest/gtest.h>

namespace oitbench {

namespace {

ParamSet oit_case(const std::string& technique, const std::string& scene) {
  ParamSet p({{"scene", scene}, {"technique", technique}, {"block", "8"}});
  if (technique.find("RBS") == std::string::npos) p.mark_unused("block");  // scoped: only RBS uses it
  return p;
}

}  // namespace

TEST(Groups, WithoutABaselineConsecutiveChunks) {
  std::vector<ParamSet> cases;
  for (int i = 0; i < 5; ++i) cases.push_back(oit_case("T" + std::to_string(i), "planes"));
  auto g = plan_groups(cases, {}, 2);
  ASSERT_EQ(g.size(), 3u);
  EXPECT_EQ(g[2].cases.size(), 1u);
  for (const auto& x : g)
    for (size_t i = 0; i < x.cases.size(); ++i) {
      EXPECT_EQ(x.baseline_of[i], -1);
      EXPECT_FALSE(x.shadow[i]);
    }
}

TEST(Groups, EveryGroupThatHoldsACaseHoldsItsBaseline) {
  const std::vector<std::string> techniques = {"BASE-IS", "BASE-IMS", "BMA-IS", "BASE-RBS-L", "CS-IS"};
  std::vector<ParamSet> cases;
  for (const auto& scene : {"planes", "hairball"})
    for (const auto& t : techniques) cases.push_back(oit_case(t, scene));
  const std::map<std::string, std::string> base = {{"technique", "BASE-IS"}};
  for (size_t size : {2u, 3u, 8u}) {
    auto groups = plan_groups(cases, base, size);
    size_t dependents = 0, written_baselines = 0;
    for (const auto& g : groups) {
      ASSERT_LE(g.cases.size(), size);
      for (size_t i = 0; i < g.cases.size(); ++i) {
        if (g.cases[i].get("technique") == "BASE-IS") {
          EXPECT_EQ(g.baseline_of[i], -1);
          written_baselines += g.shadow[i] ? 0 : 1;
          continue;
        }
        ++dependents;
        ASSERT_GE(g.baseline_of[i], 0) << "size " << size;
        const auto& b = g.cases[static_cast<size_t>(g.baseline_of[i])];
        EXPECT_EQ(b.get("technique"), "BASE-IS");
        EXPECT_EQ(b.get("scene"), g.cases[i].get("scene"));  // the same scene's baseline, in the same group
        EXPECT_FALSE(g.shadow[i]);
      }
    }
    EXPECT_EQ(dependents, 8u) << "every non-baseline case runs exactly once";
    EXPECT_EQ(written_baselines, 2u) << "each baseline writes its row once";
  }
  // Groups of two: the baseline and one case, four times per scene; three of the four copies are shadows.
  EXPECT_EQ(plan_groups(cases, base, 2).size(), 8u);
}

TEST(Groups, ACaseWithoutItsBaselineInTheGridRunsWithoutOne) {
  std::vector<ParamSet> cases = {oit_case("BASE-IS", "planes"), oit_case("BMA-IS", "planes"),
                                 oit_case("BMA-IS", "hairball")};
  auto groups = plan_groups(cases, {{"technique", "BASE-IS"}}, 2);
  ASSERT_EQ(groups.size(), 2u);
  EXPECT_EQ(groups[0].baseline_of[1], 0);
  EXPECT_EQ(groups[1].cases[0].get("scene"), "hairball");
  EXPECT_EQ(groups[1].baseline_of[0], -1);
  EXPECT_EQ(baseline_text({{"technique", "BASE-IS"}, {"bma", "off"}}), "bma=off;technique=BASE-IS");
}

TEST(Groups, NoInterleavingMeansNoPairing) {
  std::vector<ParamSet> cases = {oit_case("BASE-IS", "planes"), oit_case("BMA-IS", "planes")};
  auto groups = plan_groups(cases, {{"technique", "BASE-IS"}}, 1);
  ASSERT_EQ(groups.size(), 2u);
  EXPECT_EQ(groups[1].baseline_of[0], -1);
}

}  // namespace oitbench
