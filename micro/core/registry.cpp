#include "core/registry.hpp"

#include <algorithm>

namespace oitbench {

gl::Program CaseContext::build(const std::vector<ShaderStage>& stages, Defines defines) const {
  if (fault_ == "wrong-result") defines.emplace_back("OITBENCH_FAULT_WRONG_RESULT", "1");
  if (fault_ == "compile-error") defines.emplace_back("OITBENCH_FAULT_COMPILE_ERROR", "1");
  if (fault_ == "hang") defines.emplace_back("OITBENCH_FAULT_HANG", "1");
  if (fault_ == "lose-fragment") defines.emplace_back("OITBENCH_FAULT_LOSE_FRAGMENT", "1");
  const auto compiling = phase(Phase::Compile);
  return shaders_.build(stages, defines);
}

void Registry::add(std::unique_ptr<Experiment> e) {
  if (find(e->name())) throw std::logic_error("experiment '" + e->name() + "' registered twice");
  auto param_owner = [&](const std::string& name) -> std::string {
    for (const auto& p : params_of(*e))
      if (p.name == name) return e->name();
    for (const auto& x : experiments_)
      for (const auto& p : params_of(*x))
        if (p.name == name) return x->name();
    return "";
  };
  for (const auto& m : e->metric_specs()) {
    for (const auto& c : summary_base_columns())
      if (c.name == m.name)
        throw std::logic_error("experiment '" + e->name() + "': metric '" + m.name + "' is a framework column");
    if (auto owner = param_owner(m.name); !owner.empty())
      throw std::logic_error("experiment '" + e->name() + "': metric '" + m.name +
                             "' has the name of a parameter of '" + owner +
                             "'; a column is either a parameter or a metric");
    for (const auto& x : experiments_)
      for (const auto& other : x->metric_specs())
        if (other.name == m.name && (other.type != m.type || other.unit != m.unit))
          throw std::logic_error("experiment '" + e->name() + "': metric '" + m.name + "' (" + value_type_name(m.type) +
                                 ", '" + m.unit + "') differs from '" + x->name() + "''s (" +
                                 value_type_name(other.type) + ", '" + other.unit + "')");
  }
  for (const auto& p : params_of(*e))
    for (const auto& x : experiments_)
      for (const auto& m : x->metric_specs())
        if (m.name == p.name)
          throw std::logic_error("experiment '" + e->name() + "': parameter '" + p.name +
                                 "' has the name of a metric of '" + x->name() + "'");
  experiments_.push_back(std::move(e));
  std::sort(experiments_.begin(), experiments_.end(),
            [](const auto& a, const auto& b) { return a->name() < b->name(); });
}

const Experiment* Registry::find(const std::string& name) const {
  for (const auto& e : experiments_)
    if (e->name() == name) return e.get();
  return nullptr;
}
Experiment* Registry::find(const std::string& name) {
  return const_cast<Experiment*>(static_cast<const Registry*>(this)->find(name));
}

std::string Registry::names() const {
  std::string s;
  for (const auto& e : experiments_) s += (s.empty() ? "" : ", ") + e->name();
  return s;
}

std::vector<ParamSpec> Registry::framework_params() {
  ParamSpec fault;
  fault.name = "fault";
  fault.description =
      "fault injection for testing the framework: wrong-result (the shader perturbs its output, so the "
      "validator must fail), compile-error, hang (an endless shader loop for the watchdog), lose-fragment (oit's "
      "capture drops the fragments of the diagonal, so its capture checks must fail), no-opaque-depth (oit's "
      "geometry passes skip the opaque effect's depth test, so its occlusion checks must fail), shadow-slice-off "
      "(the self-shadowing opacity map draws every slice one layer too far, so its map check must fail), path-pop "
      "(oit's popping path adds 4/255 to an 8x8 block of every other frame, so the exact techniques' popping check "
      "must fail), no-early-stop (oit's ordered techniques blend every fragment although early_stop asks them to "
      "stop, so their checks against references that stop must fail)";
  fault.defaults = {"none"};
  fault.allowed = {"none",          "wrong-result",    "compile-error",    "hang",
                   "lose-fragment", "no-opaque-depth", "shadow-slice-off", "path-pop",
                   "no-early-stop"};
  ParamSpec seed;
  seed.name = "seed";
  seed.description = "seed of the case's random inputs";
  seed.defaults = {"1"};
  seed.kind = ParamSpec::Kind::Integer;
  seed.min = 0;
  seed.max = 4294967295.0;
  return {fault, seed};
}

std::vector<ParamSpec> Registry::params_of(const Experiment& e) const {
  auto p = e.params();
  for (auto& f : framework_params()) p.push_back(std::move(f));
  return p;
}

}  // namespace oitbench
