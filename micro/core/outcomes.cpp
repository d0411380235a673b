#include "core/outcomes.hpp"

#include <cstdio>
#include <fstream>

#include "core/files.hpp"
#include "core/junit.hpp"

namespace oitbench {

namespace {

void write_file(const std::string& path, const std::string& text, const std::string& option) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f << text;
  f.close();
  if (!f) throw FileError(option + " " + path + ": cannot write the file");
}

std::string junit_report(const RunOptions& o, const std::vector<Outcome>& outcomes,
                         const std::vector<Verdict>& verdicts, const Row& run) {
  std::vector<std::pair<std::string, std::string>> props;
  for (const auto& [name, column] : std::vector<std::pair<std::string, std::string>>{{"driver", "driver"},
                                                                                     {"renderer", "gl_renderer"},
                                                                                     {"gl_version", "gl_version"},
                                                                                     {"commit", "git_sha"},
                                                                                     {"run_id", "run_id"},
                                                                                     {"backend", "backend"},
                                                                                     {"device", "device"},
                                                                                     {"hostname", "hostname"},
                                                                                     {"preset", "preset"},
                                                                                     {"shard", "shard"}})
    if (run.count(column) && !run.at(column).empty()) props.emplace_back(name, run.at(column));
  if (!o.expect.empty()) props.emplace_back("expect", o.expect);
  std::string suite = "oitbench run";
  if (!o.preset_name.empty()) suite += " --preset " + o.preset_name;
  if (o.shard.active()) suite += " --shard " + o.shard.text();
  return junit_xml(suite, props, outcomes, verdicts);
}

std::string expect_header(const Row& run) {
  auto col = [&](const char* k) { return run.count(k) ? run.at(k) : std::string(); };
  return "# oitbench: the outcomes this run expects (PATTERN STATUS per line; see docs/ci.md)\n# driver " +
         col("driver") + ", " + col("gl_renderer") + ", commit " + col("git_sha") + ", preset " + col("preset") +
         (col("shard").empty() ? "" : ", shard " + col("shard")) + "\n";
}

}  // namespace

std::string write_expect_path(const RunOptions& o) {
  if (!o.write_expect.empty()) return o.write_expect;
  if (!o.expect.empty() && o.out != "-") return o.out + ".expect";
  return "";
}

int report_outcomes(const RunOptions& o, const std::vector<Expectation>& baseline, const std::vector<Outcome>& outcomes,
                    const std::vector<std::string>& unmatched, const Row& run, int code) {
  std::vector<Verdict> verdicts;
  size_t unexpected = 0, expected_failures = 0;
  if (!o.expect.empty()) {
    for (const auto& w : unmatched) std::fprintf(stderr, "oitbench: warning: --expect %s\n", w.c_str());
    for (const auto& out : outcomes) {
      verdicts.push_back(judge(baseline, out));
      if (!verdicts.back().expected) {
        ++unexpected;
        std::fprintf(stderr, "oitbench: unexpected: %s: %s\n", out.key.c_str(), verdicts.back().message.c_str());
      } else if (out.status != Status::Ok) {
        ++expected_failures;
      }
    }
  }
  if (!o.junit.empty()) write_file(o.junit, junit_report(o, outcomes, verdicts, run), "--junit");
  if (const auto path = write_expect_path(o); !path.empty())
    write_file(path, expectation_text(outcomes, baseline, expect_header(run)), "--write-expect");
  if (o.expect.empty()) return code;
  std::fprintf(stderr, "oitbench: --expect %s: %zu case(s), %zu unexpected, %zu expected not ok%s\n", o.expect.c_str(),
               outcomes.size(), unexpected, expected_failures,
               write_expect_path(o).empty() ? "" : ("; this run's list: " + write_expect_path(o)).c_str());
  if (code == 130) return code;
  return unexpected > 0 ? kExitUnexpected : 0;
}

}  // namespace oitbench
