// The command line end to end on the embedded default: contexts, CSV, errors, exit codes,
// interruption and the watchdog.
#include <signal.h>
#include <sys/resource.h>

#include <fstream>

#include "core/data_dirs.hpp"
#include "core/provenance.hpp"
#include "core/runner.hpp"
#include "support/test_support.hpp"

namespace oitbench::test {

namespace {
bool contains(const std::string& s, const std::string& what) { return s.find(what) != std::string::npos; }
}  // namespace

TEST(Cli, InfoReportsTheEglContext) {
  auto r = run_oitbench({"info"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "backend:        egl")) << r.out;
  EXPECT_TRUE(contains(r.out, "GL_RENDERER:")) << r.out;
  EXPECT_TRUE(contains(r.out, "fragment_shader_interlock:")) << r.out;
  EXPECT_TRUE(contains(r.out, "GL_MAX_SHADER_STORAGE_BLOCK_SIZE")) << r.out;
}

TEST(Cli, InfoListsEglDevices) {
  auto r = run_oitbench({"info", "--backend", "egl-device"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "--device 0:")) << r.out;
}

#ifdef OITBENCH_HAVE_OSMESA
TEST(Cli, InfoReportsTheOsmesaContext) {
  auto r = run_oitbench({"info", "--backend", "osmesa"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "backend:        osmesa")) << r.out;
}
#endif

class QuickRun : public ::testing::TestWithParam<std::string> {};

TEST_P(QuickRun, OccupancyWritesValidRowsWithEveryColumn) {
  auto out = temp_dir("quick") / "occ.csv";
  auto r = run_oitbench({"run", "occupancy", "--quick", "--backend", GetParam(), "--set", "size=1,33", "--out",
                         out.string(), "--no-progress"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto rows = read_csv_rows(out);
  ASSERT_EQ(rows.size(), 4u);  // 2 variants x 2 sizes, one `total` row each
  for (const char* col : {"schema",  "experiment",    "variant",        "pass",          "status", "valid",
                          "backend", "gl_vendor",     "gl_renderer",    "gl_version",    "width",  "height",
                          "reps",    "warmup",        "median_ms",      "mad_ms",        "min_ms", "max_ms",
                          "mean_ms", "stddev_ms",     "cpu_median_ms",  "gpu_median_ms", "timer",  "compile_ms",
                          "git_sha", "timestamp_utc", "lp_num_threads", "size",          "draws"})
    for (auto& row : rows) EXPECT_FALSE(row[col].empty()) << "column " << col << " empty";
  for (auto& row : rows) {
    EXPECT_EQ(row["valid"], "1") << row["reason"];
    EXPECT_EQ(row["status"], "ok");
    EXPECT_EQ(row["backend"], GetParam());
    EXPECT_EQ(row["schema"], std::to_string(kCsvSchema));
    EXPECT_LE(std::stod(row["min_ms"]), std::stod(row["median_ms"]));
    EXPECT_LE(std::stod(row["median_ms"]), std::stod(row["max_ms"]));
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, QuickRun,
                         ::testing::Values("egl"
#ifdef OITBENCH_HAVE_OSMESA
                                           ,
                                           "osmesa"
#endif
                                           ));

TEST(Cli, ABrokenShaderIsAnErrorRowAndTheRunGoesOn) {
  auto out = temp_dir("broken") / "b.csv";
  auto r = run_oitbench({"run", "occupancy", "--quick", "--set", "variant=dynamic", "--set", "size=4", "--set",
                         "fault=compile-error,none", "--out", out.string(), "--no-progress"});
  EXPECT_EQ(r.exit_code, 1) << "errors must give exit 1: " << r.err;
  auto rows = read_csv_rows(out);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0]["status"], "error");
  EXPECT_EQ(rows[0]["valid"], "0");
  EXPECT_TRUE(contains(rows[0]["reason"], "shaders/common/oitbench.glsl:8:")) << rows[0]["reason"];
  EXPECT_EQ(rows[1]["status"], "ok");
  EXPECT_TRUE(contains(r.err, "shaders/common/oitbench.glsl:8:")) << r.err;
}

TEST(Cli, AWrongResultIsWrittenInvalidNotAveragedIn) {
  auto out = temp_dir("wrong") / "w.csv";
  auto r = run_oitbench({"run", "occupancy", "--quick", "--set", "size=8", "--set", "fault=wrong-result", "--out",
                         out.string(), "--no-progress"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  auto rows = read_csv_rows(out);
  ASSERT_EQ(rows.size(), 2u);
  for (auto& row : rows) {
    EXPECT_EQ(row["valid"], "0");
    EXPECT_EQ(row["status"], "invalid");
    EXPECT_TRUE(contains(row["reason"], "differ from the CPU reference")) << row["reason"];
    EXPECT_TRUE(row["median_ms"].empty()) << "an invalid case must not carry a time";
  }
}

TEST(Cli, UsageErrorsExitTwoAndListTheValidNames) {
  auto e = run_oitbench({"run", "nosuch"});
  EXPECT_EQ(e.exit_code, 2);
  EXPECT_TRUE(contains(e.err, "unknown experiment 'nosuch'; valid experiments: ")) << e.err;
  EXPECT_TRUE(contains(e.err, "occupancy")) << e.err;
  auto p = run_oitbench({"run", "occupancy", "--set", "sise=3"});
  EXPECT_EQ(p.exit_code, 2);
  EXPECT_TRUE(contains(p.err, "valid parameters: variant, size, draws")) << p.err;
  auto v = run_oitbench({"run", "occupancy", "--set", "variant=static"});
  EXPECT_EQ(v.exit_code, 2);
  EXPECT_TRUE(contains(v.err, "valid values: dynamic|unrolled")) << v.err;
  auto b = run_oitbench({"run", "occupancy", "--backend", "vulkan"});
  EXPECT_EQ(b.exit_code, 2);
  EXPECT_TRUE(contains(b.err, "egl")) << b.err;
  auto pr = run_oitbench({"run", "--preset", "nosuch"});
  EXPECT_EQ(pr.exit_code, 2);
  EXPECT_TRUE(contains(pr.err, "unknown preset 'nosuch'; presets in")) << pr.err;
  EXPECT_EQ(run_oitbench({"frobnicate"}).exit_code, 2);
  EXPECT_EQ(run_oitbench({"run", "occupancy", "--resolution", "big"}).exit_code, 2);
}

// Issue 31: one run id per invocation in every row and raw sample (an isolated case's too), the tags
// sorted and escaped, the machine's identity; a malformed or repeated --tag is a usage error naming it.
// The memory probe (core/memory_probe.hpp) is the runner's, not a case's: where its buffer is refused (here a
// 4 GiB buffer under a 2 GiB address-space limit) the run warns once and its cases stay ok, without the column.
TEST(Cli, AMemoryProbeThatCannotAllocateWarnsAndTheCasesStayOk) {
  auto dir = temp_dir("probe");
  auto out = dir / "probe.csv";
  rlimit before{};
  ASSERT_EQ(getrlimit(RLIMIT_AS, &before), 0);
  rlimit limited = before;
  limited.rlim_cur = std::min<rlim_t>(before.rlim_max, rlim_t{2} << 30);  // the soft limit: restored below
  ASSERT_EQ(setrlimit(RLIMIT_AS, &limited), 0);
  auto r = run_oitbench({"run", "occupancy", "--quick", "--set", "size=1", "--mem-probe-mib", "4096", "--isolate",
                         "never", "--out", out.string(), "--no-progress"});
  ASSERT_EQ(setrlimit(RLIMIT_AS, &before), 0);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.err, "warning: no memory probe")) << r.err;
  auto rows = read_csv_rows(out);
  ASSERT_EQ(rows.size(), 2u);
  for (auto& row : rows) {
    EXPECT_EQ(row["status"], "ok") << row["reason"];
    EXPECT_TRUE(row["host_mem_ns"].empty()) << row["host_mem_ns"];
  }
  // and the size is bounded before anything runs: a usage error naming the option
  for (const char* bad : {"0", "4097", "64M"}) {
    auto u = run_oitbench({"run", "occupancy", "--quick", "--mem-probe-mib", bad, "--out", out.string()});
    EXPECT_EQ(u.exit_code, 2) << bad;
    EXPECT_TRUE(contains(u.err, "--mem-probe-mib")) << u.err;
  }
}

TEST(Cli, EveryRowCarriesTheRunIdTagsAndMachine) {
  auto dir = temp_dir("identity");
  auto out = dir / "id.csv", raw = dir / "id_raw.csv";
  auto r = run_oitbench({"run", "occupancy", "--quick", "--set", "size=1", "--tag", "pool=ci;nightly", "--tag",
                         "mesa=22.3.6", "--out", out.string(), "--raw", raw.string(), "--no-progress"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto rows = read_csv_rows(out);
  ASSERT_EQ(rows.size(), 2u);
  const std::string id = rows[0]["run_id"];
  EXPECT_TRUE(is_run_id(id)) << id;
  for (auto& row : rows) {
    EXPECT_EQ(row["run_id"], id);
    EXPECT_EQ(row["tags"], "mesa=22.3.6;pool=ci%3Bnightly");
    EXPECT_EQ(row["machine_id"].size(), 16u);
    EXPECT_FALSE(row["cpu_count"].empty());
    EXPECT_FALSE(row["memory_bytes"].empty());
    EXPECT_FALSE(row["kernel"].empty());
    // the host's memory latency between rounds (core/memory_probe.hpp): a median at most the maximum
    const double mem = std::stod(row["host_mem_ns"]), mem_max = std::stod(row["host_mem_max_ns"]);
    EXPECT_GT(mem, 0);
    EXPECT_LE(mem, mem_max);
    if (contains(row["gl_renderer"], "llvmpipe")) {
      EXPECT_FALSE(row["llvm_version"].empty());
      EXPECT_FALSE(row["llvm_vector_bits"].empty());
      EXPECT_TRUE(contains(row["mesa_version"], "Mesa ")) << row["mesa_version"];
    }
  }
  for (auto& row : read_csv_rows(raw)) EXPECT_EQ(row["run_id"], id);
  // A second invocation is another run; an isolated case's child writes its parent's id.
  auto iso = dir / "iso.csv";
  r = run_oitbench({"run", "occupancy", "--quick", "--set", "size=1", "--isolate", "always", "--tag", "k=v", "--out",
                    iso.string(), "--no-progress"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto iso_rows = read_csv_rows(iso);
  ASSERT_EQ(iso_rows.size(), 2u);
  EXPECT_NE(iso_rows[0]["run_id"], id);
  EXPECT_EQ(iso_rows[0]["run_id"], iso_rows[1]["run_id"]);
  EXPECT_EQ(iso_rows[1]["tags"], "k=v");
  EXPECT_FALSE(iso_rows[1]["host_mem_ns"].empty()) << "an isolated case probes the memory too";
  // --no-mem-probe: no probe, in the parent and in an isolated child (the flag is passed on)
  auto quiet = dir / "quiet.csv";
  r = run_oitbench({"run", "occupancy", "--quick", "--set", "size=1", "--isolate", "always", "--no-mem-probe", "--out",
                    quiet.string(), "--no-progress"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (auto& row : read_csv_rows(quiet)) {
    EXPECT_TRUE(row["host_mem_ns"].empty()) << row["host_mem_ns"];
    EXPECT_TRUE(row["host_mem_max_ns"].empty());
  }
  for (std::vector<std::string> bad : {std::vector<std::string>{"--tag", "nokey"},
                                       {"--tag", "9a=1"},
                                       {"--tag", "a=1", "--tag", "a=2"},
                                       {"--run-id", "xyz"}}) {
    std::vector<std::string> args = {"run", "occupancy", "--quick", "--out", (dir / "bad.csv").string()};
    args.insert(args.end(), bad.begin(), bad.end());
    auto e = run_oitbench(args);
    EXPECT_EQ(e.exit_code, 2) << bad[1];
    EXPECT_TRUE(contains(e.err, bad[0] + " ")) << e.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.csv"));
}

TEST(Cli, HelpExplainsAndExitsZero) {
  auto r = run_oitbench({"run", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_TRUE(contains(r.out, "--set")) << r.out;
  EXPECT_TRUE(contains(r.out, "Exit codes")) << r.out;
  auto l = run_oitbench({"list"});
  EXPECT_EQ(l.exit_code, 0);
  EXPECT_TRUE(contains(l.out, "occupancy")) << l.out;
  EXPECT_TRUE(contains(l.out, "allowed: dynamic|unrolled")) << l.out;
}

TEST(Cli, VersionPrintsTheVersionAndTheBuildOptions) {
  for (const auto& args : {std::vector<std::string>{"--version"}, std::vector<std::string>{"version"}}) {
    auto r = run_oitbench(args);
    EXPECT_EQ(r.exit_code, 0) << args[0] << ": " << r.err;
    EXPECT_EQ(r.out.substr(0, r.out.find('\n')), std::string("oitbench ") + version_string()) << r.out;
    for (const char* line :
         {"\nbuild type:  ", "\ncompiler:    ", "\nosmesa:      ", "\nglfw:        ", "\nsanitizers:  "})
      EXPECT_TRUE(contains(r.out, line)) << args[0] << " lacks " << line << ": " << r.out;
  }
  // The version names the commit the rows' git_sha does.
  EXPECT_TRUE(contains(version_string(), std::string(git_sha()))) << version_string() << " vs " << git_sha();
  auto h = run_oitbench({"--help"});
  EXPECT_EQ(h.exit_code, 0);
  EXPECT_TRUE(contains(h.out, "--version")) << h.out;
  EXPECT_TRUE(contains(h.out, "  version ")) << h.out;
}

TEST(Cli, InfoNamesTheDataFoldersInUse) {
  auto r = run_oitbench({"info"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "oitbench:       " + std::string(version_string()) + "\n")) << r.out;
  for (const char* kind : {"shaders", "scenes", "presets"}) {
    auto found = find_data_dir(kind);
    EXPECT_TRUE(contains(r.out, found.path + " (" + found.from + ")\n")) << kind << ": " << r.out;
  }
}

TEST(Cli, AppendingOntoADifferentHeaderIsRefused) {
  auto out = temp_dir("append") / "other.csv";
  std::ofstream(out) << "some,other,header\n1,2,3\n";
  auto r = run_oitbench({"run", "occupancy", "--quick", "--set", "size=1", "--out", out.string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "exists with a different header")) << r.err;
  EXPECT_EQ(read_csv_rows(out).size(), 1u) << "the old file was modified";
}

TEST(Cli, AppendingOntoTheSameHeaderKeepsEarlierRows) {
  auto out = temp_dir("append") / "same.csv";
  std::vector<std::string> args = {"run",   "occupancy",       "--quick", "--set",      "size=1",
                                   "--set", "variant=dynamic", "--out",   out.string(), "--no-progress"};
  ASSERT_EQ(run_oitbench(args).exit_code, 0);
  ASSERT_EQ(run_oitbench(args).exit_code, 0);
  EXPECT_EQ(read_csv_rows(out).size(), 2u);
}

TEST(Cli, RawSamplesHaveOneRowPerRepetition) {
  auto dir = temp_dir("raw");
  auto r = run_oitbench({"run", "occupancy", "--quick", "--set", "size=2", "--reps", "4", "--out",
                         (dir / "s.csv").string(), "--raw", (dir / "r.csv").string(), "--no-progress"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto raw = read_csv_rows(dir / "r.csv");
  EXPECT_EQ(raw.size(), 8u);  // 2 variants x 4 repetitions
  for (auto& row : raw) EXPECT_FALSE(row["cpu_ms"].empty());
}

TEST(Cli, CtrlCLeavesAParseableCsvWithTheFinishedRows) {
  auto out = temp_dir("interrupt") / "i.csv";
  // 200 slow cases (past the unrolling cliff), one at a time; Ctrl-C once two rows are on disk.
  auto r = run_oitbench_interrupted(
      {"run", "occupancy", "--set", "variant=unrolled", "--set", "size=33..232", "--resolution", "200x150", "--set",
       "draws=16", "--reps", "2", "--no-interleave", "--out", out.string(), "--no-progress"},
      out, 2, SIGINT);
  EXPECT_EQ(r.exit_code, 130) << r.err;
  EXPECT_TRUE(contains(r.err, "interrupted")) << r.err;
  auto rows = read_csv_rows(out);
  EXPECT_GE(rows.size(), 2u);
  EXPECT_LT(rows.size(), 200u);
  for (auto& row : rows) {
    EXPECT_EQ(row["status"], "ok");
    EXPECT_FALSE(row["median_ms"].empty());
    EXPECT_EQ(row["seed"], "1");  // a column near the end of the header: no half rows
  }
}

TEST(Cli, TheWatchdogEndsAHungCaseAndTheRunGoesOn) {
  auto out = temp_dir("hang") / "h.csv";
  // On llvmpipe a "hang" is finite (every shader loop ends after 65535 iterations): at 400x300 the hung
  // case would run ~35 s on a quiet 2-core VM, well past the 4 s watchdog (at the quick 200x150, 9 s), as long
  // as the sampler does not scale the hung repetition down to one draw (--max-sample-ms 0).
  auto r = run_oitbench(
      {"run",   "occupancy",       "--quick", "--resolution",    "400x300",    "--set",        "variant=dynamic",
       "--set", "size=1",          "--set",   "fault=hang,none", "--isolate",  "always",       "--timeout",
       "4",     "--max-sample-ms", "0",       "--out",           out.string(), "--no-progress"},
      120);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  auto rows = read_csv_rows(out);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0]["status"], "timeout");
  EXPECT_TRUE(contains(rows[0]["reason"], "watchdog")) << rows[0]["reason"];
  EXPECT_EQ(rows[1]["status"], "ok");
}

TEST(Cli, PresetRunsItsGrid) {
  auto out = temp_dir("preset") / "p.csv";
  auto r = run_oitbench({"run", "--preset", "smoke-test", "--out", out.string(), "--no-progress"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto rows = read_csv_rows(out);
  ASSERT_FALSE(rows.empty());
  for (auto& row : rows) EXPECT_EQ(row["preset"], "smoke-test");
}

}  // namespace oitbench::test

namespace oitbench::test {

TEST(Cli, RenderWritesTheImageDiffAndDepthComplexity) {
  auto dir = temp_dir("render");
  auto r = run_oitbench({"render", "--scene", "planes", "--view", "rev", "--technique", "BASE-IS", "--resolution",
                         "64x64", "--set", "detail=small", "--out", (dir / "planes.png").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f :
       {"planes.png", "planes.pfm", "planes-diff8.png", "planes-depth.png", "planes-depth-histogram.csv", "planes.csv"})
    EXPECT_GT(std::filesystem::file_size(dir / f), 0u) << f;
  EXPECT_EQ(std::filesystem::file_size(dir / "planes.pfm"), std::string("PF\n64 64\n-1.0\n").size() + 64 * 64 * 12);
  auto hist = read_csv_rows(dir / "planes-depth-histogram.csv");
  ASSERT_FALSE(hist.empty());
  auto rows = read_csv_rows(dir / "planes.csv");
  ASSERT_FALSE(rows.empty());
  EXPECT_EQ(rows.back()["status"], "ok") << rows.back()["reason"];
}

}  // namespace oitbench::test
