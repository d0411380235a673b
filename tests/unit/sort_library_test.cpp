// The sort library (shaders/sorts/, see api.glsl): every sort is defined once, in that folder, so
// the sort experiment and the resolves cannot drift apart into copies again. Reads the shader tree
// as plain files, without a GL context.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/runner.hpp"
#include "gl/shader.hpp"

namespace oitbench {
namespace {

namespace fs = std::filesystem;

// The text without // and /* */ comments (a comment may name a sort without defining it).
std::string strip_comments(const std::string& s) {
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s.compare(i, 2, "//") == 0) {
      i = s.find('\n', i);
      if (i == std::string::npos) break;
    } else if (s.compare(i, 2, "/*") == 0) {
      i = s.find("*/", i + 2);
      if (i == std::string::npos) break;
      ++i;
      continue;
    }
    out += s[i];
  }
  return out;
}

// Every shader source under the root: relative path -> text without comments.
std::map<std::string, std::string> shader_sources(const fs::path& root) {
  static const std::set<std::string> exts = {".glsl", ".frag", ".vert", ".comp", ".h"};
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    if (!e.is_regular_file() || !exts.count(e.path().extension().string())) continue;
    std::ifstream in(e.path(), std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    out[e.path().lexically_relative(root).generic_string()] = strip_comments(ss.str());
  }
  return out;
}

// Name -> the files that define it, for each match of `def` (group 1 = the name).
std::map<std::string, std::set<std::string>> definitions(const std::map<std::string, std::string>& sources,
                                                         const std::regex& def) {
  std::map<std::string, std::set<std::string>> where;
  for (const auto& [file, text] : sources)
    for (auto it = std::sregex_iterator(text.begin(), text.end(), def); it != std::sregex_iterator(); ++it)
      where[(*it)[1].str()].insert(file);
  return where;
}

class SortLibrary : public ::testing::Test {
 protected:
  fs::path root = default_shader_root();
  std::map<std::string, std::string> sources = shader_sources(root);
};

TEST_F(SortLibrary, EverySortFunctionIsDefinedInExactlyOneFileUnderSorts) {
  ASSERT_TRUE(fs::is_directory(root / "sorts")) << root;
  auto where = definitions(sources, std::regex(R"(\bvoid\s+(sort_\w+)\s*\()"));
  // The library's sorts, as shaders/sorts/api.glsl lists them: all present.
  for (const char* name : {"sort_insertion", "sort_bubble", "sort_shell", "sort_merge", "sort_bitonic",
                           "sort_odd_even_merge", "sort_register", "sort_network"})
    EXPECT_TRUE(where.count(name)) << name << " is not defined anywhere under " << root;
  for (const auto& [name, files] : where) {
    EXPECT_EQ(files.size(), 1u) << name << " is defined in " << files.size() << " files, first " << *files.begin()
                                << " and " << *files.rbegin();
    for (const auto& f : files)
      EXPECT_TRUE(f.starts_with("sorts/")) << name << " is defined in " << f << ", outside sorts/";
  }
}

TEST_F(SortLibrary, TheInsertionNetworkAndTheInsertionLoopExistOnlyInTheLibrary) {
  // RS's unrolled network (any RBS_INSERT_/RS_INS macro) and the insertion sort's shift loop
  // `while (j >= 0 && ...)`: the shapes the copies had before the library existed.
  auto network = definitions(sources, std::regex(R"(#\s*define\s+((RBS_INSERT|RS_INS)_?\d+)\b)"));
  EXPECT_FALSE(network.empty());
  for (const auto& [name, files] : network)
    for (const auto& f : files) EXPECT_EQ(f, "sorts/register_sort.glsl") << name << " is defined in " << f;
  auto shift = definitions(sources, std::regex(R"(while\s*\(\s*(\w+)\s*>=\s*0\s*&&)"));
  for (const auto& [var, files] : shift)
    for (const auto& f : files)
      EXPECT_TRUE(f.starts_with("sorts/")) << "an insertion shift loop over " << var << " in " << f;
}

TEST_F(SortLibrary, TheOldCopiesAreGone) {
  EXPECT_FALSE(fs::exists(root / "oit" / "sorts"));
  for (const char* old : {"insertion_naive.glsl", "insertion_v1.glsl", "insertion_v2.glsl", "bubble.glsl", "shell.glsl",
                          "shell_register.glsl", "merge.glsl", "bitonic.glsl", "odd_even_merge.glsl", "rbs.glsl"})
    EXPECT_FALSE(fs::exists(root / "sort" / old)) << "shaders/sort/" << old;
}

// source_id names a file by its bytes: the same text gives the same id wherever it is read from.
TEST_F(SortLibrary, SourceIdHashesTheFileText) {
  ShaderLibrary lib(root);
  const std::string id = lib.source_id("sorts/insertion.glsl");
  EXPECT_TRUE(std::regex_match(id, std::regex(R"(sorts/insertion\.glsl@[0-9a-f]{8})"))) << id;
  EXPECT_EQ(lib.source_id("sorts/insertion.glsl"), id);
  EXPECT_NE(lib.source_id("sorts/merge.glsl").substr(id.size() - 8), id.substr(id.size() - 8));
  EXPECT_THROW(lib.source_id("sorts/no_such_sort.glsl"), ShaderError);
}

}  // namespace
}  // namespace oitbench
