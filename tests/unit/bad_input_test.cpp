// Bad input and faults without a GL context: bounded --set ranges and grids, integer bounds, inputs
// that are not regular files, outputs that are not files, CSV files that appending must not damage,
// runs creating one CSV at once, presets and scenes that name their place, meshes bounded before they
// are built, stale case folders, the stop request between passes, the watchdog's grace and heartbeat.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "core/csv.hpp"
#include "core/files.hpp"
#include "core/interrupt.hpp"
#include "core/isolation.hpp"
#include "core/params.hpp"
#include "core/presets.hpp"
#include "core/runner.hpp"
#include "core/timer.hpp"
#include "experiments/experiments.hpp"
#include "oit/scene/scene.hpp"

namespace oitbench {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  auto dir = fs::temp_directory_path() / ("oitbench-badinput-" + std::to_string(getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void spit(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

template <class E, class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "(no error)";
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// ---- --set and the grid

TEST(BadInput, RangesPast2To53AreRefusedWithoutAllocating) {
  // Before: a double loop whose x += 1 no longer moved, allocating until killed.
  auto e = error_of<UsageError>([] { parse_set_option("seed=9223372036854775807..9223372036854775807"); });
  EXPECT_TRUE(has(e, "bad range")) << e;
  EXPECT_TRUE(has(e, "2^53")) << e;
  EXPECT_TRUE(has(error_of<UsageError>([] { parse_set_option("seed=1..99999999999999999999"); }), "bad range"));
  EXPECT_TRUE(has(error_of<UsageError>([] { parse_set_option("seed=-9007199254740993..0"); }), "bad range"));
  auto [name, values] = parse_set_option("seed=9007199254740990..9007199254740992");
  EXPECT_EQ(values, (std::vector<std::string>{"9007199254740990", "9007199254740991", "9007199254740992"}));
  EXPECT_EQ(parse_set_option("n=-3..3:3").second, (std::vector<std::string>{"-3", "0", "3"}));
  EXPECT_TRUE(has(error_of<UsageError>([] { parse_set_option("seed=0..9007199254740992"); }), "at most 100000"));
  EXPECT_TRUE(has(error_of<UsageError>([] { parse_set_option("seed=1..60000,1..60000"); }), "at most 100000"));
  EXPECT_THROW(parse_set_option("seed=1..5:0"), UsageError);
  EXPECT_THROW(parse_set_option("seed=1.5..3"), UsageError);
}

TEST(BadInput, AParameterSetTwiceIsRefused) {
  auto e = error_of<UsageError>([] { parse_set_options({"size=1", "size=8"}); });
  EXPECT_TRUE(has(e, "--set size is given twice")) << e;
  auto ok = parse_set_options({"size=1,8", "draws=2"});
  EXPECT_EQ(ok.at("size").size(), 2u);
}

TEST(BadInput, IntegersLandInTheirType) {
  ParamSpec unbounded{"draws", "", {"1"}, {}, {}, ParamSpec::Kind::Integer};
  EXPECT_NO_THROW(unbounded.check("2147483647", "x"));
  auto e = error_of<UsageError>([&] { unbounded.check("2147483648", "x"); });
  EXPECT_TRUE(has(e, "integer in [-2147483648, 2147483647]")) << e;
  EXPECT_THROW(unbounded.check("1e3", "x"), UsageError);
  EXPECT_THROW(unbounded.check("99999999999999999999999", "x"), UsageError);
  ParamSpec seed{"seed", "", {"1"}, {}, {}, ParamSpec::Kind::Integer, 0, 4294967295.0};  // its own bounds stand
  EXPECT_NO_THROW(seed.check("4294967295", "x"));
  EXPECT_THROW(seed.check("4294967296", "x"), UsageError);
}

TEST(BadInput, TheGridIsBoundedBeforeItIsBuiltAndTheCapCanBeRaised) {
  Registry registry;
  register_all_experiments(registry);
  // The issue's 1024 x 100000 x 1000 cases: refused from the counts alone, in well under a second.
  RunRequest r{"occupancy",
               {{"size", parse_set_option("size=1..1024").second},
                {"draws", parse_set_option("draws=1..100000").second},
                {"seed", parse_set_option("seed=1..1000").second}},
               {},
               {},
               {}};
  auto t0 = std::chrono::steady_clock::now();
  auto e = error_of<UsageError>([&] { check_requests(registry, {r}); });
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0);
  EXPECT_TRUE(has(e, "more than 100000")) << e;
  EXPECT_TRUE(has(e, "--max-cases")) << e;
  RunRequest small{"occupancy", {{"size", parse_set_option("size=1..30").second}}, {}, {}, {}};
  EXPECT_TRUE(has(error_of<UsageError>([&] { check_requests(registry, {small}, false, 10); }), "more than 10"));
  EXPECT_NO_THROW(check_requests(registry, {small}, false, 1000));
  // Several requests count together.
  EXPECT_TRUE(has(error_of<UsageError>([&] { check_requests(registry, {small, small}, false, 40); }), "more than 40"));
}

TEST(BadInput, ResolutionsPastTheBoundSayTooLarge) {
  auto e = error_of<UsageError>([] { parse_resolution("100000x100000"); });
  EXPECT_TRUE(has(e, "each side must be in [1, 16384]")) << e;
  EXPECT_TRUE(has(error_of<UsageError>([] { parse_resolution("99999999999999999999x2"); }), "[1, 16384]"));
  EXPECT_TRUE(has(error_of<UsageError>([] { parse_resolution("800by600"); }), "expected WIDTHxHEIGHT"));
  EXPECT_EQ(parse_resolution("16384x1").width, 16384);
}

// ---- files

TEST(BadInput, InputsMustBeRegularFilesOfBoundedSize) {
  auto dir = fresh_dir("inputs");
  EXPECT_TRUE(has(error_of<FileError>([&] { read_text_file(dir.string(), "scene file"); }), "is a folder")) << dir;
  auto e = error_of<FileError>([] { read_text_file("/dev/zero", "preset"); });
  EXPECT_TRUE(has(e, "/dev/zero: the preset is a character device, not a regular file")) << e;
  auto fifo = dir / "fifo";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_TRUE(has(error_of<FileError>([&] { read_text_file(fifo.string(), "scene file"); }), "a FIFO"));
  spit(dir / "binary.json", std::string("{\"a\": 1}\0\1\2", 11));
  e = error_of<FileError>([&] { read_text_file((dir / "binary.json").string(), "scene file"); });
  EXPECT_TRUE(has(e, "not a text file (a NUL byte at offset 8)")) << e;
  spit(dir / "big.json", std::string(2000, ' '));
  e = error_of<FileError>([&] { read_text_file((dir / "big.json").string(), "preset", 1000); });
  EXPECT_TRUE(has(e, "2000 bytes, more than the 1000 bytes")) << e;
  EXPECT_TRUE(
      has(error_of<FileError>([&] { read_text_file((dir / "none.json").string(), "preset"); }), "No such file"));
  spit(dir / "ok.json", "{}");
  EXPECT_EQ(read_text_file((dir / "ok.json").string(), "preset"), "{}");
}

TEST(BadInput, OutputsMustBeFilesNotDevicesOrFolders) {
  auto dir = fresh_dir("outputs");
  for (const char* dev : {"/dev/null", "/dev/full", "/dev/zero"}) {
    auto e = error_of<FileError>([&] { check_output_file(dev, "--out"); });
    EXPECT_TRUE(has(e, std::string("--out ") + dev + ": is a character device, not a regular file")) << e;
  }
  EXPECT_TRUE(has(error_of<FileError>([&] { check_output_file(dir.string(), "--raw"); }), "--raw"));
  EXPECT_TRUE(has(error_of<FileError>([&] { check_output_file(dir.string(), "--raw"); }), "is a folder"));
  EXPECT_TRUE(has(error_of<FileError>([&] { check_output_file(dir.string() + "/", "--out"); }), "names a folder"));
  EXPECT_TRUE(has(error_of<FileError>([&] { check_output_file((dir / "no/such/x.csv").string(), "--out"); }),
                  "does not exist"));
  EXPECT_NO_THROW(check_output_file((dir / "new.csv").string(), "--out"));
  EXPECT_NO_THROW(check_output_file("-", "--out"));
  // The writer itself refuses them too (naming the option), and writes nothing.
  auto e = error_of<CsvError>([] { CsvWriter w("/dev/full", {"a"}, "--raw"); });
  EXPECT_TRUE(has(e, "--raw /dev/full")) << e;
}

// ---- CSV append

TEST(BadInput, AppendingNeverTruncatesAFileWithAnEmptyFirstLine) {
  auto path = fresh_dir("empty-first") / "run.csv";
  const std::string before = "\na,b\n1,2\n3,4\n";
  spit(path, before);
  auto e = error_of<CsvError>([&] { CsvWriter w(path.string(), {"a", "b"}); });
  EXPECT_TRUE(has(e, "first line is empty")) << e;
  EXPECT_TRUE(has(e, "--out " + path.string())) << e;
  EXPECT_EQ(slurp(path), before);  // every byte kept
}

TEST(BadInput, AMissingFinalNewlineIsRepairedAfterAWholeRowAndRefusedAfterAPartOne) {
  auto dir = fresh_dir("newline");
  spit(dir / "whole.csv", "a,b\n1,2");
  {
    CsvWriter w((dir / "whole.csv").string(), {"a", "b"});
    w.write({{"a", "3"}, {"b", "4"}});
  }
  EXPECT_EQ(slurp(dir / "whole.csv"), "a,b\n1,2\n3,4\n");  // not "1,23,4"
  spit(dir / "header-only.csv", "a,b");
  {
    CsvWriter w((dir / "header-only.csv").string(), {"a", "b"});
    w.write({{"a", "5"}});
  }
  EXPECT_EQ(slurp(dir / "header-only.csv"), "a,b\n5,\n");
  const std::string cut = "a,b,c\n1,2,3\n4,5";
  spit(dir / "cut.csv", cut);
  auto e = error_of<CsvError>([&] { CsvWriter w((dir / "cut.csv").string(), {"a", "b", "c"}); });
  EXPECT_TRUE(has(e, "its last row has 2 fields where the header has 3")) << e;
  EXPECT_EQ(slurp(dir / "cut.csv"), cut);
  spit(dir / "quote.csv", "a,b\n1,\"open");
  EXPECT_TRUE(has(error_of<CsvError>([&] {
                    CsvWriter w((dir / "quote.csv").string(), {"a", "b"});
                  }),
                  "inside a quoted field"));
}

TEST(BadInput, AppendActionIsDecidedFromTheFileAlone) {
  const std::vector<std::string> cols = {"a", "b"};
  EXPECT_EQ(csv_append_action("", 0, '\n', cols, "f"), AppendAction::WriteHeader);
  EXPECT_EQ(csv_append_action("a,b\n", 4, '\n', cols, "f"), AppendAction::Append);
  EXPECT_EQ(csv_append_action("a,b\r\n1,2\r\n", 10, '\n', cols, "f"), AppendAction::Append);
  EXPECT_EQ(csv_append_action("a,b\n1,2", 7, '2', cols, "f"), AppendAction::AppendAfterNewline);
  EXPECT_THROW(csv_append_action("a,c\n", 4, '\n', cols, "f"), CsvError);
  EXPECT_THROW(csv_append_action("\r\na,b\n", 6, '\n', cols, "f"), CsvError);
  // A large file without a final newline: its last row cannot be checked from the head, so refused.
  EXPECT_THROW(csv_append_action("a,b\n1,2\n", kCsvHeadBytes + 10, '2', cols, "f"), CsvError);
}

TEST(BadInput, RunsCreatingTheSameNewCsvAtOnceWriteOneHeaderAndEveryRow) {
  auto dir = fresh_dir("concurrent");
  const std::vector<std::string> cols = {"who", "n", "pad"};
  const int writers = 6, rows = 40;
  for (int trial = 0; trial < 5; ++trial) {
    auto path = dir / ("t" + std::to_string(trial) + ".csv");
    std::vector<pid_t> kids;
    for (int w = 0; w < writers; ++w) {
      pid_t pid = fork();
      if (pid == 0) {
        try {
          CsvWriter out(path.string(), cols);
          for (int n = 0; n < rows; ++n)
            out.write({{"who", std::to_string(w)}, {"n", std::to_string(n)}, {"pad", std::string(300, 'x')}});
        } catch (...) {
          _exit(1);
        }
        _exit(0);
      }
      kids.push_back(pid);
    }
    for (pid_t k : kids) {
      int status = 0;
      waitpid(k, &status, 0);
      EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    }
    auto parsed = csv_parse(slurp(path));
    ASSERT_EQ(parsed.size(), 1u + writers * rows) << "trial " << trial;
    EXPECT_EQ(parsed[0], cols);
    for (size_t i = 1; i < parsed.size(); ++i) {
      ASSERT_EQ(parsed[i].size(), 3u) << "row " << i;
      EXPECT_NE(parsed[i][0], "who") << "a second header at row " << i;
    }
  }
}

// ---- presets

Preset preset_of(const std::string& text) { return parse_preset("p", "presets/p.json", text); }

TEST(BadInput, PresetValuesThatWereSilentlyAcceptedAreErrors) {
  auto e =
      error_of<UsageError>([] { preset_of(R"({"runs": [{"experiment": "occupancy", "set": {"size": [true]}}]})"); });
  EXPECT_TRUE(has(e, "presets/p.json:1:") && has(e, "runs[0].set.size[0]: expected a string or a number, got boolean"))
      << e;
  e = error_of<UsageError>([] { preset_of(R"({"runs": [{"experiment": "occupancy", "reps": 4294967297}]})"); });
  EXPECT_TRUE(has(e, "runs[0].reps: expected a positive integer (at most 100000), got 4294967297")) << e;
  e = error_of<UsageError>([] { preset_of(R"({"runs": [{"experiment": "occupancy", "warmup": 100000000}]})"); });
  EXPECT_TRUE(has(e, "runs[0].warmup")) << e;
  e = error_of<UsageError>([] { preset_of(R"({"runs": [{"experiment": "occupancy"}], "extra": 1})"); });
  EXPECT_TRUE(has(e, "unknown key \"extra\"")) << e;
  e = error_of<UsageError>([] { preset_of(R"({"description": 5, "runs": [{"experiment": "occupancy"}]})"); });
  EXPECT_TRUE(has(e, "presets/p.json:1:") && has(e, "description: expected a string")) << e;
}

TEST(BadInput, APresetNumberPastADoubleNamesItsPlace) {
  auto e = error_of<UsageError>(
      [] { preset_of("{\"runs\": [{\"experiment\": \"occupancy\",\n  \"set\": {\"size\": [1e400]}}]}"); });
  EXPECT_TRUE(has(e, "presets/p.json:2:")) << e;
  EXPECT_TRUE(has(e, "1e400")) << e;
}

TEST(BadInput, APresetEntrysUnknownNamesNameThePresetAndTheEntry) {
  Registry registry;
  register_all_experiments(registry);
  Preset p = preset_of(
      "{\"runs\": [{\"experiment\": \"occupancy\"},\n"
      "          {\"experiment\": \"occupancy\", \"set\": {\"sise\": [1]}}]}");
  auto e = error_of<UsageError>([&] { check_requests(registry, p.runs); });
  EXPECT_TRUE(has(e, "presets/p.json:2:11: runs[1]: experiment 'occupancy' has no parameter 'sise'")) << e;
  p = preset_of(R"({"runs": [{"experiment": "nope"}]})");
  e = error_of<UsageError>([&] { check_requests(registry, p.runs); });
  EXPECT_TRUE(has(e, "runs[0]: unknown experiment 'nope'")) << e;
  p = preset_of(R"({"runs": [{"experiment": "occupancy", "set": {"size": ["big"]}}]})");
  e = error_of<UsageError>([&] { check_requests(registry, p.runs); });
  EXPECT_TRUE(has(e, "presets/p.json:1:") && has(e, "runs[0]: experiment 'occupancy': invalid value 'big'")) << e;
}

TEST(BadInput, APresetThatIsAFolderOrADeviceIsRefusedByName) {
  auto dir = fresh_dir("presets");
  fs::create_directories(dir / "folder.json");
  auto e = error_of<UsageError>([&] { load_preset(dir.string(), "folder"); });
  EXPECT_TRUE(has(e, "is a folder, not a regular file")) << e;
  e = error_of<UsageError>([&] { load_preset(dir.string(), "/dev/zero"); });
  EXPECT_TRUE(has(e, "/dev/zero: the preset is a character device")) << e;
  spit(dir / "bin.json", std::string("\x7f"
                                     "ELF\0\0",
                                     6));
  e = error_of<UsageError>([&] { load_preset(dir.string(), "bin"); });
  EXPECT_TRUE(has(e, "not a text file")) << e;
  // list --presets names a broken one, with its file, instead of failing
  spit(dir / "desc.json", R"({"description": ["x"], "runs": [{"experiment": "occupancy"}]})");
  bool found = false;
  for (const auto& p : list_presets(dir.string()))
    if (p.name == "desc") {
      found = true;
      EXPECT_TRUE(has(p.description, "desc.json:1:")) << p.description;
    }
  EXPECT_TRUE(found);
}

// ---- scenes

std::string scene_error(const std::string& text) {
  return error_of<oit::SceneError>([&] { oit::parse_scene("s.json", text); });
}

std::string scene_with(const std::string& generator, const std::string& params, const std::string& view = "") {
  return R"({"materials": {"m": {"alpha": 0.5}}, "objects": [{"generator": ")" + generator +
         R"(", "material": "m", "params": )" + params + R"(}], "views": {"v": )" +
         (view.empty() ? R"({"eye": [0, 0, 3]})" : view) + "}}";
}

TEST(BadInput, SceneCountsAreWholeAndSizesAboveZero) {
  EXPECT_TRUE(has(scene_error(scene_with("planes", R"({"count": 2.5})")), "expected a whole number"));
  EXPECT_TRUE(has(scene_error(scene_with("hairball", R"({"strands": 10.7})")), "/objects/0/params/strands"));
  EXPECT_TRUE(has(scene_error(scene_with("hairball", R"({"segment_length": 0})")), "above 0"));
  EXPECT_TRUE(has(scene_error(scene_with("hairball", R"({"radius": 0})")), "above 0"));
  EXPECT_TRUE(has(scene_error(scene_with("strands", R"({"head_radius": 0})")), "above 0"));
  auto model = R"({"materials": {"m": {"alpha": 0.5}}, "objects": [{"generator": "model", "file": "x.obj",
      "material": "m", "params": {"grid": [2, 2.5, 1]}}], "views": {"v": {"eye": [0, 0, 3]}}})";
  EXPECT_TRUE(has(scene_error(model), "/objects/0/params/grid/1: expected a whole number")) << scene_error(model);
  auto e = scene_error(scene_with("planes", "{}", R"({"eye": [0, 3, 0], "up": [0, 1, 0]})"));
  EXPECT_TRUE(has(e, "\"up\" is parallel to the view direction")) << e;
  EXPECT_EQ(scene_error(scene_with("planes", R"({"count": 3, "depth": 0})")), "(no error)");  // coplanar is data
}

TEST(BadInput, ASceneNumberPastADoubleNamesItsPlace) {
  auto e = scene_error(
      "{\"materials\": {\"m\": {\"alpha\": 0.5}},\n \"objects\": [{\"generator\": \"planes\", "
      "\"material\": \"m\", \"params\": {\"count\": 1e400}}]}");
  EXPECT_TRUE(has(e, "s.json:2:")) << e;
  EXPECT_TRUE(has(e, "1e400")) << e;
}

TEST(BadInput, ASceneFolderOrDeviceIsRefusedByName) {
  auto dir = fresh_dir("scenes");
  fs::create_directories(dir / "x.json");
  auto e = error_of<oit::SceneError>([&] { oit::load_scene((dir / "x.json").string()); });
  EXPECT_TRUE(has(e, "is a folder, not a regular file")) << e;
  e = error_of<oit::SceneError>([&] { oit::load_scene("/dev/zero"); });
  EXPECT_TRUE(has(e, "character device")) << e;
}

TEST(BadInput, AMeshTooLargeIsRefusedBeforeItIsBuiltNamingFileAndParameters) {
  auto s = oit::parse_scene("hb.json", scene_with("hairball", R"({"strands": 10000000, "segments": 10000000})"));
  auto t0 = std::chrono::steady_clock::now();
  auto e = error_of<oit::SceneError>([&] { oit::build_mesh(s, s.view("v"), oit::Detail::Full); });
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 2.0);
  EXPECT_TRUE(has(e, "hb.json: /objects/0 (hairball): strands 1e+07 x segments 1e+07")) << e;
  EXPECT_TRUE(has(e, "the most oitbench builds is 4 GiB")) << e;
  // A model: its file is read (it is small), its instances are not made.
  auto dir = fresh_dir("model");
  spit(dir / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  spit(dir / "grid.json", R"({"materials": {"m": {"alpha": 0.5}}, "objects": [{"generator": "model",
      "file": "tri.obj", "material": "m", "params": {"grid": [10000, 10000, 10000]}}],
      "views": {"v": {"eye": [0, 0, 3]}}})");
  auto g = oit::load_scene((dir / "grid.json").string());
  e = error_of<oit::SceneError>([&] { oit::build_mesh(g, g.view("v"), oit::Detail::Full); });
  EXPECT_TRUE(has(e, "grid.json: /objects/0 (model): ")) << e;
  EXPECT_TRUE(has(e, "tri.obj (1 triangles) x grid 10000 x 10000 x 10000")) << e;
  // The same scenes at a size that fits build.
  auto fits = oit::parse_scene("hb.json", scene_with("hairball", R"({"strands": 3, "segments": 4})"));
  EXPECT_EQ(oit::build_mesh(fits, fits.view("v"), oit::Detail::Full).polygons(), 3u * 4 * 3 * 2);  // 3-sided tubes
  // A cap of its own (the fuzz harness's) is honoured too.
  EXPECT_THROW(oit::build_mesh(fits, fits.view("v"), oit::Detail::Full, false, 100), oit::SceneError);
}

// ---- isolation and interruption

TEST(BadInput, StaleCaseFoldersOfDeadRunsAreRemovedOthersKept) {
  auto dir = fresh_dir("tmp");
  pid_t dead = fork();
  if (dead == 0) _exit(0);
  waitpid(dead, nullptr, 0);
  const std::string stale = "oitbench-case-" + std::to_string(dead) + "-abcdef";
  const std::string mine = "oitbench-case-" + std::to_string(getpid()) + "-abcdef";
  const std::string other = "oitbench-case-1-abcdef";  // a living process (init): left alone
  const std::string old_style = "oitbench-case-XyZ123";
  for (const auto& n : {stale, mine, other, old_style}) fs::create_directories(dir / n / "inner");
  spit(dir / stale / "case.csv", "x\n");
  EXPECT_EQ(remove_stale_case_dirs(dir.string()), 1u);
  EXPECT_FALSE(fs::exists(dir / stale));
  for (const auto& n : {mine, other, old_style}) EXPECT_TRUE(fs::exists(dir / n)) << n;
}

TEST(BadInput, AStopRequestEndsACaseBeforeItsNextPass) {
  PassTimer timer(false, false);
  request_stop_for_test(SIGINT);
  EXPECT_THROW({ auto s = timer.cpu_pass("resolve"); }, Interrupted);
  request_stop_for_test(0);
  EXPECT_FALSE(stop_requested());
}

TEST(BadInputDeathTest, TheWatchdogCutsAStuckRunShort3SecondsAfterCtrlC) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        Watchdog w(600, "out.csv");
        w.set_current("occupancy size=1");
        request_stop_for_test(SIGINT);
        std::this_thread::sleep_for(std::chrono::seconds(30));  // a draw that does not return
        std::_Exit(0);
      },
      ::testing::ExitedWithCode(130), "interrupted; 'occupancy size=1' did not reach the end of a pass");
}

TEST(BadInputDeathTest, ASecondCtrlCExitsAtOnce) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        SignalGuard g;
        raise(SIGINT);
        if (!g.stopped()) std::_Exit(2);
        raise(SIGINT);
        std::_Exit(0);
      },
      ::testing::ExitedWithCode(130), "interrupted again");
}

TEST(BadInput, TheWatchdogPrintsAHeartbeatDuringALongStep) {
  ::testing::internal::CaptureStderr();
  {
    Watchdog w(600, "out.csv", true);
    w.set_current("oit technique=BASE-IS");
    std::this_thread::sleep_for(std::chrono::milliseconds(static_cast<int>(Watchdog::kHeartbeatSeconds * 1000) + 900));
  }
  std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_TRUE(has(err, "still running 'oit technique=BASE-IS'")) << err;
  ::testing::internal::CaptureStderr();
  {
    Watchdog quiet(600, "out.csv", false);
    std::this_thread::sleep_for(std::chrono::milliseconds(static_cast<int>(Watchdog::kHeartbeatSeconds * 1000) + 900));
  }
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

}  // namespace
}  // namespace oitbench
