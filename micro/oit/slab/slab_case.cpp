// The oit experiment's SLAB case (slab.hpp): one insertion pass and a resolve (shaders/slab/),
// validated against slab_model, which replays the same masks and insertions from the fragments'
// record (captured_view.hpp's record_coverage, on a single-sample target).
#include <string>

#include "oit/case_support.hpp"
#include "oit/moments/captured_view.hpp"
#include "oit/slab/slab.hpp"
#include "shaders/slab/bindings.h"

namespace oitbench::oit {

namespace {

// The GPU sums the resolve in float where the model sums in double, and a merge's average can round
// to the other 8-bit neighbour in float than in the model's float (fused or not): one merged colour
// off by 1/255 moves a pixel by less than that.
constexpr double kSlabTolerance = 2.0 / 255.0;

}  // namespace

std::vector<ParamSpec> slab_params() {
  return {ParamSpec::choice("slab_layers",
                            "layers a pixel keeps (depth, coverage mask, colour); as many as samples_per_pixel "
                            "never merge (stochastic transparency's estimate), fewer merge the two farthest",
                            {"1", "2", "4", "8"}, {"4"})};
}

namespace {

class SlabCase final : public CapturedViewCase {
 public:
  SlabCase(const ParamSet& p, CaseContext& ctx) : CapturedViewCase(p, ctx), run_seed_(ctx.seed()) {
    const int layers = static_cast<int>(p.get_int("slab_layers")),
              samples = static_cast<int>(p.get_int("samples_per_pixel"));
    setup_ = {width_, height_, layers, samples, 0, 0};  // the model on every core
    const size_t pixels = static_cast<size_t>(width_) * height_;
    layers_ = gl::make_buffer();
    glNamedBufferStorage(layers_.get(),
                         static_cast<GLsizeiptr>(pixels * setup_.layers * SLAB_LAYER_WORDS * sizeof(GLuint)), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    stats_ = gl::make_buffer();
    glNamedBufferStorage(stats_.get(), sizeof(GLuint), nullptr, GL_DYNAMIC_STORAGE_BIT);
    locks_ = gl::make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(locks_.get(), 1, GL_R32UI, width_, height_);
    // What the buffers hold: per layer a float depth, a 32-bit mask word and RGBA8; and the lock.
    bytes_ = setup_.layers * SLAB_LAYER_WORDS * 4 + 4;

    Defines d = view_.fx->geometry_defines();
    for (auto& x : view_.fx->depth_sampler_defines()) d.push_back(x);
    d.push_back({"SLAB_LAYERS", std::to_string(setup_.layers)});
    d.push_back({"SLAB_SAMPLES", std::to_string(setup_.samples)});
    d.push_back({"SPIN_CAP", std::to_string(kSpinCap)});
    const std::string vert = "scene/scene.vert";
    record_ = ctx.build({{GL_VERTEX_SHADER, vert}, {GL_FRAGMENT_SHADER, "stochastic/coverage.frag"}}, d);
    insert_ = ctx.build({{GL_VERTEX_SHADER, vert}, {GL_FRAGMENT_SHADER, "slab/insert.frag"}}, d);
    resolve_ = ctx.build({{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "slab/resolve.frag"}}, d);
    projected_ = {&record_, &insert_};
    for (const gl::Program* prog : {&insert_, &resolve_})
      glProgramUniform1i(prog->get(), glGetUniformLocation(prog->get(), "width"), width_);
    set_view_projection(view_.view_proj);
    // Every fragment once, in the order it reaches its pixel (the model inserts in that order).
    fragments_lost_ = !record_coverage(view_, out_.framebuffer(), width_, height_, record_, fragments_);
  }

  void run(PassTimer& timer) override {
    if (!begin_run(timer, {&insert_})) return;
    setup_.frame_seed = stochastic_frame_seed(run_seed_, frame_++);
    glProgramUniform1ui(insert_.get(), glGetUniformLocation(insert_.get(), "frameSeed"), setup_.frame_seed);
    glDisable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    {
      auto t = timer.pass("slab");
      glClearNamedBufferData(layers_.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
      glClearNamedBufferData(stats_.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
      glClearTexImage(locks_.get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
      out_.bind();
      glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SLAB_LAYERS_BINDING, layers_.get());
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SLAB_STATS_BINDING, stats_.get());
      glBindImageTexture(SLAB_LOCK_IMAGE_UNIT, locks_.get(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
      glUseProgram(insert_.get());
      view_.mesh->draw();
      glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    resolve_pass(timer, resolve_,
                 [&] { glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SLAB_LAYERS_BINDING, layers_.get()); });
  }

  Validation validate() override {
    ModelValidation mv =
        validate_against([&] { return slab_model(fragments_, view_.ref->backdrop, setup_); }, kSlabTolerance);
    GLuint capped = 0;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(stats_.get(), 0, sizeof(GLuint), &capped);
    mv.v.metrics["capped_updates"] = std::to_string(capped);
    if (fragments_lost_) mv.problems.push_back("the fragment record lost fragments");
    if (capped) mv.problems.push_back(std::to_string(capped) + " insertion(s) gave up on the spinlock (lost)");
    return conclude_against(mv, kSlabTolerance, 0, " (same masks, same insertions)");
  }

 private:
  uint32_t run_seed_;
  SlabSetup setup_;
  gl::Buffer layers_, stats_;
  gl::Texture locks_;
  gl::Program record_, insert_, resolve_;
  std::vector<CoverageFragment> fragments_;
  bool fragments_lost_ = false;
  uint32_t frame_ = 0;
};

}  // namespace

std::unique_ptr<OitCase> make_slab_case(const ParamSet& p, CaseContext& ctx) {
  return std::make_unique<SlabCase>(p, ctx);
}

}  // namespace oitbench::oit
