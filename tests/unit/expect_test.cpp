// --expect's baseline files (parsing, bad lines named FILE:LINE), the verdict on each outcome, the
// patterns that match nothing, the list a run writes for the next one, and the JUnit XML text.
#include "core/expect.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/junit.hpp"
#include "core/params.hpp"

namespace oitbench {
namespace {

std::string usage_error(const std::string& text) {
  try {
    parse_expectations(text, "E.txt");
  } catch (const UsageError& e) {
    return e.what();
  }
  return "";
}

Outcome outcome(const std::string& key, Status s, const std::string& reason = "") {
  return {key, key.substr(0, key.find('/')), s, reason, s == Status::Ok ? 12.5 : std::nan("")};
}

TEST(Expect, ParsesPatternsStatusesAndComments) {
  auto b = parse_expectations(
      "# a comment\n\noit/*/technique=BMA-* invalid  # the driver miscompiles it\n"
      "  sort/256x256/algorithm=shell   error\nspinlock/* flaky\nocc[u]pancy/* timeout\nx/y#z unsupported\n",
      "E.txt");
  ASSERT_EQ(b.size(), 5u);
  EXPECT_EQ(b[0].pattern, "oit/*/technique=BMA-*");
  EXPECT_EQ(b[0].status, "invalid");
  EXPECT_EQ(b[0].where, "E.txt:3");
  EXPECT_EQ(b[1].where, "E.txt:4");
  EXPECT_EQ(b[4].pattern, "x/y#z");  // '#' starts a comment only at a line's start or after a blank
}

TEST(Expect, MalformedLinesAndUnknownStatusesNameFileAndLine) {
  EXPECT_NE(usage_error("ok/* invalid\noit/*\n").find("E.txt:2: expected 'PATTERN STATUS'"), std::string::npos);
  EXPECT_NE(usage_error("a b c\n").find("E.txt:1: expected 'PATTERN STATUS'"), std::string::npos);
  const std::string e = usage_error("\n\noit/* broken\n");
  EXPECT_NE(e.find("E.txt:3: unknown status 'broken'"), std::string::npos) << e;
  EXPECT_NE(e.find("invalid, unsupported, error, timeout, flaky"), std::string::npos) << e;
  EXPECT_NE(usage_error("oit/* ok\n").find("unknown status 'ok'"), std::string::npos);
}

TEST(Expect, OnlyUnexpectedOutcomesFail) {
  const auto b = parse_expectations("oit/*/technique=BMA-IS invalid\nsort/* flaky\noit/* unsupported\n", "E");
  // Expected: ok and unlisted; the listed status; anything under flaky; the first matching line decides.
  EXPECT_TRUE(judge(b, outcome("occupancy/256x256/size=1", Status::Ok)).expected);
  EXPECT_TRUE(judge(b, outcome("oit/64x64/technique=BMA-IS", Status::Invalid)).expected);
  EXPECT_TRUE(judge(b, outcome("sort/64x64/n=8", Status::Error)).expected);
  EXPECT_TRUE(judge(b, outcome("sort/64x64/n=8", Status::Ok)).expected);
  EXPECT_TRUE(judge(b, outcome("oit/64x64/technique=BASE-IS", Status::Unsupported)).expected);
  // Unexpected: a new failure, another failure than listed, a listed failure that now passes.
  auto v = judge(b, outcome("occupancy/256x256/size=1", Status::Invalid, "pixel (3,4) differs"));
  EXPECT_FALSE(v.expected);
  EXPECT_EQ(v.message, "new invalid: pixel (3,4) differs");
  v = judge(b, outcome("oit/64x64/technique=BMA-IS", Status::Error, "shader.glsl:3: syntax"));
  EXPECT_FALSE(v.expected);
  EXPECT_EQ(v.message, "expected invalid (E:1), got error: shader.glsl:3: syntax");
  v = judge(b, outcome("oit/64x64/technique=BMA-IS", Status::Ok));
  EXPECT_FALSE(v.expected);
  EXPECT_EQ(v.message, "fixed: expected invalid (E:1), now ok; update the list");
}

TEST(Expect, PatternsThatMatchNoCaseAreListed) {
  const auto b = parse_expectations("oit/* invalid\nnosuch/* error\n", "E");
  const auto w = unmatched_patterns(b, {"oit/64x64/technique=BMA-IS", "sort/64x64/n=8"});
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0], "E:2: 'nosuch/*' matches no case of this run");
  EXPECT_EQ(unmatched_patterns(b, {"oit/1x1", "nosuch/1x1"}).size(), 0u);
}

TEST(Expect, TheWrittenListExpectsThisRunsOutcomes) {
  const std::vector<Outcome> run = {
      outcome("sort/8x8/n=2", Status::Error, "boom"), outcome("oit/8x8/technique=B", Status::Invalid, "two\nlines"),
      outcome("oit/8x8/technique=A", Status::Ok), outcome("spin/8x8/v=1", Status::Timeout, "killed")};
  const auto kept = parse_expectations("spin/* flaky\noit/* invalid\n", "E");
  const std::string text = expectation_text(run, kept, "# header\n");
  EXPECT_EQ(text,
            "# header\nspin/* flaky  # kept from E:1\noit/8x8/technique=B invalid  # two lines\n"
            "sort/8x8/n=2 error  # boom\n");
  // Read back, it expects every outcome of the run that wrote it.
  const auto again = parse_expectations(text, "W");
  for (const auto& o : run) EXPECT_TRUE(judge(again, o).expected) << o.key;
  // And catches a change.
  EXPECT_FALSE(judge(again, outcome("oit/8x8/technique=A", Status::Invalid, "x")).expected);
  EXPECT_FALSE(judge(again, outcome("sort/8x8/n=2", Status::Ok)).expected);
}

TEST(Junit, OneTestcasePerCaseWithFailuresErrorsAndSkips) {
  const std::vector<Outcome> run = {
      outcome("oit/8x8/technique=A", Status::Ok), outcome("oit/8x8/technique=B", Status::Invalid, "pixel <1,2> & more"),
      outcome("sort/8x8/n=2", Status::Error, "boom"), outcome("spin/8x8/v=1", Status::Unsupported, "no interlock")};
  const std::string x = junit_xml("oitbench run", {{"driver", "llvmpipe"}, {"commit", "abc\"1"}}, run, {});
  EXPECT_NE(x.find("<testsuites name=\"oitbench\" tests=\"4\" failures=\"1\" errors=\"1\" skipped=\"1\""),
            std::string::npos)
      << x;
  EXPECT_NE(x.find("<property name=\"commit\" value=\"abc&quot;1\"/>"), std::string::npos) << x;
  EXPECT_NE(x.find("<testcase name=\"oit/8x8/technique=A\" classname=\"oitbench.oit\" time=\"0.012500\"/>"),
            std::string::npos)
      << x;
  EXPECT_NE(x.find("<failure type=\"invalid\" message=\"pixel &lt;1,2&gt; &amp; more\">"), std::string::npos) << x;
  EXPECT_NE(x.find("<error type=\"error\" message=\"boom\">boom</error>"), std::string::npos) << x;
  EXPECT_NE(x.find("<skipped message=\"no interlock\"/>"), std::string::npos) << x;
  // Under --expect: the expected failure skipped with the line that expected it, the unexpected one a failure.
  const auto b = parse_expectations("oit/*/technique=B invalid\n", "E");
  std::vector<Verdict> v;
  for (const auto& o : run) v.push_back(judge(b, o));
  const std::string y = junit_xml("s", {}, run, v);
  EXPECT_NE(y.find("<skipped message=\"expected invalid (E:1): pixel"), std::string::npos) << y;
  EXPECT_NE(y.find("<failure type=\"unexpected error\" message=\"new error: boom\">"), std::string::npos) << y;
  EXPECT_NE(y.find("failures=\"2\" errors=\"0\" skipped=\"1\""), std::string::npos) << y;
}

}  // namespace
}  // namespace oitbench
