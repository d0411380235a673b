// sort_source: the sort experiment and the resolves that sort (oit's exact techniques, stencil's
// resolve=sort) run the same files of the sort library (shaders/sorts/), and each row says which,
// with a hash of the file's text, so a micro-benchmark number and a resolve number can be seen to
// describe the same code. End to end through the oitbench binary.
#include <set>
#include <string>
#include <vector>

#include "core/runner.hpp"
#include "gl/shader.hpp"
#include "support/test_support.hpp"

namespace oitbench::test {

namespace {

// Runs `oitbench run EXPERIMENT --set ...` at a small size; returns every row.
std::vector<Row> run_rows(const std::string& experiment, const std::vector<std::string>& sets,
                          const std::string& resolution) {
  auto out = temp_dir("sort_source_" + experiment) / "rows.csv";
  std::vector<std::string> args = {"run",      experiment, "--resolution",  resolution, "--reps",    "1",
                                   "--warmup", "0",        "--no-progress", "--out",    out.string()};
  for (const auto& s : sets) {
    args.push_back("--set");
    args.push_back(s);
  }
  auto r = run_oitbench(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return read_csv_rows(out);
}

// The one sort_source of rows matching `column == value` (every pass of a case carries the same).
std::string source_of(const std::vector<Row>& rows, const std::string& column, const std::string& value) {
  std::set<std::string> seen;
  for (const auto& row : rows)
    if (row.at(column) == value) {
      EXPECT_EQ(row.at("status"), "ok") << value << ": " << row.at("reason");
      seen.insert(row.at("sort_source"));
    }
  EXPECT_EQ(seen.size(), 1u) << column << "=" << value << " rows name " << seen.size() << " sort sources";
  return seen.empty() ? "" : *seen.begin();
}

std::string id(const std::string& file) { return ShaderLibrary(default_shader_root()).source_id(file); }

std::vector<Row> sort_rows() {
  return run_rows("sort", {"variant=rbs,insertion-naive", "n=8", "stage=fragment", "memory=registers", "keys=random"},
                  "16x16");
}

// `block` is scoped to the register-block techniques: a --set of it where none runs is a usage error.
std::vector<std::string> oit_small(const std::string& techniques, bool register_blocks = true) {
  std::vector<std::string> sets = {"technique=" + techniques, "scene=planes", "view=fwd", "detail=small"};
  if (register_blocks) sets.push_back("block=8");
  return sets;
}

}  // namespace

// The requirement: sort's rbs and oit's BASE-RBS-L name the same file and hash, and so do
// insertion-naive and BASE-IS; both are the hash of the file as it is on disk.
TEST(SortSource, SortExperimentAndOitResolvesNameTheSameLibraryFile) {
  auto sorts = sort_rows();
  auto oit = run_rows("oit", oit_small("BASE-RBS-L,BASE-IS,RBS-G,CS-IS"), "32x32");
  const std::string rbs = source_of(sorts, "variant", "rbs");
  const std::string insertion = source_of(sorts, "variant", "insertion-naive");
  EXPECT_EQ(rbs, id("sorts/register_sort.glsl"));
  EXPECT_EQ(insertion, id("sorts/insertion.glsl"));
  EXPECT_EQ(source_of(oit, "technique", "BASE-RBS-L"), rbs);
  EXPECT_EQ(source_of(oit, "technique", "RBS-G"), rbs);
  EXPECT_EQ(source_of(oit, "technique", "BASE-IS"), insertion);
  EXPECT_EQ(source_of(oit, "technique", "CS-IS"), insertion);
}

// IMS runs insertion and, for lists deeper than 32, merge: both files, joined with '+'. Below 33
// fragments the merge is not compiled and not named. CPU-NATIVE runs no shader sort.
TEST(SortSource, ImsNamesInsertionThenMergeOnlyWhereItCompilesTheMerge) {
  auto shallow = oit_small("BASE-IMS,CPU-NATIVE", false);
  auto deep = oit_small("BASE-IMS", false);
  deep.push_back("max_frags=64");
  EXPECT_EQ(source_of(run_rows("oit", deep, "32x32"), "technique", "BASE-IMS"),
            id("sorts/insertion.glsl") + "+" + id("sorts/merge.glsl"));
  auto rows = run_rows("oit", shallow, "32x32");
  EXPECT_EQ(source_of(rows, "technique", "BASE-IMS"), id("sorts/insertion.glsl"));
  EXPECT_EQ(source_of(rows, "technique", "CPU-NATIVE"), "");
}

// stencil's resolve=sort is the library's insertion sort too; resolve=blend sorts nothing.
TEST(SortSource, StencilSortResolveRunsTheLibraryInsertion) {
  auto rows =
      run_rows("stencil", {"resolve=sort,blend", "variant=stencil", "coverage=50", "nodes=4", "layers=4"}, "32x32");
  EXPECT_EQ(source_of(rows, "resolve", "sort"), id("sorts/insertion.glsl"));
  EXPECT_EQ(source_of(rows, "resolve", "blend"), "");
}

}  // namespace oitbench::test
