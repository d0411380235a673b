#pragma once
// Small helpers every technique family's case (and the scene and model code that explains a
// validation failure) shares, written once.
#include <glm/glm.hpp>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/params.hpp"
#include "core/registry.hpp"
#include "gl/gl.hpp"
#include "gl/gl_objects.hpp"
#include "gl/shader.hpp"
#include "oit/scene/shadow_map.hpp"

namespace oitbench::oit {

// Tries a fragment's per-pixel spinlock insertion makes before it gives up (the SPIN_CAP define of
// the approximate techniques' and SLAB's insertions; the gave-ups are counted as capped_updates).
inline constexpr int kSpinCap = 1 << 16;

// A number in a reason or a log line: six significant digits.
inline std::string fmt(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

// The RGB of an RGBA image (the channels the error metrics compare).
inline std::vector<float> rgb_of(const std::vector<float>& rgba) {
  std::vector<float> rgb(rgba.size() / 4 * 3);
  for (size_t p = 0; p < rgba.size() / 4; ++p)
    for (int k = 0; k < 3; ++k) rgb[p * 3 + k] = rgba[p * 4 + k];
  return rgb;
}

// Sets a program's `viewProj` uniform.
inline void set_view_proj(const gl::Program& prog, const glm::mat4& vp) {
  glProgramUniformMatrix4fv(prog.get(), glGetUniformLocation(prog.get(), "viewProj"), 1, GL_FALSE, &vp[0][0]);
}

// The self-shadowing pass's own checks (scene_passes.hpp) in a case's metrics and problems.
inline void merge_shadow_check(std::map<std::string, std::string>& metrics, std::vector<std::string>& problems,
                               const ShadowCheck& shadow) {
  metrics.insert(shadow.metrics.begin(), shadow.metrics.end());
  problems.insert(problems.end(), shadow.problems.begin(), shadow.problems.end());
}

// 3DGS's early termination (Kerbl et al. 2023), an option of the ordered techniques (the technique table
// says which read it): front to back, the fragment that would take the transmittance below the threshold
// is not blended, nor any after it. 0: off, every fragment blended.
inline ParamSpec early_stop_param() {
  ParamSpec s = ParamSpec::text(
      "early_stop",
      "3DGS's early termination (Kerbl et al. 2023): the ordered techniques composite front to back and stop at the "
      "fragment that would take the transmittance below this threshold (not blended, nor any after it; 1e-4 is "
      "3DGS's); 0: off, every fragment blended. Validated against references that stop at the same threshold",
      {"0"});
  s.kind = ParamSpec::Kind::Number;
  s.min = 0;
  s.max = 0.5;
  return s;
}
// The case's early_stop threshold (0: off, or a technique that does not read it).
inline double early_stop_of(const ParamSet& p) { return p.has("early_stop") ? std::stod(p.get("early_stop")) : 0.0; }

// A double as a GLSL float literal (a define's value): 9 significant digits, always with an exponent.
inline std::string glsl_float(double v) {
  std::ostringstream s;
  s.precision(8);
  s << std::scientific << v;
  return s.str();
}

// The EARLY_STOP define of a resolve that stops at `threshold` (nothing when 0); fault=no-early-stop keeps the
// front-to-back composite but stops nowhere (its threshold 0), so the checks against stopping references must fail.
inline Defines early_stop_defines(double threshold, const std::string& fault) {
  if (threshold <= 0) return {};
  return {{"EARLY_STOP", fault == "no-early-stop" ? "0.0" : glsl_float(threshold)}};
}

// The end of every case's validate(): valid when nothing is wrong, the problems joined as the reason.
inline void conclude(Validation& v, const std::vector<std::string>& problems) {
  v.valid = problems.empty();
  for (const auto& s : problems) v.reason += (v.reason.empty() ? "" : "; ") + s;
}

}  // namespace oitbench::oit
