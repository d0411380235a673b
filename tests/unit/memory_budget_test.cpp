// Memory decided before it is used (issue 27): sizes parsed and written readably, the refusal names
// the estimate and the limit, and the fragment estimate a case's refusal starts from counts what a
// capture would store.
#include "core/memory_budget.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "oit/capture/fragment_storage.hpp"
#include "oit/scene/coverage_estimate.hpp"
#include "oit/scene/scene.hpp"

namespace oitbench {
namespace {

TEST(MemoryBudget, SizesParseWithBinaryUnits) {
  EXPECT_EQ(parse_byte_size("8G"), 8ull << 30);
  EXPECT_EQ(parse_byte_size("512M"), 512ull << 20);
  EXPECT_EQ(parse_byte_size("512MiB"), 512ull << 20);
  EXPECT_EQ(parse_byte_size("1.5GiB"), 3ull << 29);
  EXPECT_EQ(parse_byte_size("64k"), 64ull << 10);
  EXPECT_EQ(parse_byte_size("2TB"), 2ull << 40);
  EXPECT_EQ(parse_byte_size("1000000"), 1000000ull);
  EXPECT_EQ(parse_byte_size("900B"), 900ull);
}

TEST(MemoryBudget, BadSizesAreRefusedSayingWhatIsAccepted) {
  for (const char* bad :
       {"", "nan", "inf", "-1", "0", "0.5", "1Q", "G", "8 GB x", "1e3", "1..5G", "99999P", "9999999T"}) {
    try {
      parse_byte_size(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("e.g. 8G"), std::string::npos) << bad << ": " << e.what();
    }
  }
}

TEST(MemoryBudget, BytesAndCountsAreWrittenReadably) {
  EXPECT_EQ(format_bytes(900), "900 B");
  EXPECT_EQ(format_bytes(512ull << 20), "512 MiB");
  EXPECT_EQ(format_bytes(9.6 * (1ull << 30)), "9.60 GiB");
  EXPECT_EQ(format_count(1100), "1100");
  EXPECT_EQ(format_count(4194304), "4.19 M");
  EXPECT_EQ(format_count(402000000), "402 M");
  EXPECT_EQ(format_count(4613734400ull), "4.61 G");
}

TEST(MemoryBudget, TheRefusalNamesTheEstimateAndTheLimit) {
  MemoryLimits limits;
  limits.cpu = {6ull << 30, "MemAvailable 6.00 GiB"};
  MemoryNeed need{1ull << 30, 10ull << 30, "the lists", "the reference (402 M fragments x 24 B)"};
  const std::string why = memory_refusal(need, limits);
  EXPECT_NE(why.find("needs 10.0 GiB of CPU memory for the reference (402 M fragments x 24 B)"), std::string::npos)
      << why;
  EXPECT_NE(why.find("limit 6.00 GiB (MemAvailable 6.00 GiB)"), std::string::npos) << why;
  need.cpu_bytes = 11ull << 29;                 // 5.5 GiB
  EXPECT_EQ(memory_refusal(need, limits), "");  // the GPU's limit is unknown: not checked
  limits.gpu = {512ull << 20, "GL_NVX_gpu_memory_info's free memory"};
  EXPECT_NE(memory_refusal(need, limits).find("1.00 GiB of GPU memory for the lists"), std::string::npos);
  // A software renderer: both against the CPU limit together.
  limits.shared = true;
  EXPECT_NE(memory_refusal(need, limits).find("needs 6.50 GiB"), std::string::npos) << memory_refusal(need, limits);
  need.cpu_bytes = 4ull << 30;
  EXPECT_EQ(memory_refusal(need, limits), "");
  EXPECT_EQ(memory_refusal(need, MemoryLimits{}), "");  // unknown limits check nothing
  EXPECT_THROW(require_memory({0, 7ull << 30, "", ""}, limits, "a case"), Unsupported);
}

TEST(MemoryBudget, TheCpuLimitIsKnownHere) {
  MemoryLimit l = cpu_memory_limit();
  EXPECT_TRUE(l.known());
  EXPECT_FALSE(l.source.empty());
}

TEST(MemoryBudget, FragmentMemoryCountsNodesAndPixels) {
  using namespace oit;
  MemoryNeed n = fragment_memory(CaptureStorage::PPLL, {}, false, 1000000, 1000);
  EXPECT_EQ(n.gpu_bytes, 1000000ull * 12 + 1000 * 4);
  EXPECT_EQ(n.cpu_bytes, 1000000ull * 12 + 1000 * kValidationBytesPerPixel);
  EXPECT_NE(n.gpu_what.find("1.00 M fragments x 12 B"), std::string::npos) << n.gpu_what;
  MemoryNeed wide = fragment_memory(CaptureStorage::PPPA, {FragColour::RGBA32F, FragDepth::Window}, false, 1000, 10, 3);
  EXPECT_EQ(wide.gpu_bytes, 1000ull * 20 + 10 * 12);
  EXPECT_EQ(wide.cpu_bytes, 3ull * 1000 * 32 + 10 * kValidationBytesPerPixel);
}

// A square of clip space [-1, 1]^2 at depth 0: two triangles.
oit::Mesh square(float half, float z = 0) {
  oit::Mesh m;
  for (auto [x, y] : {std::pair{-half, -half}, {half, -half}, {half, half}, {-half, half}})
    m.vertices.push_back({{x, y, z}, glm::vec4(1), glm::vec2(0), 0});
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

TEST(FragmentEstimate, ATriangleCountsItsPixelsInsideTheView) {
  const glm::mat4 identity(1.0f);
  EXPECT_NEAR(oit::estimate_fragments(square(1), identity, 64, 32), 64.0 * 32, 1e-6);
  EXPECT_NEAR(oit::estimate_fragments(square(3), identity, 64, 32), 64.0 * 32, 1e-6);  // clipped to the view
  EXPECT_NEAR(oit::estimate_fragments(square(0.5), identity, 64, 32), 16.0 * 32 / 2 * 2, 1e-6);
  EXPECT_EQ(oit::estimate_fragments(square(1, 2.0f), identity, 64, 32), 0.0);  // beyond the far plane
  oit::Mesh line = square(1);
  line.indices.clear();
  line.line_indices = {0, 1, 1, 2};  // the bottom edge (64 pixels) and the right one (32)
  EXPECT_NEAR(oit::estimate_fragments(line, identity, 64, 32), 96.0, 1e-6);
}

TEST(FragmentEstimate, PlanesDeepIsElevenHundredFragmentsAPixel) {
  oit::SceneDesc s = oit::load_scene("planes-deep");
  oit::Mesh m = oit::build_mesh(s, s.view("fwd"), oit::Detail::Full);
  const double at64 = oit::estimate_fragments(m, oit::view_projection(s.view("fwd"), m, 1.0f), 64, 64);
  EXPECT_NEAR(at64, 1100.0 * 64 * 64, 1100.0 * 64 * 64 * 0.01);
  const double at2048 = oit::estimate_fragments(m, oit::view_projection(s.view("fwd"), m, 1.0f), 2048, 2048);
  EXPECT_NEAR(at2048, 1100.0 * 2048 * 2048, 1100.0 * 2048 * 2048 * 0.01);
}

}  // namespace
}  // namespace oitbench
