// lines: transparency of line primitives (Sintorn et al., poster: hair as line segments sorted per
// primitive into 256 depth slices by a stream-split radix sort in CUDA). The line strands of a scene
// (scenes/hair.json: the `strands` generator), `segments` of them, are rendered from one of its views
//   technique=exact:  per fragment: linked-list capture + the exact BASE-IMS resolve (oit experiment)
//   technique=slices: per primitive: each segment's depth slice, a stable radix sort (count, prefix
//                     sum, scatter per bit, in compute shaders), then one back-to-front blended draw
// The slice sort is validated exactly (a stable CPU sort of the same keys); its image's error against
// the per-fragment exact reference is data (`rmse` etc.), since slices are an approximation.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/registry.hpp"
#include "gl/render_target.hpp"
#include "oit/capture/fragment_lists.hpp"
#include "oit/reference/image_compare.hpp"
#include "oit/reference/metrics.hpp"
#include "oit/reference/reference.hpp"
#include "oit/resolve/resolve_sort.hpp"
#include "oit/scene/gpu_mesh.hpp"
#include "oit/scene/radix_sort.hpp"
#include "oit/scene/scene.hpp"
#include "shaders/lines/bindings.h"

namespace oitbench {

namespace {

using namespace oit;

// The scene with its strands' segment count set to `segments` (0: the file's own), split evenly over
// its strands objects; the scene's line primitives for `view`, its triangles left out.
Mesh hair_mesh(SceneDesc scene, const View& view, long long segments) {
  std::vector<SceneObject*> strands;
  for (auto& o : scene.objects)
    if (o.generator == "strands") strands.push_back(&o);
  if (strands.empty())
    throw std::runtime_error("lines: scene \"" + scene.name + "\" (" + scene.path +
                             ") has no line strands; give it an object with \"generator\": \"strands\" "
                             "(scenes/hair.json)");
  if (segments > 0)
    for (size_t k = 0; k < strands.size(); ++k)
      strands[k]->params["segments"] = segments / static_cast<long long>(strands.size()) +
                                       (k == 0 ? segments % static_cast<long long>(strands.size()) : 0);
  Mesh mesh = build_mesh(scene, view, Detail::Full);
  if (mesh.segments() == 0) throw std::runtime_error("lines: scene \"" + scene.name + "\" makes no line segments");
  mesh.indices.clear();
  mesh.opaque_indices.clear();
  return mesh;
}

class LinesCase final : public CaseInstance {
 public:
  LinesCase(const ParamSet& p, CaseContext& ctx, const SceneDesc& scene)
      : LinesCase(p, ctx, scene, scene.view(p.get("view")),
                  hair_mesh(scene, scene.view(p.get("view")), p.get_int("segments"))) {}

 private:
  LinesCase(const ParamSet& p, CaseContext& ctx, const SceneDesc& scene, const View& view, const Mesh& mesh)
      : ctx_(ctx),
        slices_mode_(p.get("technique") == "slices"),
        slices_(static_cast<int>(p.get_int("slices"))),
        background_(scene.background),
        view_proj_(view_projection(view, mesh, static_cast<float>(ctx.width()) / ctx.height())),
        target_(ctx.width(), ctx.height()),
        mesh_(std::make_unique<GpuMesh>(mesh)),
        segments_(mesh.segments()),
        lists_(ctx.width(), ctx.height(), segments_ * 8, false) {
    // The depth range cut into slices: the segments' vertices' distances along the view direction.
    const glm::vec3 forward = glm::normalize(view.target - view.eye);
    float near_distance = 1e30f, far_distance = -1e30f;
    for (unsigned v : mesh.line_indices) {
      float w = glm::dot(mesh.vertices[v].position - view.eye, forward);
      near_distance = std::min(near_distance, w);
      far_distance = std::max(far_distance, w);
    }
    far_distance = std::max(far_distance, near_distance + 1e-6f);
    capture_ = ctx.build({{GL_VERTEX_SHADER, "scene/scene.vert"}, {GL_FRAGMENT_SHADER, "capture/capture.frag"}}, {});
    glProgramUniformMatrix4fv(capture_.get(), glGetUniformLocation(capture_.get(), "viewProj"), 1, GL_FALSE,
                              &view_proj_[0][0]);
    // One capture now: the exact reference, and MAX_FRAGS for the exact resolve.
    capture();
    auto host = lists_.read_back();
    stats_ = list_stats(host);
    reference_ = composite_reference(host, background_);
    if (!slices_mode_) {
      max_frags_ = std::max(8u, std::bit_ceil(stats_.peak_depth));
      resolve_ = ctx.build({{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "resolve/resolve.frag"}},
                           sort_defines(ResolveSort::IMS, max_frags_, 32));
      glProgramUniform3f(resolve_.get(), glGetUniformLocation(resolve_.get(), "background"), background_.r,
                         background_.g, background_.b);
      return;
    }
    if (slices_ & (slices_ - 1)) throw std::invalid_argument("slices must be a power of two");
    bits_ = 0;
    while ((1 << bits_) < slices_) ++bits_;
    static_assert(sizeof(Vertex) % sizeof(float) == 0 && offsetof(Vertex, position) == 0,
                  "shaders/lines/slice_keys.comp reads Vertex as floats, the position first");
    const Defines slice_defines = {{"SLICES", std::to_string(slices_)},
                                   {"VERTEX_FLOATS", std::to_string(sizeof(Vertex) / sizeof(float))}};
    keys_prog_ = ctx.build({{GL_COMPUTE_SHADER, "lines/slice_keys.comp"}}, slice_defines);
    glProgramUniformMatrix4fv(keys_prog_.get(), glGetUniformLocation(keys_prog_.get(), "viewProj"), 1, GL_FALSE,
                              &view_proj_[0][0]);
    glProgramUniform1f(keys_prog_.get(), glGetUniformLocation(keys_prog_.get(), "nearDistance"), near_distance);
    glProgramUniform1f(keys_prog_.get(), glGetUniformLocation(keys_prog_.get(), "farDistance"), far_distance);
    emit_ = ctx.build({{GL_COMPUTE_SHADER, "lines/emit_indices.comp"}}, {});
    blend_ = ctx.build({{GL_VERTEX_SHADER, "scene/scene.vert"}, {GL_FRAGMENT_SHADER, "lines/blend.frag"}}, {});
    glProgramUniformMatrix4fv(blend_.get(), glGetUniformLocation(blend_.get(), "viewProj"), 1, GL_FALSE,
                              &view_proj_[0][0]);
    sort_ = std::make_unique<RadixSort>(ctx, segments_, bits_);
    const GLsizeiptr n = static_cast<GLsizeiptr>(segments_ * sizeof(unsigned));
    elements_ = gl::make_buffer();
    glNamedBufferStorage(elements_.get(), 2 * n, nullptr, 0);
  }

 public:
  void run(PassTimer& timer) override {
    if (!slices_mode_) {
      {
        auto t = timer.pass("capture");
        capture();
      }
      auto t = timer.pass("resolve");
      target_.bind_cleared(0, 0, 0, 0);
      glEnable(GL_BLEND);
      glBlendFunc(GL_ONE, GL_ONE);
      lists_.bind();
      glUseProgram(resolve_.get());
      quad_.draw();
      glDisable(GL_BLEND);
      return;
    }
    {
      auto t = timer.pass("keys");
      per_segment(keys_prog_,
                  {{SLICE_KEYS_VERTICES_BINDING, mesh_->vertex_buffer()},
                   {SLICE_KEYS_KEYS_BINDING, sort_->keys_in().get()},
                   {SLICE_KEYS_INDICES_BINDING, sort_->indices_in().get()},
                   {SLICE_KEYS_PRIMITIVES_BINDING, mesh_->line_index_buffer()}},
                  GL_SHADER_STORAGE_BARRIER_BIT);
    }
    {
      auto t = timer.pass("sort");
      sort_->sort();  // micro/oit/scene/radix_sort.hpp: the one primitive sort
      per_segment(emit_,
                  {{EMIT_SORTED_BINDING, sorted_index().get()},
                   {EMIT_ELEMENTS_BINDING, elements_.get()},
                   {EMIT_PRIMITIVES_BINDING, mesh_->line_index_buffer()}},
                  GL_ELEMENT_ARRAY_BARRIER_BIT);
    }
    auto t = timer.pass("blend");
    target_.bind_cleared(background_.r, background_.g, background_.b, 1);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
    glUseProgram(blend_.get());
    mesh_->draw_lines(elements_.get(), segments_);
    glDisable(GL_BLEND);
  }

  Validation validate() override {
    Validation v;
    auto px = target_.read_rgba32f();
    std::vector<float> rgb(px.size() / 4 * 3);
    size_t nonfinite = 0;
    for (size_t p = 0; p < px.size() / 4; ++p)
      for (int k = 0; k < 3; ++k) {
        // The exact resolve leaves uncovered pixels at alpha 0: they show the background.
        float c = (!slices_mode_ && px[p * 4 + 3] == 0.0f) ? background_[k] : px[p * 4 + k];
        nonfinite += !std::isfinite(c);
        rgb[p * 3 + k] = c;
      }
    auto err = approx_error(rgb, reference_);
    v.metrics = {{"line_segments", std::to_string(segments_)},
                 {"total_fragments", std::to_string(stats_.total_fragments)},
                 {"peak_depth", std::to_string(stats_.peak_depth)},
                 {"rmse", std::to_string(err.rmse)},
                 {"psnr", std::to_string(err.psnr)},
                 {"max_abs_error", std::to_string(err.max_abs_error)},
                 {"frac_pixels_off", std::to_string(err.frac_pixels_off)},
                 {"nonfinite", std::to_string(nonfinite)}};
    if (nonfinite) {
      v.reason = std::to_string(nonfinite) + " non-finite channel(s) in the image";
      return v;
    }
    if (!slices_mode_) {
      auto e = compare_with_reference(px, reference_, stats_, background_, target_.width(), 2.0 / 255);
      v.valid = e.bad_pixels == 0 && e.visit_errors == 0 && stats_.peak_depth <= max_frags_;
      if (!v.valid) v.reason = "exact line resolve differs from the CPU reference: " + e.first_bad;
      return v;
    }
    // The sort: the GPU's own keys, sorted stably on the CPU, must give exactly the GPU's order.
    std::vector<unsigned> keys(segments_), order(segments_), gpu(segments_);
    glGetNamedBufferSubData(sort_->keys_in().get(), 0, static_cast<GLsizeiptr>(segments_ * sizeof(unsigned)),
                            keys.data());
    glGetNamedBufferSubData(sorted_index().get(), 0, static_cast<GLsizeiptr>(segments_ * sizeof(unsigned)), gpu.data());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](unsigned a, unsigned b) { return keys[a] < keys[b]; });
    auto wrong = std::mismatch(order.begin(), order.end(), gpu.begin());
    if (wrong.first != order.end()) {
      v.reason = "radix sort differs from a stable CPU sort at position " +
                 std::to_string(wrong.first - order.begin()) + " (segment " + std::to_string(*wrong.second) +
                 ", expected " + std::to_string(*wrong.first) + ")";
      return v;
    }
    const auto [lo, hi] = std::minmax_element(rgb.begin(), rgb.end());
    v.valid = *lo >= -1e-6f && *hi <= 1.0f + 1e-6f;
    if (!v.valid) v.reason = "blended colour outside [0, 1]";
    return v;
  }

 private:
  const gl::Buffer& sorted_index() const { return sort_->sorted_indices(); }
  // A compute pass of one thread per segment (256 per group) reading and writing `buffers` (binding,
  // buffer), then `barrier` for what reads its output.
  void per_segment(const gl::Program& program, std::initializer_list<std::pair<GLuint, GLuint>> buffers,
                   GLbitfield barrier) const {
    for (const auto& [binding, buffer] : buffers) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buffer);
    glUseProgram(program.get());
    glUniform1ui(glGetUniformLocation(program.get(), "segments"), static_cast<GLuint>(segments_));
    glDispatchCompute(static_cast<GLuint>((segments_ + 255) / 256), 1, 1);
    glMemoryBarrier(barrier);
  }

  void capture() {
    target_.bind();
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    lists_.capture({capture_.get()}, [&] { mesh_->draw(); });
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  }

  CaseContext ctx_;
  bool slices_mode_;
  int slices_, bits_ = 0;
  unsigned max_frags_ = 0;
  glm::vec3 background_;  // the scene's backdrop behind the hair
  glm::mat4 view_proj_{1.0f};
  RenderTarget target_;
  std::unique_ptr<GpuMesh> mesh_;  // the scene's line strands only
  size_t segments_;
  FullscreenTriangle quad_;
  FragmentLists lists_;
  ListStats stats_;
  std::vector<double> reference_;
  std::unique_ptr<RadixSort> sort_;  // the segments' (slice key, index) pairs
  gl::Buffer elements_;
  gl::Program capture_, resolve_, keys_prog_, emit_, blend_;
};

class LinesExperiment final : public Experiment {
 public:
  std::string name() const override { return "lines"; }
  std::string description() const override {
    return "hair as line segments (Sintorn et al. poster), the line strands of a scene (scenes/hair.json): "
           "per-fragment exact OIT vs a per-primitive stream-split radix sort into depth slices, blended back to "
           "front; time and error against exact";
  }
  std::vector<ParamSpec> params() const override {
    ParamSpec technique = ParamSpec::choice("technique",
                                            "exact: linked lists sorted per pixel by insertion+merge sort (IMS) and "
                                            "blended; slices: per-segment radix sort + blend",
                                            {"exact", "slices"});
    ParamSpec segments =
        ParamSpec::integer("segments",
                           "line segments, split over the scene's strands (the poster's models: beard 90 K, woman2 320 "
                           "K, woman1 620 K, dog 1.8 M); 0: as many as the scene file says",
                           0, 50000000, {"90000", "320000", "620000", "1800000"}, {"20000"});
    ParamSpec slices =
        ParamSpec::integer("slices", "depth slices of the primitive sort (a power of two)", 2, 65536, {"256"});
    // The scene and view columns are oit's too, and the schema takes the first experiment's wording: it fits both.
    ParamSpec scene =
        ParamSpec::text("scene",
                        "scene name in scenes/ (shipped: planes, planes-deep, hairball, hair, smoke, engine-grid, "
                        "house) or a path to a scene .json; lines draws its line strands only",
                        {"hair"});
    ParamSpec view = ParamSpec::text(
        "view", "camera view named in the scene file (fwd: lists arrive sorted, rev: reverse sorted)", {"fwd"});
    return {technique, segments, slices, scene, view};
  }
  std::vector<MetricSpec> metric_specs() const override {
    std::vector<MetricSpec> m = {{"line_segments", ValueType::Integer, "", "line segments drawn"},
                                 {"total_fragments", ValueType::Integer, "", "fragments captured in the view"},
                                 {"peak_depth", ValueType::Integer, "", "most fragments in one pixel"}};
    for (auto& e : oit::image_error_metrics()) m.push_back(std::move(e));
    return m;
  }
  Resolution default_resolution() const override { return {512, 512}; }
  Resolution quick_resolution() const override { return {128, 128}; }
  int max_interleave(Resolution) const override { return 2; }
  std::string unsupported_reason(const GlInfo& gl, const ParamSet&) const override {
    return gl.has_compute() ? "" : "needs compute shaders (GL 4.3)";
  }
  std::unique_ptr<CaseInstance> prepare(const ParamSet& p, CaseContext& ctx) override {
    try {
      return std::make_unique<LinesCase>(p, ctx, load_scene(p.get("scene")));
    } catch (const SceneError& e) {
      throw std::runtime_error(std::string("lines: ") + e.what());
    }
  }
};

}  // namespace

void register_lines(Registry& registry) { registry.add(std::make_unique<LinesExperiment>()); }

}  // namespace oitbench
