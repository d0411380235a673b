// Beyond one driver, on the embedded default (a software renderer): presets' hardware sizes stay unused here
// and list --presets says so; the GPU state columns are empty without NVML and filled through a fake NVML
// (tests/support/fake_nvml.cpp).
#include <cstdlib>
#include <fstream>

#include "core/schema.hpp"
#include "support/test_support.hpp"

namespace oitbench::test {

namespace {
bool contains(const std::string& s, const std::string& what) { return s.find(what) != std::string::npos; }

// A preset folder with one preset, "sized": llvmpipe's 40x30 with 2 repetitions, hardware's 1920x1080 with 50.
std::filesystem::path sized_preset_dir(const std::string& name) {
  auto dir = temp_dir(name);
  std::ofstream(dir / "sized.json") << R"({"description": "sized for the machine",
  "runs": [ {"experiment": "occupancy", "set": {"variant": "dynamic", "size": 4, "draws": 1},
             "resolution": "40x30", "reps": 2, "warmup": 0,
             "hardware": {"resolution": "1920x1080", "reps": 50, "warmup": 3}},
            {"experiment": "occupancy", "set": {"variant": "unrolled", "size": 4, "draws": 1},
             "resolution": "20x10", "reps": 1} ]})";
  return dir;
}

// Sets an environment variable for the child processes of one test.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) { setenv(name, value.c_str(), 1); }
  ~ScopedEnv() { unsetenv(name_); }

 private:
  const char* name_;
};
}  // namespace

TEST(HardwarePresets, ASoftwareRendererRunsEachEntryAtItsOwnSize) {
  auto dir = sized_preset_dir("sized-run");
  auto out = dir / "run.csv";
  auto r =
      run_oitbench({"run", "--preset", "sized", "--presets-dir", dir.string(), "--out", out.string(), "--no-progress"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto rows = read_csv_rows(out);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0]["width"], "40");
  EXPECT_EQ(rows[0]["height"], "30");
  EXPECT_EQ(rows[0]["reps"], "2");
  EXPECT_EQ(rows[0]["warmup"], "0");
  EXPECT_EQ(rows[0]["samples"], "2");
  EXPECT_EQ(rows[1]["width"], "20");
  EXPECT_EQ(rows[1]["reps"], "1");
}

TEST(HardwarePresets, TheCommandLineStillWins) {
  auto dir = sized_preset_dir("sized-cli");
  auto out = dir / "run.csv";
  auto r = run_oitbench({"run", "--preset", "sized", "--presets-dir", dir.string(), "--resolution", "24x16", "--reps",
                         "1", "--out", out.string(), "--no-progress"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto rows = read_csv_rows(out);
  ASSERT_EQ(rows.size(), 2u);
  for (auto& row : rows) {
    EXPECT_EQ(row["width"], "24");
    EXPECT_EQ(row["height"], "16");
    EXPECT_EQ(row["reps"], "1");
  }
}

TEST(HardwarePresets, ListSaysWhichSizeAppliesHere) {
  auto dir = sized_preset_dir("sized-list");
  auto r = run_oitbench({"list", "--presets", "--presets-dir", dir.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "Sizes here: software renderer llvmpipe")) << r.out;
  EXPECT_TRUE(contains(r.out, "software renderer: 40x30, 2 reps, 0 warm-up   <- applies here\n")) << r.out;
  EXPECT_TRUE(contains(r.out, "hardware:          1920x1080, 50 reps, 3 warm-up\n")) << r.out;
  // An entry without "hardware" runs at its own size everywhere (reps 1; warm-up the default 1).
  EXPECT_TRUE(contains(r.out, "software renderer: 20x10, 1 rep, 1 warm-up   <- applies here\n")) << r.out;
  EXPECT_TRUE(contains(r.out, "hardware:          20x10, 1 rep, 1 warm-up (no \"hardware\" entry: the same)\n"))
      << r.out;
}

TEST(HardwarePresets, ListWithoutAContextSaysItCannotTell) {
  auto dir = sized_preset_dir("sized-nocontext");
  auto r =
      run_oitbench({"list", "--presets", "--presets-dir", dir.string(), "--backend", "egl-device", "--device", "999"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "Sizes here: unknown: no GL context could be created (EGL: --device 999 out of range"))
      << r.out;
  EXPECT_FALSE(contains(r.out, "<- applies here")) << r.out;
  EXPECT_TRUE(contains(r.out, "hardware:          1920x1080, 50 reps, 3 warm-up\n")) << r.out;
}

TEST(HardwarePresets, ThePaperPresetsCarryThePapersSizesForHardware) {
  auto r = run_oitbench({"list", "--presets"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* size : {"1920x1080", "1680x1050", "800x800", "800x600"})
    EXPECT_TRUE(contains(r.out, std::string("hardware:          ") + size)) << size << "\n" << r.out;
  EXPECT_FALSE(contains(r.out, "(broken:")) << r.out;
}

TEST(GpuStateColumns, WithoutNvmlTheyAreEmptyAndNothingFails) {
  auto out = temp_dir("nonvml") / "occ.csv";
  auto r = run_oitbench({"run", "occupancy", "--quick", "--set", "size=4", "--out", out.string(), "--no-progress"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto rows = read_csv_rows(out);
  ASSERT_EQ(rows.size(), 2u);
  for (auto& row : rows) {
    EXPECT_EQ(row["status"], "ok") << row["reason"];
    EXPECT_EQ(row["schema"], std::to_string(kCsvSchema));
    for (const char* col :
         {"gpu_driver_version", "gpu_sm_clock_start_mhz", "gpu_sm_clock_end_mhz", "gpu_mem_clock_start_mhz",
          "gpu_mem_clock_end_mhz", "gpu_temp_start_c", "gpu_temp_end_c", "gpu_power_start_w", "gpu_power_end_w"}) {
      ASSERT_TRUE(row.count(col)) << "no column " << col;
      EXPECT_EQ(row[col], "") << col;
    }
    EXPECT_FALSE(contains(row["reason"], "gpu clocks")) << row["reason"];
  }
  auto info = run_oitbench({"info"});
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_TRUE(contains(info.out, "GPU state (NVML): none (GL_VENDOR '")) << info.out;
  EXPECT_TRUE(contains(info.out, "' is not NVIDIA's: no NVML)")) << info.out;
}

TEST(GpuStateColumns, ThroughNvmlEachGroupRecordsItsClocksAndNotesAChange) {
  // The fake NVML's SM clock alternates 1980 and 1410 MHz from reading to reading: each case group (here
  // one: 2 variants x 2 sizes interleaved) starts at 1980 and ends at 1410.
  ScopedEnv nvml("OITBENCH_NVML_LIBRARY", FAKE_NVML_LIBRARY);
  auto out = temp_dir("fakenvml") / "occ.csv";
  auto r = run_oitbench({"run", "occupancy", "--quick", "--set", "size=1,4", "--out", out.string(), "--no-progress"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto rows = read_csv_rows(out);
  ASSERT_EQ(rows.size(), 4u);
  for (auto& row : rows) {
    EXPECT_EQ(row["status"], "ok") << row["reason"];
    EXPECT_EQ(row["gpu_driver_version"], "550.54.15");
    EXPECT_EQ(row["gpu_sm_clock_start_mhz"], "1980");
    EXPECT_EQ(row["gpu_sm_clock_end_mhz"], "1410");
    EXPECT_EQ(row["gpu_mem_clock_start_mhz"], "2619");
    EXPECT_EQ(row["gpu_temp_end_c"], "45");
    EXPECT_EQ(row["gpu_power_start_w"], "350.1");
    EXPECT_TRUE(contains(row["reason"], "gpu clocks changed during the case group: SM 1980 -> 1410 MHz"))
        << row["reason"];
    EXPECT_TRUE(contains(row["env"], "OITBENCH_NVML_LIBRARY=")) << row["env"];
  }
  auto info = run_oitbench({"info"});
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_TRUE(contains(info.out, "GPU state (NVML): NVIDIA A100-SXM4-80GB, driver 550.54.15, SM 1980 MHz")) << info.out;
}

}  // namespace oitbench::test
