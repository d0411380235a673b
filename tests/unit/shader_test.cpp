// #include resolution and #line mapping, without a GL context.
#include "gl/shader.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "support/test_support.hpp"

namespace oitbench {

class ShaderAssembly : public ::testing::Test {
 protected:
  void SetUp() override {
    root = test::temp_dir("shaders");
    std::filesystem::create_directories(root / "a");
    std::ofstream(root / "a" / "main.frag") << "// line 1\n#include \"lib.glsl\"\nvoid main() {}\n";
    std::ofstream(root / "a" / "lib.glsl") << "#include \"../common.glsl\"\nfloat f() { return 1.0; }\n";
    std::ofstream(root / "common.glsl") << "const int K = 3;\n";
  }
  std::filesystem::path root;
};

TEST_F(ShaderAssembly, PreambleDefinesIncludesAndLineMarkers) {
  ShaderLibrary lib(root);
  auto src = lib.assemble("a/main.frag", {{"SIZE", "8"}, {"FLAG", ""}});
  EXPECT_EQ(src.text.rfind("#version 450 core\n#define SIZE 8\n#define FLAG\n", 0), 0u) << src.text;
  ASSERT_EQ(src.files.size(), 4u);
  EXPECT_EQ(src.files[1], "shaders/a/main.frag");
  EXPECT_EQ(src.files[2], "shaders/a/lib.glsl");
  EXPECT_EQ(src.files[3], "shaders/common.glsl");
  // After the include, main.frag resumes at its line 3.
  EXPECT_NE(src.text.find("#line 3 1\nvoid main() {}"), std::string::npos) << src.text;
}

// FNV-1a 32-bit of the file's bytes: "" -> 811c9dc5, "a" -> e40c292c (the published test vectors).
TEST_F(ShaderAssembly, SourceIdIsThePathAndTheFnv1aOfTheBytes) {
  std::ofstream(root / "empty.glsl", std::ios::binary);
  std::ofstream(root / "a" / "one.glsl", std::ios::binary) << "a";
  ShaderLibrary lib(root);
  EXPECT_EQ(lib.source_id("empty.glsl"), "empty.glsl@811c9dc5");
  EXPECT_EQ(lib.source_id("a/one.glsl"), "a/one.glsl@e40c292c");
  EXPECT_THROW(lib.source_id("a/missing.glsl"), ShaderError);
}

TEST_F(ShaderAssembly, MapsMesaAndNvidiaLogsToFileAndLine) {
  ShaderLibrary lib(root);
  auto src = lib.assemble("a/main.frag", {});
  EXPECT_EQ(map_shader_log("2:2(5): error: bad\n", src), "shaders/a/lib.glsl:2:5: error: bad\n");
  EXPECT_EQ(map_shader_log("1(3) : error C0000: bad\n", src), "shaders/a/main.frag:3: error C0000: bad\n");
}

TEST_F(ShaderAssembly, MissingIncludeAndCycleAreErrors) {
  std::ofstream(root / "bad.frag") << "#include \"nowhere.glsl\"\n";
  std::ofstream(root / "x.glsl") << "#include \"y.glsl\"\n";
  std::ofstream(root / "y.glsl") << "#include \"x.glsl\"\n";
  ShaderLibrary lib(root);
  EXPECT_THROW(lib.assemble("bad.frag", {}), ShaderError);
  EXPECT_THROW(lib.assemble("missing.frag", {}), ShaderError);
  // Each file is included once: a cycle resolves instead of recursing forever.
  EXPECT_NO_THROW(lib.assemble("x.glsl", {}));
}

}  // namespace oitbench
