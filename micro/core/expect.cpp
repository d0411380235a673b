#include "core/expect.hpp"

#include <fnmatch.h>

#include <algorithm>
#include <sstream>

#include "core/files.hpp"
#include "core/params.hpp"

namespace oitbench {

namespace {

constexpr const char* kStatuses[] = {"invalid", "unsupported", "error", "timeout", "flaky"};
constexpr size_t kMaxBaselineBytes = 16u << 20;

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

// The line without its comment: `#` at its start or after a blank.
std::string without_comment(const std::string& line) {
  for (size_t i = 0; i < line.size(); ++i)
    if (line[i] == '#' && (i == 0 || line[i - 1] == ' ' || line[i - 1] == '\t')) return line.substr(0, i);
  return line;
}

bool matches(const std::string& pattern, const std::string& key) {
  return fnmatch(pattern.c_str(), key.c_str(), 0) == 0;
}

// A reason on one line, short enough for a comment.
std::string one_line(std::string s, size_t most = 160) {
  std::replace_if(
      s.begin(), s.end(), [](char c) { return c == '\n' || c == '\r' || c == '\t'; }, ' ');
  return s.size() > most ? s.substr(0, most) + "..." : s;
}

}  // namespace

std::vector<Expectation> parse_expectations(const std::string& text, const std::string& path) {
  std::vector<Expectation> out;
  std::istringstream in(text);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    const std::string body = trimmed(without_comment(line));
    if (body.empty()) continue;
    const std::string where = path + ":" + std::to_string(n);
    std::istringstream words(body);
    std::string pattern, status, extra;
    words >> pattern >> status >> extra;
    if (status.empty() || !extra.empty())
      throw UsageError(where + ": expected 'PATTERN STATUS' (a case key or a glob of one, then a status), got '" +
                       one_line(body, 80) + "'");
    if (std::find(std::begin(kStatuses), std::end(kStatuses), status) == std::end(kStatuses))
      throw UsageError(where + ": unknown status '" + status +
                       "'; valid: invalid, unsupported, error, timeout, flaky (a case no line names is expected ok)");
    out.push_back({pattern, status, where});
  }
  return out;
}

std::vector<Expectation> load_expectations(const std::string& path) {
  return parse_expectations(read_text_file(path, "expected-status file (--expect)", kMaxBaselineBytes), path);
}

Verdict judge(const std::vector<Expectation>& baseline, const Outcome& o) {
  const std::string got = status_name(o.status);
  const auto line =
      std::find_if(baseline.begin(), baseline.end(), [&](const Expectation& e) { return matches(e.pattern, o.key); });
  if (line == baseline.end()) {
    if (o.status == Status::Ok) return {};
    return {false, "new " + got + ": " + one_line(o.reason), nullptr};
  }
  Verdict v{true, "", &*line};
  if (line->status == "flaky" || line->status == got) return v;
  v.expected = false;
  if (o.status == Status::Ok)
    v.message = "fixed: expected " + line->status + " (" + line->where + "), now ok; update the list";
  else
    v.message = "expected " + line->status + " (" + line->where + "), got " + got + ": " + one_line(o.reason);
  return v;
}

std::vector<std::string> unmatched_patterns(const std::vector<Expectation>& baseline,
                                            const std::vector<std::string>& keys) {
  return unmatched_patterns(baseline, [&](const std::function<bool(const std::string&)>& visit) {
    for (const auto& k : keys)
      if (!visit(k)) return;
  });
}

std::vector<std::string> unmatched_patterns(const std::vector<Expectation>& baseline, const KeyWalk& walk) {
  std::vector<char> matched(baseline.size(), 0);
  size_t left = baseline.size();
  if (left > 0)
    walk([&](const std::string& key) {
      for (size_t i = 0; i < baseline.size(); ++i)
        if (!matched[i] && matches(baseline[i].pattern, key)) {
          matched[i] = 1;
          --left;
        }
      return left > 0;
    });
  std::vector<std::string> out;
  for (size_t i = 0; i < baseline.size(); ++i)
    if (!matched[i]) out.push_back(baseline[i].where + ": '" + baseline[i].pattern + "' matches no case of this run");
  return out;
}

std::string expectation_text(const std::vector<Outcome>& outcomes, const std::vector<Expectation>& kept,
                             const std::string& header) {
  std::string s = header;
  std::vector<const Outcome*> failed;
  for (const auto& o : outcomes)
    if (o.status != Status::Ok) failed.push_back(&o);
  std::stable_sort(failed.begin(), failed.end(), [](const Outcome* a, const Outcome* b) { return a->key < b->key; });
  for (const auto& e : kept)
    if (e.status == "flaky") s += e.pattern + " flaky  # kept from " + e.where + "\n";
  for (const Outcome* o : failed) {
    const bool flaky = std::any_of(kept.begin(), kept.end(), [&](const Expectation& e) {
      return e.status == "flaky" && matches(e.pattern, o->key);
    });
    if (!flaky) s += o->key + " " + status_name(o->status) + "  # " + one_line(o->reason) + "\n";
  }
  return s;
}

}  // namespace oitbench
