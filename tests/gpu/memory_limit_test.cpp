// Memory decided before it is used (issue 27, docs/measurement.md#memory-decided-before-it-is-used):
// a case whose fragments cannot be held is `unsupported` in seconds with its estimate and the limit,
// not an `error` row saying std::bad_alloc after minutes; and the same check lets a case that fits run.
// The runs are bounded by run_oitbench's timeout: a refusal that took minutes fails as exit 124.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "support/test_support.hpp"

namespace oitbench {
namespace {

namespace fs = std::filesystem;
using namespace test;

// A size in a reason: "104 GiB", "16.0 MiB".
const std::regex kSize(R"([0-9.]+ (B|KiB|MiB|GiB|TiB|PiB))");

TEST(MemoryLimit, TheDeepCaseAt2048IsRefusedWithItsSize) {
  auto dir = temp_dir("memory-deep");
  const fs::path csv = dir / "deep.csv";
  // BASE-IS on linked lists and CPU-NATIVE on packed arrays: 4.6 G fragments each.
  auto r = run_oitbench({"run", "oit", "--set", "scene=planes-deep", "--set", "view=fwd", "--set",
                         "technique=BASE-IS,CPU-NATIVE", "--set", "capture=PPLL,PPPA", "--resolution", "2048x2048",
                         "--reps", "1", "--out", csv.string(), "--no-progress"},
                        120);
  ASSERT_EQ(r.exit_code, 3) << r.err;  // nothing could run: every case unsupported (docs/usage.md's exit table)
  auto rows = read_csv_rows(csv);
  ASSERT_EQ(rows.size(), 4u);
  for (auto& row : rows) {
    EXPECT_EQ(row["status"], "unsupported") << row["reason"];
    EXPECT_NE(row["reason"].find("4.61 G fragments"), std::string::npos) << row["reason"];
    EXPECT_NE(row["reason"].find("limit"), std::string::npos) << row["reason"];
    EXPECT_TRUE(std::regex_search(row["reason"], kSize)) << row["reason"];
  }
}

// The check can fail both ways: a small case refused under a small --memory-limit runs (ok) without it.
TEST(MemoryLimit, TheLimitOptionDecidesASmallCase) {
  auto dir = temp_dir("memory-small");
  auto run = [&](const std::string& name, const std::vector<std::string>& extra) {
    const fs::path csv = dir / (name + ".csv");
    std::vector<std::string> args = {"run",          "oit",      "--set",  "scene=planes",
                                     "--set",        "view=fwd", "--set",  "technique=BASE-IS",
                                     "--resolution", "64x64",    "--reps", "1",
                                     "--warmup",     "0",        "--out",  csv.string(),
                                     "--no-progress"};
    args.insert(args.end(), extra.begin(), extra.end());
    auto r = run_oitbench(args, 300);
    auto rows = read_csv_rows(csv);  // one row per pass (one for a case refused before it ran): the total's
    EXPECT_FALSE(rows.empty()) << r.err;
    return std::make_pair(r.exit_code, rows.empty() ? Row{} : rows.back());
  };
  auto [refused_exit, refused] = run("refused", {"--memory-limit", "4M"});
  EXPECT_EQ(refused_exit, 3);
  EXPECT_EQ(refused["status"], "unsupported");
  EXPECT_NE(refused["reason"].find("limit 4.00 MiB (--memory-limit)"), std::string::npos) << refused["reason"];
  EXPECT_TRUE(std::regex_search(refused["reason"], kSize)) << refused["reason"];
  auto [ran_exit, ran] = run("ran", {"--memory-limit", "1G"});
  EXPECT_EQ(ran_exit, 0);
  EXPECT_EQ(ran["pass"], "total");
  EXPECT_EQ(ran["status"], "ok") << ran["reason"];
}

// The approximate techniques' node arrays are in the estimate too: MLAB with 64 nodes at 128x128 holds
// 16,384 pixels x 64 x 8 B (8 MiB), refused under 4M with what it is for, run under 1G.
TEST(MemoryLimit, TheNodeArraysOfAnApproximateTechniqueAreHeldAgainstTheLimit) {
  auto dir = temp_dir("memory-nodes");
  auto run = [&](const std::string& name, const std::string& limit) {
    const fs::path csv = dir / (name + ".csv");
    auto r = run_oitbench(
        {"run",   "oit",        "--set",         "scene=planes",   "--set",  "view=fwd", "--set",    "technique=MLAB",
         "--set", "nodes=64",   "--resolution",  "128x128",        "--reps", "1",        "--warmup", "0",
         "--out", csv.string(), "--no-progress", "--memory-limit", limit},
        300);
    auto rows = read_csv_rows(csv);
    EXPECT_FALSE(rows.empty()) << r.err;
    return std::make_pair(r.exit_code, rows.empty() ? Row{} : rows.back());
  };
  auto [refused_exit, refused] = run("refused", "4M");
  EXPECT_EQ(refused_exit, 3);
  EXPECT_EQ(refused["status"], "unsupported");
  EXPECT_NE(refused["reason"].find("MLAB's node arrays"), std::string::npos) << refused["reason"];
  EXPECT_NE(refused["reason"].find("limit 4.00 MiB (--memory-limit)"), std::string::npos) << refused["reason"];
  auto [ran_exit, ran] = run("ran", "1G");
  EXPECT_EQ(ran_exit, 0);
  EXPECT_EQ(ran["status"], "ok") << ran["reason"];
}

// A splat scene is held against the limit from its splat count before it is built (issue 29: one BASE-IS case
// of 10^7 splats ran for 5 minutes under --memory-limit 1G): its splats while they build and upload, and for
// GLOBAL-SORT its sort's buffers; every case is refused in seconds with the estimate and the limit.
TEST(MemoryLimit, TenMillionSplatsAreRefusedBeforeTheSceneIsBuilt) {
  auto dir = temp_dir("memory-splats");
  const fs::path scene = dir / "splats-10m.json";
  std::ofstream(scene) << R"({ "name": "splats-10m", "background": [1, 1, 1], "effects": ["transparency"],
    "materials": { "splat": { "colour": [0.6, 0.6, 0.6], "alpha": 1.0 } },
    "objects": [ { "generator": "splats", "material": "splat", "params": { "count": 10000000, "clusters": 24 } } ],
    "views": { "gen": { "eye": [0, 0, 4], "target": [0, 0, 0], "up": [0, 1, 0], "fov": 45 } } })";
  const fs::path csv = dir / "splats.csv";
  auto r = run_oitbench({"run", "oit", "--set", "scene=" + scene.string(), "--set", "view=gen", "--set",
                         "technique=BASE-IS,GLOBAL-SORT", "--resolution", "256x256", "--reps", "1", "--warmup", "0",
                         "--out", csv.string(), "--no-progress", "--memory-limit", "1G"},
                        120);
  ASSERT_EQ(r.exit_code, 3) << r.err;
  auto rows = read_csv_rows(csv);
  ASSERT_EQ(rows.size(), 2u);
  for (auto& row : rows) {
    EXPECT_EQ(row["status"], "unsupported") << row["reason"];
    EXPECT_NE(row["reason"].find("(10.0 M splats)"), std::string::npos) << row["reason"];
    EXPECT_NE(row["reason"].find("limit 1.00 GiB (--memory-limit)"), std::string::npos) << row["reason"];
    EXPECT_TRUE(std::regex_search(row["reason"], kSize)) << row["reason"];
  }
}

// Past the splats, the fragments: a splat scene's fragments are estimated from its splats' projected
// ellipses (coverage_estimate.hpp), and with the splats the scene holds, a capture that does not fit is
// refused before it allocates; the same case runs under a limit it fits.
TEST(MemoryLimit, TheFragmentsOfASplatSceneAreEstimatedFromItsSplats) {
  auto dir = temp_dir("memory-splat-fragments");
  auto run = [&](const std::string& name, const std::string& limit) {
    const fs::path csv = dir / (name + ".csv");
    auto r = run_oitbench({"run", "oit", "--set", "scene=" + std::string(OITBENCH_TEST_DATA) + "/splats_gpu.json",
                           "--set", "view=fwd", "--set", "technique=BASE-IS", "--resolution", "64x64", "--reps", "1",
                           "--warmup", "0", "--out", csv.string(), "--no-progress", "--memory-limit", limit},
                          300);
    auto rows = read_csv_rows(csv);
    EXPECT_FALSE(rows.empty()) << r.err;
    return std::make_pair(r.exit_code, rows.empty() ? Row{} : rows.back());
  };
  auto [refused_exit, refused] = run("refused", "2M");
  EXPECT_EQ(refused_exit, 3);
  EXPECT_EQ(refused["status"], "unsupported");
  EXPECT_NE(refused["reason"].find("fragments (estimated from the scene's primitives)"), std::string::npos)
      << refused["reason"];
  EXPECT_NE(refused["reason"].find("the scene's splats"), std::string::npos) << refused["reason"];
  auto [ran_exit, ran] = run("ran", "1G");
  EXPECT_EQ(ran_exit, 0);
  EXPECT_EQ(ran["status"], "ok") << ran["reason"];
}
}  // namespace
}  // namespace oitbench
