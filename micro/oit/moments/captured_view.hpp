#pragma once
// What MBOIT's and STOCHASTIC's cases (moments.hpp) share, written once (captured_view.cpp).
#include <functional>
#include <initializer_list>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gl/render_target.hpp"
#include "oit/moments/moment_model.hpp"
#include "oit/moments/moments.hpp"
#include "oit/reference/reference.hpp"
#include "oit/reference/visible_capture.hpp"

namespace oitbench::oit {

// What both cases start from: the scene's mesh for the view, its camera, and the view's fragments
// captured once per run and view (visible_capture.hpp: reference_view, shared with every other
// CPU-model-checked case of the run that sees the same fragments) for the exact reference and the CPU models.
struct CapturedView {
  // The scene's effects (scene_passes.hpp): the opaque pass, the shading, the backdrop; these
  // techniques test the opaque depth in their shaders (opaque_hides, depth_sampler_defines()).
  std::unique_ptr<ScenePasses> fx;
  const SceneDesc* scene = nullptr;
  const GpuMesh* mesh = nullptr;  // fx's transparent primitives
  glm::mat4 view_proj{1.0f};
  glm::vec2 near_far{0.1f, 10.f};
  glm::vec2 depth_range{0.1f, 10.f};  // nearest and farthest vertex along the view direction
  // The opaque colour and depth read back for the references, the visible fragments (with the opaque
  // effect, hidden by the CPU: `hidden` of them), their statistics and exact composite.
  std::shared_ptr<const ReferenceView> ref;
};
CapturedView capture_view(const ParamSet& p, CaseContext& ctx);
// MBOIT's and WOIT's warp needs depth_range, the extent of the mesh's vertices; a view of splats has none
// (a splat's extent along the ray is not a vertex), so `technique` is Unsupported there, never a
// degenerate warp whose image agrees with its model and not with the scene.
void require_depth_bounds(const CapturedView& view, const std::string& technique);

// Every fragment of the view as shaders/stochastic/coverage.frag records it (pixel, primitive, sample
// coverage, colour, depth), drawn with `program` into `framebuffer` (MSAA for STOCHASTIC, single-sample
// for SLAB), outside the timed passes: the CPU models draw the same hashed masks from it. Per pixel,
// the record keeps the order the fragments reached the pixel; those behind the opaque depth are left
// out (the shaders hide them). False when the record lost fragments (its buffer overflowed twice).
bool record_coverage(const CapturedView& view, GLuint framebuffer, int width, int height, const gl::Program& program,
                     std::vector<CoverageFragment>& out);

// The part MBOIT's and STOCHASTIC's cases share (captured_view.cpp): the view captured once, the
// result target and its read-backs, the frames the flicker metric compares, and the validation
// against the reference and the technique's CPU model up to the technique's own checks.
class CapturedViewCase : public OitCase {
 public:
  CapturedViewCase(const ParamSet& p, CaseContext& ctx);
  GLuint result_texture() override { return out_.color_texture(); }
  GLuint opaque_texture() const override { return view_.fx->opaque_texture(); }
  std::map<std::string, std::string> resolved_params() const override { return view_.fx->resolved_params(); }
  // The effects' passes and every program of projected_ follow the camera.
  void set_view_projection(const glm::mat4& view_proj) override;

 protected:
  // run()'s start: the effects' passes; false when nothing is transparent (the image is then the
  // backdrop). Else the programs that draw the transparent geometry this frame (`drawing`) get the
  // geometry's bindings, and the opaque depth is bound for their test.
  bool begin_run(PassTimer& timer, std::initializer_list<const gl::Program*> drawing);
  // run()'s end, outside the timed passes: keeps the last flicker_runs frames.
  void keep_frame();
  // run()'s last timed pass, "resolve": `resolve` draws the full-screen triangle into out_ over the
  // backdrop, reading what `bind_inputs` binds (the technique's sums); then keep_frame().
  void resolve_pass(PassTimer& timer, const gl::Program& resolve, const std::function<void()>& bind_inputs);

  // What validate() has after the checks every model-checked case makes: the list and error metrics,
  // the model's error, bytes_per_pixel, the model check's nonfinite and model_max_diff, the flicker,
  // and the problems of the shadow pass and of a broken list.
  struct ModelValidation {
    Validation v;
    std::vector<float> rgb;
    ListStats stats;
    ModelCheck check;
    std::vector<std::string> problems;
  };
  // `model` computes the technique's CPU model of the image (inside a Reference stretch of phases_).
  ModelValidation validate_against(const std::function<std::vector<double>()>& model, double tolerance);
  // validate()'s end: the output's non-finite and out-of-range channels, then more than `allowed`
  // channels off the technique's CPU model by more than `tolerance` (written in 255ths, as the models'
  // tolerances are), as problems after the technique's own; the verdict. `same` says what the model
  // shares with the GPU (" (same masks)"), after "TECHNIQUE's CPU model" in the message.
  Validation conclude_against(ModelValidation& mv, double tolerance, size_t allowed = 0,
                              const std::string& same = "") const;

  int width_, height_;
  std::string technique_;  // the case's technique (the `technique` parameter), for messages
  CapturedView view_;
  RenderTarget out_;
  FullscreenTriangle quad_;
  int bytes_ = 0;                              // per pixel
  PhaseClock* phases_ = nullptr;               // the run's time account (core/phases.hpp); null: none
  std::vector<const gl::Program*> projected_;  // the technique's programs that draw the scene's geometry

 private:
  int flicker_runs_;
  std::string dump_;
  std::vector<std::vector<float>> frames_;
};

}  // namespace oitbench::oit
