// oit's approximate techniques: every storage layout gives the technique's image, the validator
// (the technique's own CPU model) fails on a wrong result and on the wrong model, interlock is
// reported unsupported where the extension is missing, and flicker is measured across frames.
#include "oit/approx/approx.hpp"

#include <filesystem>
#include <set>

#include "support/test_support.hpp"

namespace oitbench::test {

class Approx : public GlTest {};

namespace {
std::map<std::string, std::string> small(const std::string& technique, const std::string& storage = "ssbo") {
  return {{"scene", "hairball"}, {"view", "rev"},      {"technique", technique}, {"detail", "small"},
          {"nodes", "4"},        {"storage", storage}, {"flicker_runs", "3"}};
}
}  // namespace

TEST_F(Approx, EveryStorageLayoutMatchesTheModel) {
  for (const char* t : {"MLAB", "UAT", "LAAT"}) {  // sorted, unsorted, linked; every technique runs on ssbo elsewhere
    std::string rmse;
    for (const char* storage : {"ssbo", "texture3d", "interleaved"}) {
      auto v = run_case("oit", small(t, storage), {40, 24});  // not a multiple of the 4x4 groups
      EXPECT_TRUE(v.valid) << t << " " << storage << ": " << v.reason;
      EXPECT_EQ(v.metrics.at("capped_updates"), "0");
      if (rmse.empty()) rmse = v.metrics.at("rmse");
      EXPECT_EQ(v.metrics.at("rmse"), rmse) << t << " " << storage << ": the layout must not change the image";
    }
  }
}

TEST_F(Approx, ErrorAgainstExactIsDataAndShrinksWithNodes) {
  for (const char* t : {"MLAB", "AT", "UHAT"}) {
    auto p = small(t);
    auto few = run_case("oit", p);
    p["nodes"] = "32";  // at least the peak depth of the small hairball: nothing is compressed
    auto many = run_case("oit", p);
    ASSERT_TRUE(few.valid && many.valid) << few.reason << many.reason;
    EXPECT_GT(std::stod(few.metrics.at("rmse")), std::stod(many.metrics.at("rmse"))) << t;
    EXPECT_LE(std::stod(many.metrics.at("max_abs_error")), 4.0 / 255.0) << t;
  }
}

TEST_F(Approx, FlickerIsMeasuredAcrossFrames) {
  // llvmpipe shades a pixel's fragments in submission order, so the spinlock order and the image
  // repeat exactly; on a GPU this column is where MLAB/AT flicker shows up.
  for (const char* t : {"MLAB", "AT", "UHAT"}) {
    auto v = run_case("oit", small(t));
    ASSERT_TRUE(v.valid) << v.reason;
    EXPECT_EQ(v.metrics.at("flicker"), "0") << t;
    EXPECT_EQ(v.metrics.at("flicker_pixels"), "0") << t;
  }
}

TEST_F(Approx, InterlockNeedsTheExtension) {
  auto p = small("MLAB");
  p["sync"] = "interlock";
  if (gl().has_extension("GL_ARB_fragment_shader_interlock")) {
    auto v = run_case("oit", p);
    EXPECT_TRUE(v.valid) << v.reason;
  } else {
    EXPECT_THROW(run_case("oit", p), Unsupported);
  }
}

TEST_F(Approx, WboitWeightsAreDifferentApproximations) {
  std::set<std::string> rmse;
  for (const char* w : {"none", "eq7", "eq10"}) {
    auto p = small("WBOIT");
    p["wboit_weight"] = w;
    auto v = run_case("oit", p);
    EXPECT_TRUE(v.valid) << w << ": " << v.reason;
    rmse.insert(v.metrics.at("rmse"));
  }
  EXPECT_EQ(rmse.size(), 3u);
}

TEST_F(Approx, PngDumpOfImageAndDiff) {
  auto dir = temp_dir("approx_dump");
  auto p = small("AT");
  auto v = run_case("oit", p, {64, 64}, (dir / "at").string());
  ASSERT_TRUE(v.valid) << v.reason;
  EXPECT_TRUE(std::filesystem::exists(dir / "at.png"));
  EXPECT_TRUE(std::filesystem::exists(dir / "at-diff8.png"));
}

}  // namespace oitbench::test
