#include "core/junit.hpp"

#include <cmath>
#include <cstdio>

namespace oitbench {

namespace {

// Text for an attribute or an element: the five entities, and no control characters XML 1.0 forbids.
std::string xml_escaped(const std::string& s) {
  std::string out;
  for (char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    switch (ch) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        if (c < 0x20 && ch != '\n' && ch != '\t' && ch != '\r')
          out += ' ';
        else
          out += ch;
    }
  }
  return out;
}

std::string attr(const std::string& name, const std::string& value) {
  return " " + name + "=\"" + xml_escaped(value) + "\"";
}

std::string seconds(double ms) {
  if (!std::isfinite(ms)) return "0";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6f", ms / 1000);
  return buf;
}

struct Counts {
  int failures = 0, errors = 0, skipped = 0;
};

// The element inside a testcase, if any; counts it.
std::string case_body(const Outcome& o, const Verdict* v, Counts& n) {
  const std::string status = status_name(o.status);
  auto element = [&](const char* tag, const std::string& type, const std::string& message) {
    return std::string("      <") + tag + attr("type", type) + attr("message", message) + ">" + xml_escaped(o.reason) +
           "</" + tag + ">\n";
  };
  if (v && !v->expected) {  // a new failure, another status than expected, or fixed
    ++n.failures;
    return element("failure", "unexpected " + status, v->message);
  }
  if (o.status == Status::Ok) return "";
  if (v && v->line) {
    ++n.skipped;
    return "      <skipped" +
           attr("message", "expected " + v->line->status + " (" + v->line->where + "): " + o.reason) + "/>\n";
  }
  if (o.status == Status::Unsupported) {
    ++n.skipped;
    return "      <skipped" + attr("message", o.reason) + "/>\n";
  }
  if (o.status == Status::Invalid) {
    ++n.failures;
    return element("failure", status, o.reason);
  }
  ++n.errors;
  return element("error", status, o.reason);
}

}  // namespace

std::string junit_xml(const std::string& suite, const std::vector<std::pair<std::string, std::string>>& properties,
                      const std::vector<Outcome>& outcomes, const std::vector<Verdict>& verdicts) {
  Counts n;
  double total_ms = 0;
  std::string cases;
  for (size_t i = 0; i < outcomes.size(); ++i) {
    const Outcome& o = outcomes[i];
    if (std::isfinite(o.median_ms)) total_ms += o.median_ms;
    const std::string body = case_body(o, i < verdicts.size() ? &verdicts[i] : nullptr, n);
    cases += "    <testcase" + attr("name", o.key) + attr("classname", "oitbench." + o.experiment) +
             attr("time", seconds(o.median_ms)) + (body.empty() ? "/>\n" : ">\n" + body + "    </testcase>\n");
  }
  const std::string counts = attr("tests", std::to_string(outcomes.size())) +
                             attr("failures", std::to_string(n.failures)) + attr("errors", std::to_string(n.errors)) +
                             attr("skipped", std::to_string(n.skipped)) + attr("time", seconds(total_ms));
  std::string s = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites" + attr("name", "oitbench") + counts + ">\n";
  s += "  <testsuite" + attr("name", suite) + counts + ">\n    <properties>\n";
  for (const auto& [k, v] : properties) s += "      <property" + attr("name", k) + attr("value", v) + "/>\n";
  s += "    </properties>\n" + cases + "  </testsuite>\n</testsuites>\n";
  return s;
}

}  // namespace oitbench
