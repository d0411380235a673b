// lines: the per-fragment exact resolve matches the CPU reference, the per-primitive radix sort
// matches a stable CPU sort exactly, and both validators fail on a broken variant. The hair is the
// line strands of scenes/hair.json, which `oit` (exact and approximate techniques) also renders.
#include "support/test_support.hpp"

namespace oitbench::test {

class Lines : public GlTest {};

TEST_F(Lines, ExactAndSlicesAreValidAndSlicesCostSomeError) {
  auto exact = run_case("lines", {{"technique", "exact"}, {"segments", "6000"}}, {96, 96});
  EXPECT_TRUE(exact.valid) << exact.reason;
  EXPECT_EQ(exact.metrics.at("line_segments"), "6000");
  EXPECT_LT(std::stod(exact.metrics.at("max_abs_error")), 2.0 / 255);
  for (const char* slices : {"256", "4"}) {
    auto v = run_case("lines", {{"technique", "slices"}, {"segments", "6000"}, {"slices", slices}}, {96, 96});
    EXPECT_TRUE(v.valid) << v.reason;
    EXPECT_GT(std::stod(v.metrics.at("rmse")), 0.0) << "slices are an approximation";
  }
  // Fewer slices sort coarser: more error (the same segments, same order within a slice).
  auto coarse = run_case("lines", {{"technique", "slices"}, {"segments", "6000"}, {"slices", "2"}}, {96, 96});
  auto fine = run_case("lines", {{"technique", "slices"}, {"segments", "6000"}, {"slices", "1024"}}, {96, 96});
  EXPECT_GT(std::stod(coarse.metrics.at("rmse")), std::stod(fine.metrics.at("rmse")));
}

TEST_F(Lines, ReadsTheScenesViewsAndItsOwnSegmentCount) {
  for (const char* view : {"fwd", "rev"})
    for (const char* technique : {"exact", "slices"}) {
      auto v = run_case("lines", {{"technique", technique}, {"view", view}, {"segments", "3000"}}, {64, 64});
      EXPECT_TRUE(v.valid) << technique << " " << view << ": " << v.reason;
      EXPECT_EQ(v.metrics.at("line_segments"), "3000");
    }
  // segments=0: the scene file's own count (hair.json's full 90 K).
  auto own = run_case("lines", {{"technique", "slices"}, {"segments", "0"}}, {64, 64});
  EXPECT_TRUE(own.valid) << own.reason;
  EXPECT_EQ(own.metrics.at("line_segments"), "90000");
}

TEST_F(Lines, ASceneWithoutStrandsIsAnErrorNamingIt) {
  try {
    run_case("lines", {{"technique", "exact"}, {"scene", "planes"}}, {32, 32});
    FAIL() << "planes has no line strands";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("has no line strands"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("planes"), std::string::npos) << e.what();
  }
}

TEST_F(Lines, ValidatorsCatchABrokenSortAndABrokenResolve) {
  auto s = run_case("lines", {{"technique", "slices"}, {"segments", "3000"}, {"fault", "wrong-result"}}, {64, 64});
  EXPECT_FALSE(s.valid);
  EXPECT_NE(s.reason.find("radix sort differs"), std::string::npos) << s.reason;
  auto e = run_case("lines", {{"technique", "exact"}, {"segments", "3000"}, {"fault", "wrong-result"}}, {64, 64});
  EXPECT_FALSE(e.valid);
}

// The hair scene's line segments go through every oit capture path (GpuMesh::draw draws GL_LINES
// after the triangles): exact resolves match the CPU reference, approximate ones their CPU models.
TEST_F(Lines, HairSceneRunsInOitForExactAndApproximateTechniques) {
  for (const char* technique : {"BASE-IS", "BMA-RBS-L", "CS-IMS", "CPU-NATIVE", "MLAB", "AT", "WBOIT", "unsorted"})
    for (const char* view : {"fwd", "rev"}) {
      auto v = run_case(
          "oit", {{"scene", "hair"}, {"view", view}, {"technique", technique}, {"detail", "small"}, {"block", "8"}});
      EXPECT_TRUE(v.valid) << technique << " " << view << ": " << v.reason;
      EXPECT_EQ(v.metrics.at("polygons"), "6000") << technique << ": polygons count the line segments";
      EXPECT_GT(std::stoll(v.metrics.at("total_fragments")), 1000) << technique;
    }
}

}  // namespace oitbench::test
