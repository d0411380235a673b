// Drivers as a choice (backends/drivers.hpp): what `info --drivers` lists, the second driver every
// Debian machine has (zink over lavapipe) running the smoke preset valid with the validators
// unchanged, rows recording the driver, and the bad inputs.
#include <set>

#include "support/test_support.hpp"

namespace oitbench::test {

namespace {
bool contains(const std::string& s, const std::string& what) { return s.find(what) != std::string::npos; }
}  // namespace

TEST(Drivers, InfoListsLlvmpipeAndZinkAsUsable) {
  auto r = run_oitbench({"info", "--drivers"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "ok: llvmpipe (LLVM")) << r.out;
  EXPECT_TRUE(contains(r.out, "ok: zink (llvmpipe")) << r.out;
  EXPECT_TRUE(contains(r.out, "egl-device-0")) << r.out;
}

TEST(Drivers, SmokePresetRunsValidOnZinkAndRowsNameTheDriver) {
  auto dir = temp_dir("zink");
  auto out = dir / "smoke.csv";
  auto r =
      run_oitbench({"run", "--preset", "smoke-test", "--driver", "zink", "--out", out.string(), "--no-progress"}, 600);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(contains(r.err, "XDG_RUNTIME_DIR")) << "zink's warning should be silenced: " << r.err;
  auto rows = read_csv_rows(out);
  ASSERT_FALSE(rows.empty());
  std::set<std::string> experiments;
  for (const auto& row : rows) {
    EXPECT_EQ(row.at("status"), "ok") << row.at("experiment") << " " << row.at("parameters") << ": "
                                      << row.at("reason");
    EXPECT_EQ(row.at("driver"), "zink-lavapipe");
    EXPECT_TRUE(contains(row.at("gl_renderer"), "zink")) << row.at("gl_renderer");
    experiments.insert(row.at("experiment"));
  }
  EXPECT_EQ(experiments, std::set<std::string>{"occupancy"});
}

TEST(Drivers, TheQuickOitGridRunsValidOnZink) {
  auto dir = temp_dir("zink-oit");
  auto out = dir / "oit.csv";
  auto r = run_oitbench({"run", "oit", "--quick", "--driver", "zink", "--out", out.string(), "--no-progress"}, 600);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto rows = read_csv_rows(out);
  std::set<std::string> techniques;
  for (const auto& row : rows) {
    EXPECT_EQ(row.at("status"), "ok") << row.at("technique") << " " << row.at("scene") << ": " << row.at("reason");
    EXPECT_EQ(row.at("driver"), "zink-lavapipe");
    techniques.insert(row.at("technique"));
  }
  EXPECT_EQ(techniques.size(), 5u);
}

TEST(Drivers, TheDefaultRowsNameLlvmpipe) {
  auto dir = temp_dir("llvmpipe");
  auto out = dir / "occ.csv";
  auto r = run_oitbench({"run", "occupancy", "--quick", "--set", "size=1", "--out", out.string(), "--no-progress"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const auto& row : read_csv_rows(out)) EXPECT_EQ(row.at("driver"), "llvmpipe");
}

TEST(Drivers, AnUnknownDriverExitsTwoListingTheDrivers) {
  auto r = run_oitbench({"run", "occupancy", "--quick", "--driver", "nosuch"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "unknown driver 'nosuch'")) << r.err;
  EXPECT_TRUE(contains(r.err, "llvmpipe, zink, softpipe")) << r.err;
}

TEST(Drivers, ADriverWithoutGl45IsUnsupportedWithTheVersionItOffered) {
  auto dir = temp_dir("softpipe");
  auto out = dir / "sp.csv";
  auto r = run_oitbench({"run", "occupancy", "--quick", "--driver", "softpipe", "--out", out.string()});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  auto rows = read_csv_rows(out);
  ASSERT_FALSE(rows.empty());
  for (const auto& row : rows) {
    EXPECT_EQ(row.at("status"), "unsupported");
    EXPECT_TRUE(contains(row.at("reason"), "offers OpenGL 3.")) << row.at("reason");
    EXPECT_TRUE(contains(row.at("gl_version"), "3.")) << row.at("gl_version");
    EXPECT_EQ(row.at("median_ms"), "");
  }
}

}  // namespace oitbench::test
