#include "support/test_support.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

#include "core/csv.hpp"
#include "core/runner.hpp"
#include "experiments/experiments.hpp"

namespace oitbench::test {

namespace {
std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

size_t data_rows(const std::filesystem::path& csv) {
  std::error_code ec;
  if (!std::filesystem::exists(csv, ec)) return 0;
  auto rows = csv_parse(slurp(csv));
  return rows.empty() ? 0 : rows.size() - 1;
}

// `signal_rows` > 0: send `sig` once `signal_csv` holds that many data rows.
ProcessResult spawn(const std::vector<std::string>& args, double timeout_s, const std::filesystem::path& signal_csv,
                    size_t signal_rows, int sig) {
  auto dir = temp_dir("proc");
  auto out_path = dir / "stdout", err_path = dir / "stderr";
  std::vector<std::string> full = {OITBENCH_EXE};
  full.insert(full.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : full) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = fork();
  if (pid == 0) {
    int o = ::open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    int e = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(o, STDOUT_FILENO);
    dup2(e, STDERR_FILENO);
    execv(argv[0], argv.data());
    _exit(127);
  }
  ProcessResult r;
  auto t0 = std::chrono::steady_clock::now();
  bool signalled = false;
  int status = 0;
  for (;;) {
    if (waitpid(pid, &status, WNOHANG) == pid) break;
    double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!signalled && signal_rows > 0 && data_rows(signal_csv) >= signal_rows) {
      kill(pid, sig);
      signalled = true;
    }
    if (s > timeout_s) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      r.exit_code = 124;
      r.out = slurp(out_path);
      r.err = slurp(err_path);
      return r;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = slurp(out_path);
  r.err = slurp(err_path);
  return r;
}
}  // namespace

ProcessResult run_oitbench(const std::vector<std::string>& args, double timeout_s) {
  return spawn(args, timeout_s, {}, 0, 0);
}

ProcessResult run_oitbench_interrupted(const std::vector<std::string>& args, const std::filesystem::path& csv,
                                       size_t rows, int signal) {
  return spawn(args, 600, csv, rows, signal);
}

std::vector<Row> read_csv_rows(const std::filesystem::path& path) {
  auto rows = csv_parse(slurp(path));
  std::vector<Row> out;
  if (rows.empty()) return out;
  for (size_t i = 1; i < rows.size(); ++i) {
    Row r;
    for (size_t j = 0; j < rows[0].size(); ++j) r[rows[0][j]] = j < rows[i].size() ? rows[i][j] : "";
    out.push_back(std::move(r));
  }
  return out;
}

std::filesystem::path temp_dir(const std::string& name) {
  auto base = std::filesystem::temp_directory_path() / ("oitbench-test-" + std::to_string(getpid()));
  static int counter = 0;
  auto dir = base / (name + "-" + std::to_string(counter++));
  // A folder left by an earlier test process with the same pid would hand this test its old files (a CSV
  // of an older header to append to): start empty.
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::unique_ptr<Context> GlTest::context_;
std::unique_ptr<GlInfo> GlTest::info_;
std::unique_ptr<ShaderLibrary> GlTest::shaders_;
std::unique_ptr<Registry> GlTest::registry_;

void GlTest::SetUpTestSuite() {
  ContextOptions o;
  if (const char* b = std::getenv("OITBENCH_TEST_BACKEND")) o.backend = b;
  context_ = create_context(o);
  info_ = std::make_unique<GlInfo>(GlInfo::query());
  shaders_ = std::make_unique<ShaderLibrary>(default_shader_root());
  registry_ = std::make_unique<Registry>();
  register_all_experiments(*registry_);
}

void GlTest::TearDownTestSuite() {
  registry_.reset();
  shaders_.reset();
  info_.reset();
  context_.reset();
}

Validation GlTest::run_case(const std::string& experiment, const std::map<std::string, std::string>& params,
                            Resolution res, const std::string& image_stem) {
  Experiment* e = registry_->find(experiment);
  if (!e) throw std::runtime_error("no experiment " + experiment);
  // Defaults for everything not given (the first default value of each parameter).
  ParamSet p;
  for (const auto& spec : registry_->params_of(*e)) {
    auto it = params.find(spec.name);
    std::string v = it != params.end() ? it->second : spec.defaults.at(0);
    spec.check(v, experiment);
    p.set(spec.name, v);
  }
  for (const auto& [k, v] : params)
    if (!p.has(k)) throw std::runtime_error("experiment " + experiment + " has no parameter " + k);
  if (auto why = e->unsupported_reason(*info_, p); !why.empty()) throw Unsupported(why);
  CaseContext ctx(*shaders_, *info_, res, p.get("fault"), static_cast<unsigned>(p.get_int("seed")), image_stem);
  auto instance = e->prepare(p, ctx);
  PassTimer timer(false);
  for (int i = 0; i < 2; ++i) {
    timer.begin_repetition();
    instance->run(timer);
    timer.end_repetition();
  }
  return instance->validate();
}

}  // namespace oitbench::test
