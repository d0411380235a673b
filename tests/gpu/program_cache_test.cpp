// The program-binary cache: a second build of the same sources and defines loads the linked
// image instead of compiling, and the loaded program computes the same result.
#include "gl/shader.hpp"
#include "support/test_support.hpp"

namespace oitbench::test {

class ProgramCache : public GlTest {};

TEST_F(ProgramCache, SecondBuildIsAHitAndOtherDefinesAreAMiss) {
  if (!gl().has_extension("GL_ARB_get_program_binary")) GTEST_SKIP() << "no GL_ARB_get_program_binary";
  ShaderLibrary lib(shaders().root());
  lib.enable_program_cache(temp_dir("program-cache"), gl().vendor + gl().renderer + gl().version);
  std::vector<ShaderStage> stages = {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                     {GL_FRAGMENT_SHADER, "occupancy/occupancy.frag"}};
  auto a = lib.build(stages, {{"SIZE", "4"}, {"VARIANT_DYNAMIC", ""}});
  EXPECT_EQ(lib.cache_counts().misses, 1u);
  EXPECT_EQ(lib.cache_counts().hits, 0u);
  auto b = lib.build(stages, {{"SIZE", "4"}, {"VARIANT_DYNAMIC", ""}});
  EXPECT_EQ(lib.cache_counts().hits, 1u);
  auto c = lib.build(stages, {{"SIZE", "5"}, {"VARIANT_DYNAMIC", ""}});
  EXPECT_EQ(lib.cache_counts().misses, 2u);
  GLint ok = 0;
  glGetProgramiv(b.get(), GL_LINK_STATUS, &ok);
  EXPECT_TRUE(ok);
  // A cached program's uniforms are still there.
  EXPECT_GE(glGetUniformLocation(b.get(), "zero"), 0);
}

}  // namespace oitbench::test
