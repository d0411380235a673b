// Bad input as data: tests/data/bad_options.tsv lists command lines with the exit code and the text the
// message must hold (the option or file it comes from); every line is fed to the binary. And the exit
// table of docs/usage.md, read from the file, checked code by code against a real invocation.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "support/test_support.hpp"

namespace oitbench {
namespace {

namespace fs = std::filesystem;
using namespace test;

const fs::path kSourceDir = fs::path(OITBENCH_TEST_DATA).parent_path().parent_path();

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
    s.replace(at, from.size(), to);
  return s;
}

struct BadLine {
  int line = 0;
  int exit_code = 0;
  std::string message, args;
};

std::vector<BadLine> read_table(const fs::path& path) {
  std::vector<BadLine> lines;
  std::ifstream in(path);
  std::string text;
  for (int n = 1; std::getline(in, text); ++n) {
    if (text.empty() || text[0] == '#') continue;
    size_t a = text.find('\t'), b = text.find('\t', a + 1);
    if (a == std::string::npos || b == std::string::npos)
      throw std::runtime_error(path.string() + ":" + std::to_string(n));
    lines.push_back({n, std::stoi(text.substr(0, a)), text.substr(a + 1, b - a - 1), text.substr(b + 1)});
  }
  return lines;
}

// A scene whose model file is `model` (the engine grid's scene, its model replaced).
std::string scene_with_model(const fs::path& dir, const std::string& name, const std::string& model) {
  auto text = replace_all(slurp(kSourceDir / "scenes" / "engine-grid.json"),
                          "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb", model);
  auto path = dir / (name + ".json");
  std::ofstream(path) << text;
  return path.string();
}

TEST(BadOptions, EveryLineOfTheTableExitsWithItsCodeNamingTheOption) {
  auto dir = temp_dir("bad-options-table");
  const std::string out = (dir / "x.csv").string();
  const std::string nullmodel = scene_with_model(dir, "nullmodel", "/dev/null");
  const std::string dirmodel = scene_with_model(dir, "dirmodel", dir.string());
  // Presets whose hardware set is wrong: the error names the set's line, not the entry's.
  const std::string hwname = (dir / "hwname.json").string(), hwvalue = (dir / "hwvalue.json").string();
  std::ofstream(hwname) << "{\"runs\": [{\"experiment\": \"occupancy\",\n  \"hardware\": {\"set\": {\"sise\": [4]}}}]}";
  std::ofstream(hwvalue)
      << "{\"runs\": [{\"experiment\": \"occupancy\",\n  \"hardware\": {\"set\": {\"size\": [-3]}}}]}";
  auto lines = read_table(fs::path(OITBENCH_TEST_DATA) / "bad_options.tsv");
  ASSERT_GE(lines.size(), 50u);
  for (const auto& l : lines) {
    const bool each_bad = l.args.find("{bad}") != std::string::npos;
    for (std::string bad : {"nan", "inf", "-inf", "-1", "1e300", "1e999", "abc"}) {
      auto expand = [&](std::string s) {
        s = replace_all(s, "{out}", out);
        s = replace_all(s, "{nullmodel}", nullmodel);
        s = replace_all(s, "{dirmodel}", dirmodel);
        s = replace_all(s, "{hwname}", hwname);
        s = replace_all(s, "{hwvalue}", hwvalue);
        return replace_all(s, "{bad}", bad);
      };
      std::vector<std::string> args;
      std::stringstream words(expand(l.args));
      for (std::string w; words >> w;) args.push_back(w);
      auto r = run_oitbench(args, 120);
      const std::string where = "bad_options.tsv:" + std::to_string(l.line) + ": " + expand(l.args) + "\n" + r.err;
      EXPECT_EQ(r.exit_code, l.exit_code) << where;
      EXPECT_NE(r.err.find(expand(l.message)), std::string::npos) << where << "\nexpected: " << expand(l.message);
      EXPECT_FALSE(std::regex_search(r.err, std::regex("[0-9]{30}"))) << "an unreadable number: " << where;
      EXPECT_LT(r.err.size(), 2000u) << where;
      EXPECT_FALSE(fs::exists(out)) << "a refused run created its --out: " << where;
      if (!each_bad) break;
    }
  }
}

// The rows of the first table under "## Exit codes and bad input": code -> meaning.
std::map<int, std::string> exit_table(const std::string& usage) {
  std::map<int, std::string> codes;
  auto at = usage.find("## Exit codes and bad input");
  if (at == std::string::npos) return codes;
  std::stringstream in(usage.substr(at));
  static const std::regex row(R"(^\| (\d+) \| (.+) \|$)");
  bool in_table = false;
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (std::regex_match(line, m, row)) {
      codes[std::stoi(m[1])] = m[2];
      in_table = true;
    } else if (in_table && (line.empty() || line[0] != '|')) {
      break;
    }
  }
  return codes;
}

TEST(BadOptions, TheExitTableOfUsageMdIsWhatTheBinaryDoes) {
  auto codes = exit_table(slurp(kSourceDir / "docs" / "usage.md"));
  ASSERT_EQ(codes.size(), 6u) << "docs/usage.md's exit table not found or changed: extend this test";
  auto dir = temp_dir("exit-table");
  auto out = [&](const std::string& name) { return (dir / (name + ".csv")).string(); };
  const std::vector<std::string> quick = {"run", "occupancy", "--quick", "--set", "size=4", "--no-progress"};
  auto with = [&](std::vector<std::string> more) {
    auto a = quick;
    a.insert(a.end(), more.begin(), more.end());
    return a;
  };
  std::map<int, ProcessResult> ran;
  ran[0] = run_oitbench(with({"--reps", "1", "--out", out("ok")}));
  ran[1] = run_oitbench(with({"--reps", "1", "--set", "fault=compile-error", "--out", out("error")}));
  ran[2] = run_oitbench(with({"--set", "sise=1", "--out", out("usage")}));
  const auto expect = dir / "none.expect";  // every case expected ok: an error row is unexpected
  std::ofstream(expect) << "# no known failures\n";
  ran[4] = run_oitbench(
      with({"--reps", "1", "--set", "fault=compile-error", "--expect", expect.string(), "--out", out("unexpected")}));
  ran[3] = run_oitbench({"run", "spinlock", "--quick", "--driver", "softpipe", "--out", out("unsupported")});
  ran[130] = run_oitbench_interrupted(
      {"run", "occupancy", "--set", "variant=unrolled", "--set", "size=33..232", "--resolution", "200x150", "--set",
       "draws=16", "--reps", "2", "--no-interleave", "--out", out("interrupted"), "--no-progress"},
      out("interrupted"), 1, SIGINT);
  for (const auto& [code, meaning] : codes) {
    ASSERT_TRUE(ran.count(code)) << "docs/usage.md documents exit " << code << " (" << meaning
                                 << ") and this test runs nothing for it";
    EXPECT_EQ(ran[code].exit_code, code) << meaning << "\n" << ran[code].err;
  }
}

}  // namespace
}  // namespace oitbench
