// spinlock on the embedded default: every lock inserts exactly, a lock that is never released is
// capped instead of hanging, a hung shader becomes a timeout row, and the validator can fail.
#include "support/test_support.hpp"

namespace oitbench::test {

class Spinlock : public GlTest {};

TEST_F(Spinlock, EveryLockVariantInsertsExactly) {
  for (const char* variant : {"naive", "loop", "helper-guard"}) {
    auto v = run_case("spinlock", {{"variant", variant}, {"layers", "8"}, {"draws", "2"}});
    EXPECT_TRUE(v.valid) << variant << ": " << v.reason;
    EXPECT_EQ(v.metrics.at("capped_updates"), "0") << variant;
    EXPECT_EQ(v.metrics.at("lost_updates"), "0") << variant;
  }
}

TEST_F(Spinlock, InterlockRunsWhereTheDriverHasItAndIsUnsupportedElsewhere) {
  bool has = gl().has_extension("GL_ARB_fragment_shader_interlock") ||
             gl().has_extension("GL_NV_fragment_shader_interlock") ||
             gl().has_extension("GL_INTEL_fragment_shader_ordering");
  if (has) {
    auto v = run_case("spinlock", {{"variant", "interlock"}, {"layers", "8"}});
    EXPECT_TRUE(v.valid) << v.reason;
    return;
  }
  auto out = temp_dir("spinlock_interlock") / "rows.csv";
  auto r = run_oitbench({"run", "spinlock", "--quick", "--set", "variant=interlock", "--out", out.string()});
  EXPECT_EQ(r.exit_code, 3) << r.err;  // nothing ran: every case unsupported
  auto rows = read_csv_rows(out);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].at("status"), "unsupported");
  EXPECT_NE(rows[0].at("reason").find("GL_ARB_fragment_shader_interlock"), std::string::npos) << rows[0].at("reason");
}

TEST_F(Spinlock, ValidatorCatchesAWrongEntry) {
  auto v = run_case("spinlock", {{"variant", "loop"}, {"layers", "4"}, {"fault", "wrong-result"}});
  EXPECT_FALSE(v.valid);
  EXPECT_NE(v.reason.find("pixel (1,1)"), std::string::npos) << v.reason;
  EXPECT_EQ(v.metrics.at("mismatched_pixels"), "1");
}

TEST_F(Spinlock, ALockNeverReleasedIsCappedNotHung) {
  // Only the first fragment of each pixel gets the lock; every later one gives up at spin_cap.
  auto v =
      run_case("spinlock", {{"variant", "no-release"}, {"layers", "4"}, {"draws", "1"}, {"spin_cap", "16"}}, {32, 32});
  EXPECT_FALSE(v.valid);
  EXPECT_EQ(v.metrics.at("capped_updates"), std::to_string(3 * 32 * 32));
  EXPECT_EQ(v.metrics.at("lost_updates"), std::to_string(3 * 32 * 32));
  EXPECT_NE(v.reason.find("gave up at spin_cap"), std::string::npos) << v.reason;
}

TEST_F(Spinlock, AHungCaseBecomesATimeoutRowAndTheRunGoesOn) {
  auto out = temp_dir("spinlock_hang") / "rows.csv";
  // llvmpipe ends any shader loop after 65535 iterations (gallivm's loop budget), so its "hang" is a
  // long finite loop per fragment: at 256x256 a hung case runs ~12 s on a quiet 2-core VM, 6x the 2 s watchdog
  // (at the quick 64x64 it finished in 1.6 s on a quiet machine and the case was not killed).
  auto r = run_oitbench({"run", "spinlock", "--quick", "--reps", "1", "--resolution", "256x256", "--set",
                         "variant=loop,naive", "--set", "fault=hang", "--timeout", "2", "--out", out.string()},
                        120);
  EXPECT_EQ(r.exit_code, 1) << r.err;  // timeouts are failures of the run
  auto rows = read_csv_rows(out);
  ASSERT_EQ(rows.size(), 2u) << r.err;  // the second case ran after the first was killed
  for (const auto& row : rows) {
    EXPECT_EQ(row.at("status"), "timeout");
    EXPECT_NE(row.at("reason").find("watchdog"), std::string::npos) << row.at("reason");
  }
}

}  // namespace oitbench::test
