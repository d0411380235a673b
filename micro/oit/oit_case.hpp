#pragma once
// The oit experiment's cases (exact: exact_case.cpp; approximate: approx_case.cpp) as objects that the
// experiment times and validates and that the interactive viewer (`oitbench view`) drives with its
// own camera: the same code renders the benchmark and the picture a person looks at.
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

#include "core/registry.hpp"
#include "gl/gl.hpp"

namespace oitbench::oit {

class FragmentStorage;

class OitCase : public CaseInstance {
 public:
  // The camera for the following run()s. The primitives keep the submission order of the view the
  // case was made for (its fwd/rev ordering is part of what is measured).
  virtual void set_view_projection(const glm::mat4& view_proj) = 0;
  // The last run()'s image, RGBA32F: the colour where alpha > 0, the scene's background elsewhere.
  virtual GLuint result_texture() = 0;
  // The opaque effect's colour (what lies behind where result_texture() has alpha 0), or 0.
  virtual GLuint opaque_texture() const { return 0; }
  // The fragments the last run() captured, or nullptr where the technique keeps none on the GPU.
  virtual const FragmentStorage* fragments() const { return nullptr; }
  // MAX_FRAGS in use (0 where the technique has none).
  virtual unsigned max_frags() const { return 0; }
};

// An exact technique's case (parameters as the oit experiment declares them, micro/experiments/oit.cpp).
std::unique_ptr<OitCase> make_exact_case(const ParamSet& p, CaseContext& ctx);
// The case for any technique: make_oit_case in techniques.hpp, the technique table.

}  // namespace oitbench::oit
