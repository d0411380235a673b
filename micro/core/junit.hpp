#pragma once
// JUnit XML (--junit FILE), the report GitLab, Jenkins and CI dashboards read: <testsuites> with one
// <testsuite> holding the run's <properties> (driver, renderer, commit, ...) and one <testcase> per case
// (name: its case key, classname: oitbench.EXPERIMENT, time: its median in seconds). A case that did not
// end ok has a <failure> (invalid), an <error> (error, timeout) or is <skipped> (unsupported), its message
// the reason; under --expect an expected outcome is <skipped> with what expected it, an unexpected one a
// <failure> saying why (a "fixed" case included).
#include <string>
#include <utility>
#include <vector>

#include "core/expect.hpp"

namespace oitbench {

// `properties`: name and value, in order. `verdicts`: empty without --expect, else one per outcome.
std::string junit_xml(const std::string& suite, const std::vector<std::pair<std::string, std::string>>& properties,
                      const std::vector<Outcome>& outcomes, const std::vector<Verdict>& verdicts);

}  // namespace oitbench
