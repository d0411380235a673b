// occupancy on the embedded default: results match the CPU reference, and the validator can fail.
#include "support/test_support.hpp"

namespace oitbench::test {

class Occupancy : public GlTest {};

TEST_F(Occupancy, BothVariantsMatchTheCpuReference) {
  for (const char* variant : {"dynamic", "unrolled"})
    for (const char* size : {"1", "8", "33"}) {
      auto v = run_case("occupancy", {{"variant", variant}, {"size", size}, {"draws", "2"}});
      EXPECT_TRUE(v.valid) << variant << " size " << size << ": " << v.reason;
    }
}

TEST_F(Occupancy, ValidatorCatchesAWrongPixel) {
  auto v = run_case("occupancy", {{"variant", "unrolled"}, {"size", "4"}, {"draws", "1"}, {"fault", "wrong-result"}});
  EXPECT_FALSE(v.valid);
  EXPECT_NE(v.reason.find("pixel (1,1)"), std::string::npos) << v.reason;
  EXPECT_EQ(v.metrics.at("mismatched_pixels"), "1");
}

TEST_F(Occupancy, CompileErrorNamesTheRealFileAndLine) {
  try {
    run_case("occupancy", {{"size", "4"}, {"fault", "compile-error"}});
    FAIL() << "the injected compile error compiled";
  } catch (const ShaderError& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("shaders/common/oitbench.glsl:8:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("OITBENCH_FAULT_COMPILE_ERROR"), std::string::npos) << "defines missing: " << msg;
  }
}

}  // namespace oitbench::test
