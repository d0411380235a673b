// Beyond one driver, on the embedded default (a software renderer): presets' hardware sizes stay unused here
// and list --presets says so; the occupancy experiment's measured occupancy is empty with its reason and its
// measuring variant builds only with GL_NV_shader_thread_group; the GPU state columns are empty without NVML
// and filled through a fake NVML (tests/support/fake_nvml.cpp).
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
  auto r = run_oitbench({"list", "--presets", "--presets-dir", dir.string(), "--driver", "egl-device-999"});
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

class MeasuredOccupancy : public GlTest {};

TEST_F(MeasuredOccupancy, WithoutTheExtensionTheColumnIsEmptyWithItsReason) {
  if (gl().has_extension("GL_NV_shader_thread_group")) GTEST_SKIP() << "this driver can measure";
  auto v = run_case("occupancy", {{"variant", "unrolled"}, {"size", "8"}, {"draws", "1"}});
  EXPECT_TRUE(v.valid) << v.reason;
  EXPECT_EQ(v.metrics.count("measured_occupancy"), 0u);
  EXPECT_EQ(v.metrics.at("measured_occupancy_note"),
            "not measured: the driver does not offer GL_NV_shader_thread_group");
}

TEST_F(MeasuredOccupancy, TheMeasuringVariantBuildsOnlyWithTheExtension) {
  const std::vector<ShaderStage> stages = {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                           {GL_FRAGMENT_SHADER, "occupancy/occupancy.frag"}};
  for (const char* variant : {"VARIANT_DYNAMIC", "VARIANT_UNROLLED"}) {
    Defines defines = {{"SIZE", "4"}, {variant, ""}};
    EXPECT_NO_THROW(shaders().build(stages, defines)) << variant;
    defines.emplace_back("OCCUPANCY_MEASURE", "");
    if (gl().has_extension("GL_NV_shader_thread_group")) {
      EXPECT_NO_THROW(shaders().build(stages, defines)) << variant;
    } else {
      try {
        shaders().build(stages, defines);
        ADD_FAILURE() << variant << ": the measuring variant compiled without GL_NV_shader_thread_group";
      } catch (const ShaderError& e) {
        EXPECT_TRUE(contains(e.what(), "GL_NV_shader_thread_group")) << e.what();
      }
    }
  }
}

// No driver here has the extension; this compiles the measuring variant with its built-ins declared as the
// spec declares them (uniform uint gl_WarpsPerSMNV, gl_SMCountNV; in uint gl_WarpIDNV, gl_SMIDNV,
// gl_ThreadInWarpNV; uint ballotThreadNV(bool)), under other names, so the rest of the GLSL is checked.
TEST_F(MeasuredOccupancy, TheMeasuringVariantTypeChecksAgainstTheExtensionsDeclarations) {
  for (const char* variant : {"VARIANT_DYNAMIC", "VARIANT_UNROLLED"}) {
    auto text =
        shaders().assemble("occupancy/occupancy.frag", {{"SIZE", "16"}, {variant, ""}, {"OCCUPANCY_MEASURE", ""}}).text;
    const std::string ext = "#extension GL_NV_shader_thread_group : require\n";
    auto at = text.find(ext);
    ASSERT_NE(at, std::string::npos) << "the extension is required inside OCCUPANCY_MEASURE";
    text.replace(at, ext.size(),
                 "uniform uint mock_WarpsPerSMNV;\nuniform uint mock_SMCountNV;\nflat in uint mock_WarpIDNV;\n"
                 "flat in uint mock_SMIDNV;\nflat in uint mock_ThreadInWarpNV;\n"
                 "uint mock_ballotThreadNV(bool value) { return value ? 1u : 0u; }\n");
    for (const char* name :
         {"gl_WarpsPerSMNV", "gl_SMCountNV", "gl_WarpIDNV", "gl_SMIDNV", "gl_ThreadInWarpNV", "ballotThreadNV"}) {
      const std::string from = name, to = "mock_" + from.substr(from.rfind('_') == 2 ? 3 : 0);
      for (size_t p = text.find(from); p != std::string::npos; p = text.find(from, p + to.size()))
        if (p < 5 || text.compare(p - 5, 5, "mock_") != 0) text.replace(p, from.size(), to);
    }
    GLuint shader = glCreateShader(GL_FRAGMENT_SHADER);
    const char* src = text.c_str();
    glShaderSource(shader, 1, &src, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    char log[4096] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    EXPECT_TRUE(ok) << variant << ":\n" << log;
    EXPECT_TRUE(contains(text, "mock_ballotThreadNV(!gl_HelperInvocation)")) << text;
  }
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
         {"gpu_driver_version", "gpu_pci_id", "gpu_vbios_version", "gpu_sm_clock_start_mhz", "gpu_sm_clock_end_mhz",
          "gpu_mem_clock_start_mhz", "gpu_mem_clock_end_mhz", "gpu_temp_start_c", "gpu_temp_end_c", "gpu_power_start_w",
          "gpu_power_end_w", "measured_occupancy"}) {
      ASSERT_TRUE(row.count(col)) << "no column " << col;
      EXPECT_EQ(row[col], "") << col;
    }
    EXPECT_FALSE(contains(row["reason"], "gpu clocks")) << row["reason"];
    EXPECT_TRUE(contains(row["measured_occupancy_note"], "GL_NV_shader_thread_group"))
        << row["measured_occupancy_note"];
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
    EXPECT_EQ(row["gpu_pci_id"], "10de:20b2");  // llvmpipe's renderer names no fake device: the first, the A100
    EXPECT_EQ(row["gpu_vbios_version"], "92.00.45.00.06");
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
