#pragma once
// What an experiment is to the framework. An experiment is one C++ file in micro/experiments/
// (plus its shaders) that defines `void register_<file>(Registry&)`; CMake generates the list.
// The framework expands its parameter grid, prepares each case (compile, allocate: timed as
// compile_ms), runs warm-up and timed repetitions interleaved across cases, then validates each
// case once against its CPU reference and writes a row per pass.
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "backends/backend.hpp"
#include "core/memory_budget.hpp"
#include "core/params.hpp"
#include "core/phases.hpp"
#include "core/schema.hpp"
#include "core/shared_cache.hpp"
#include "core/timer.hpp"
#include "gl/shader.hpp"

namespace oitbench {

// Thrown from prepare() when the driver lacks something this case needs: status `unsupported`.
class Unsupported : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Resolution {
  int width = 800, height = 600;
};

struct Validation {
  bool valid = false;
  std::string reason;                          // why not valid (or a note on a valid one)
  std::map<std::string, std::string> metrics;  // values for the experiment's metric columns
};

// Everything a case may use: the shader library, the context's facts, the target size, and the
// case's framework-level settings (fault injection for testing validators, the random seed).
class CaseContext {
 public:
  CaseContext(const ShaderLibrary& shaders, const GlInfo& gl, Resolution res, std::string fault, unsigned seed,
              std::string image_stem = "", bool gpu_clock = false, SharedCache* shared = nullptr,
              PhaseClock* phases = nullptr)
      : shaders_(shaders),
        gl_(gl),
        res_(res),
        fault_(std::move(fault)),
        seed_(seed),
        image_stem_(std::move(image_stem)),
        gpu_clock_(gpu_clock),
        shared_(shared),
        phases_(phases) {}
  const ShaderLibrary& shaders() const { return shaders_; }
  const GlInfo& gl() const { return gl_; }
  int width() const { return res_.width; }
  int height() const { return res_.height; }
  unsigned seed() const { return seed_; }
  const std::string& fault() const { return fault_; }
  // Where a case that can show its result writes images at validation (STEM.png, STEM-diff8.png,
  // ...): an output option of `oitbench render`, not a parameter. Empty: no images.
  const std::string& image_stem() const { return image_stem_; }
  // The run's primary clock is GL_TIME_ELAPSED (hardware drivers): a case that times something
  // itself (BMA-AUTO's calibration) uses the same clock.
  bool gpu_clock() const { return gpu_clock_; }
  // What the run's cases share (a scene's meshes); null where nothing is shared (each case builds its own).
  SharedCache* shared() const { return shared_; }
  // A stretch of the case's own work in a finer phase of the time account (core/phases.hpp): pool
  // sizing, read-back, the reference. A no-op where the run keeps no account (the viewer, tests).
  PhaseClock::Scope phase(Phase p) const { return PhaseClock::Scope(phases_, p); }
  PhaseClock* phase_clock() const { return phases_; }  // for a case that keeps it (null: no account)
  // What the case may allocate (core/memory_budget.hpp): checked from its counts before it allocates.
  // Unknown limits (the default) check nothing.
  const MemoryLimits& memory() const { return memory_; }
  void set_memory(MemoryLimits limits) { memory_ = std::move(limits); }
  // Compiles with the experiment's defines plus the fault define (OITBENCH_FAULT_WRONG_RESULT, ...);
  // its time is the account's compile phase.
  gl::Program build(const std::vector<ShaderStage>& stages, Defines defines) const;

 private:
  const ShaderLibrary& shaders_;
  const GlInfo& gl_;
  Resolution res_;
  std::string fault_;
  unsigned seed_;
  std::string image_stem_;
  bool gpu_clock_;
  SharedCache* shared_;
  PhaseClock* phases_;
  MemoryLimits memory_{};
};

class CaseInstance {
 public:
  virtual ~CaseInstance() = default;
  // One repetition. GPU work goes inside `timer.pass(name)` scopes; a case with several passes
  // gets a row per pass plus `total`.
  virtual void run(PassTimer& timer) = 0;
  // Reads back the last repetition's result and compares it with the CPU reference.
  virtual Validation validate() = 0;
  // Values for metric columns that are known without validation (e.g. a model's prediction).
  virtual std::map<std::string, std::string> metrics() const { return {}; }
  // Parameters whose value was a request the case resolved (effects=scene -> opaque+transparency):
  // the rows carry what ran, so a row's parameters rerun the same case.
  virtual std::map<std::string, std::string> resolved_params() const { return {}; }
  // Scalable work: a case whose repetition is nominal_units() units of the same work (occupancy's draws)
  // can run fewer of them when a repetition is longer than --max-sample-ms; the framework scales the times
  // back to the nominal repetition (sample_units in the rows). 0: not scalable.
  virtual int nominal_units() const { return 0; }
  virtual void set_units(int units) { (void)units; }
};

class Experiment {
 public:
  virtual ~Experiment() = default;
  virtual std::string name() const = 0;
  virtual std::string description() const = 0;
  virtual std::vector<ParamSpec> params() const = 0;
  // The metric columns its rows fill (values come from Validation::metrics or CaseInstance::metrics()).
  // A metric may share a name with another experiment's only with the same type and unit, and
  // never with a parameter or a framework column: Registry::add refuses both.
  virtual std::vector<MetricSpec> metric_specs() const { return {}; }
  virtual Resolution default_resolution() const { return {800, 600}; }
  virtual Resolution quick_resolution() const { return {256, 256}; }
  // Variants that can hang a real GPU (spinlocks): each case runs in a child process under a watchdog.
  virtual bool hang_prone() const { return false; }
  // Cases held in memory at once for interleaving at this render target size; experiments with large
  // buffers lower it.
  virtual int max_interleave(Resolution res) const {
    (void)res;
    return 8;
  }
  // Empty when the case can run on this driver; else the reason it is unsupported.
  virtual std::string unsupported_reason(const GlInfo&, const ParamSet&) const { return ""; }
  virtual std::unique_ptr<CaseInstance> prepare(const ParamSet& params, CaseContext& ctx) = 0;
  // Before anything runs: throws UsageError for a case the parameter grid allows but the
  // experiment's data rules out (an effect its scene does not declare).
  // It is given one case per distinct combination of the values of checked_params() (holding only
  // those), so a grid of millions of cases is checked without being built; not called where that is empty.
  virtual void check_cases(const std::vector<ParamSet>& cases) const { (void)cases; }
  virtual std::vector<std::string> checked_params() const { return {}; }
};

// Most experiments: a name, a description, the render targets (default and --quick), and cases of one
// class built from (parameters, context). Such an experiment derives from ExperimentOf<ItsCase>, passes
// those to the constructor, and overrides only what it adds (params(), metric_specs(), unsupported_reason()).
template <class Case>
class ExperimentOf : public Experiment {
 public:
  ExperimentOf(std::string name, std::string description, Resolution resolution, Resolution quick_resolution)
      : name_(std::move(name)),
        description_(std::move(description)),
        resolution_(resolution),
        quick_resolution_(quick_resolution) {}
  std::string name() const override { return name_; }
  std::string description() const override { return description_; }
  Resolution default_resolution() const override { return resolution_; }
  Resolution quick_resolution() const override { return quick_resolution_; }
  std::unique_ptr<CaseInstance> prepare(const ParamSet& p, CaseContext& ctx) override {
    return std::make_unique<Case>(p, ctx);
  }

 private:
  std::string name_, description_;
  Resolution resolution_, quick_resolution_;
};

class Registry {
 public:
  // Throws std::logic_error for a second experiment of the same name, or a metric that collides
  // with a parameter, a framework column or another experiment's metric of another type or unit.
  void add(std::unique_ptr<Experiment> e);
  const Experiment* find(const std::string& name) const;
  Experiment* find(const std::string& name);
  const std::vector<std::unique_ptr<Experiment>>& all() const { return experiments_; }
  std::string names() const;  // "occupancy, sort, ..."
  // The framework's own parameters, appended to every experiment's list.
  static std::vector<ParamSpec> framework_params();
  std::vector<ParamSpec> params_of(const Experiment& e) const;

 private:
  std::vector<std::unique_ptr<Experiment>> experiments_;
};

}  // namespace oitbench
