#pragma once
// What the viewer renders with: one case of the registered `oit` experiment, its parameters taken
// from the experiment's defaults, then the command line, then the keys (T technique, B BMA, M
// MAX_FRAGS, C capture storage). Every value is checked against the experiment's ParamSpecs, so
// the viewer can only show what `oitbench run oit` could measure.
#include <map>
#include <string>
#include <vector>

#include "core/registry.hpp"

namespace oitbench::viewer {

class OitSettings {
 public:
  // `chosen`: parameter -> value (scene, view, technique, detail, --set ...). Throws UsageError
  // naming the parameter and its valid values.
  OitSettings(Registry& registry, const std::map<std::string, std::string>& chosen);

  Experiment& experiment() const { return *experiment_; }
  const ParamSet& params() const { return params_; }
  const std::string& get(const std::string& name) const { return params_.get(name); }
  bool has_param(const std::string& name) const;
  void set(const std::string& name, const std::string& value);  // checked

  const std::string& technique() const { return params_.get("technique"); }
  bool is_exact() const;        // one of the exact techniques (a capture, PPLL or PPPA, the viewer can walk)
  bool uses_max_frags() const;  // MAX_FRAGS means something to the resolve (not CPU-NATIVE)
  bool uses_nodes() const;      // an approximate technique with per-pixel node arrays

  // Each returns a note for the screen: what changed, or why nothing did. `changed` says whether
  // the case must be rebuilt.
  std::string step_technique(int step, bool& changed);
  std::string toggle_bma(bool& changed);  // BASE-X <-> BMA-X
  // x2 (up) or /2 of MAX_FRAGS (0 = auto, as the parameter; `in_use` is what auto chose) or, for
  // the approximate array techniques, of their node count.
  std::string scale_max_frags(bool up, unsigned in_use, bool& changed);
  std::string step_capture(bool& changed);

 private:
  const ParamSpec& spec(const std::string& name) const;
  Experiment* experiment_ = nullptr;
  std::vector<ParamSpec> specs_;
  ParamSet params_;
};

}  // namespace oitbench::viewer
