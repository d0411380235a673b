#pragma once
// Helpers shared by the tests: run the oitbench binary, read its CSV, a GL context per test suite.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "backends/backend.hpp"
#include "core/registry.hpp"

namespace oitbench::test {

struct ProcessResult {
  int exit_code = -1;
  std::string out, err;
};

// Runs build/oitbench with the arguments (no shell); `timeout_s` kills it (exit_code 124).
ProcessResult run_oitbench(const std::vector<std::string>& args, double timeout_s = 300);
// Starts it and sends `signal` once `csv` holds at least `rows` data rows (to test Ctrl-C mid-run).
ProcessResult run_oitbench_interrupted(const std::vector<std::string>& args, const std::filesystem::path& csv,
                                       size_t rows, int signal);

using Row = std::map<std::string, std::string>;
std::vector<Row> read_csv_rows(const std::filesystem::path& path);

// A fresh directory under the test temp dir, removed at exit.
std::filesystem::path temp_dir(const std::string& name);

// One headless GL context (egl, or the backend in OITBENCH_TEST_BACKEND) for a test suite.
class GlTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite();
  static void TearDownTestSuite();
  static const GlInfo& gl() { return *info_; }
  static Context& context() { return *context_; }
  static const ShaderLibrary& shaders() { return *shaders_; }

  // Prepares and runs one case of a registered experiment in this process: warm-up once, run,
  // validate. Throws what prepare() throws. `image_stem`: where the case writes its images.
  static Validation run_case(const std::string& experiment, const std::map<std::string, std::string>& params,
                             Resolution res = {64, 64}, const std::string& image_stem = "");

 private:
  static std::unique_ptr<Context> context_;
  static std::unique_ptr<GlInfo> info_;
  static std::unique_ptr<ShaderLibrary> shaders_;
  static std::unique_ptr<Registry> registry_;
};

}  // namespace oitbench::test
