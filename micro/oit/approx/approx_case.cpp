// The oit experiment's case for the approximate techniques (approx.hpp): captures the view's
// fragments once for the exact reference and the CPU model, then times the technique's own passes.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <sstream>
#include <stdexcept>

#include "core/memory_budget.hpp"
#include "gl/render_target.hpp"
#include "oit/approx/approx.hpp"
#include "oit/approx/approx_model.hpp"
#include "oit/case_support.hpp"
#include "oit/moments/moments.hpp"
#include "oit/reference/geometric_reference.hpp"
#include "oit/reference/image_compare.hpp"
#include "oit/reference/image_io.hpp"
#include "oit/reference/reference.hpp"
#include "oit/reference/visible_capture.hpp"
#include "oit/scene/coverage_estimate.hpp"
#include "oit/scene/gpu_mesh.hpp"
#include "oit/scene/radix_sort.hpp"
#include "oit/scene/scene.hpp"
#include "oit/scene/scene_passes.hpp"
#include "oit/splats/splat_check.hpp"
#include "oit/storage/storage_layout.hpp"
#include "oit/techniques.hpp"
#include "shaders/approx/bindings.h"
#include "shaders/splats/bindings.h"

namespace oitbench::oit {

namespace {

// The GPU and its model differ by float rounding (fused multiply-adds, exp/log/pow), and MLAB's
// RGBA8 nodes can round the other way at a half step and carry that through later merges.
constexpr double kModelTolerance = 3.0 / 255.0;

}  // namespace

std::vector<ParamSpec> approx_params() {
  // Scoped to the techniques that read them by the technique table (micro/oit/techniques.cpp).
  return {
      ParamSpec::integer(
          "nodes",
          "nodes per pixel (the thesis: 4-16); for hybrid transparency and its K-only mode, the fragments of its "
          "core (K)",
          2, 64, {"8"}),
      ParamSpec::choice(
          "ht_variant",
          "hybrid transparency's configuration: maule (Maule et al. 2013: every fragment may enter the core; the tail "
          "covers 1 - (1 - mean alpha)^n) or htgs (HTGS's HYBRID_BLEND, Hahlbohm et al. 2025: only "
          "fragments of alpha >= 0.05 enter the core; the tail covers 1 - prod (1 - alpha))",
          {"maule", "htgs"}, {"maule"}),
      ParamSpec::integer("window",
                         "the fragments each pixel's sorted window holds (StopThePop's per-pixel queue: "
                         "16 in its k-buffer mode, 4 behind its tile queues)",
                         1, 64, {"16"}),
      ParamSpec::choice("storage", "node storage of the per-pixel array techniques (shaders/storage/)",
                        {"ssbo", "texture3d", "interleaved"}, {"ssbo"}),
      ParamSpec::choice(
          "wboit_weight",
          "depth weight of the weighted blend: none (weighted average), eq7 (view distance), eq10 (window depth)",
          {"none", "eq7", "eq10"}, {"eq7"}),
      ParamSpec::choice(
          "sync", "per-pixel insertion: spinlock (Listing 4.3, capped) or interlock (ARB_fragment_shader_interlock)",
          {"spinlock", "interlock"}, {"spinlock"}),
      ParamSpec::choice("guard", "numeric guards (off: the deliberately unguarded variant the hard-case tests use)",
                        {"on", "off"}, {"on"}),
      ParamSpec::integer("flicker_runs", "frames kept for the flicker metric (per-pixel variance across runs; 0: off)",
                         0, 64, {"4"}),
  };
}
namespace {

class ApproxCase final : public OitCase {
 public:
  ApproxCase(const ParamSet& p, CaseContext& ctx)
      : width_(ctx.width()),
        height_(ctx.height()),
        passes_(p, ctx),
        scene_(passes_.scene()),
        out_(ctx.width(), ctx.height(), GL_RGBA32F),
        accum_(ctx.width(), ctx.height(), GL_RGBA32F),
        flicker_runs_(static_cast<int>(p.get_int("flicker_runs"))),
        dump_(ctx.image_stem()) {
    phases_ = ctx.phase_clock();
    settings_.technique = static_cast<ApproxTechnique>(technique(p.get("technique")).variant);
    using T = ApproxTechnique;
    const T tech = settings_.technique;
    settings_.nodes = static_cast<int>(p.get_int(tech == T::WindowSort ? "window" : "nodes"));
    settings_.weight = p.get("wboit_weight");
    settings_.unguarded = p.get("guard") == "off";
    settings_.htgs = tech == T::Ht && p.get("ht_variant") == "htgs";
    arrays_ = tech != T::Wboit && tech != T::Unsorted && tech != T::GlobalSort;
    ht_ = tech == T::Ht;
    at_family_ = arrays_ && tech != T::Mlab && tech != T::Umlab && !ht_ && tech != T::FirstK && tech != T::WindowSort;
    splat_order_ = tech == T::GlobalSort || tech == T::WindowSort;
    if (splat_order_ && !passes_.splats())
      throw Unsupported(p.get("technique") + " sorts splats: scene '" + scene_.name + "' (" + scene_.path +
                        ") has none");
    bool interlock = p.get("sync") == "interlock";
    if (arrays_ && interlock && !ctx.gl().has_extension("GL_ARB_fragment_shader_interlock"))
      throw Unsupported("sync=interlock needs GL_ARB_fragment_shader_interlock");
    if (arrays_) require_array_memory(p, ctx);            // refused before the reference capture or anything else
    if (tech == T::GlobalSort) plan_global_sort(ctx, p);  // its sort and early_stop's targets

    const View& view = passes_.view();
    glm::mat4 vp = passes_.view_projection();
    passes_.attach_opaque_depth(out_.framebuffer());
    passes_.attach_opaque_depth(accum_.framebuffer());
    // Analytic scenes: the truth from the scene's own planes (the capture keeps RGBA8 colours).
    auto referencing = ctx.phase(Phase::Reference);
    if (passes_.effects() == std::vector<std::string>{"transparency"})  // the geometry knows no other effect
      geometry_ = shared_geometric_reference(ctx.shared(), scene_, view,
                                             p.get("detail") == "small" ? Detail::Small : Detail::Full,
                                             near_far(view, passes_.mesh()), width_, height_, FragColour::RGBA8);
    // The planes back out of the perspective matrix (glm::perspective's layout).
    glm::mat4 pm = vp * glm::inverse(glm::lookAt(view.eye, view.target, view.up));
    settings_.near_far = {pm[3][2] / (pm[2][2] - 1.0f), pm[3][2] / (pm[2][2] + 1.0f)};

    // The view's fragments, once per run and view (visible_capture.hpp): the exact reference and the CPU model.
    ref_ = reference_view(passes_, vp, p, ctx);
    if (splat_order_) global_sort_model_view(p, ctx, vp);
    referencing.end();

    Defines d = {{"TECH_" + upper(p.get("technique")), ""}, {"SPIN_CAP", std::to_string(kSpinCap)}};
    if (settings_.unguarded) d.push_back({"APPROX_UNGUARDED", ""});
    if (interlock) d.push_back({"SYNC_INTERLOCK", ""});
    if (settings_.htgs) d.push_back({"HT_HTGS", ""});
    for (auto& x : passes_.geometry_defines()) d.push_back(x);
    if (splat_order_) build_global_sort(ctx, p.get("technique"), d, vp, tech == T::WindowSort);
    if (arrays_) {
      std::string storage = p.get("storage");
      layout_ = StorageLayout::parse(storage == "interleaved" ? "interleaved-4x4-a4" : storage);
      const int slots = array_slots();
      if (layout_.kind == StorageLayout::Kind::Interleaved && slots % layout_.align) layout_.align = 1;
      for (const auto& x : layout_.defines(width_, height_, slots)) d.push_back(x);
      storage_ = std::make_unique<StorageResources>(layout_, width_, height_, slots);
      locks_ = gl::make_texture(GL_TEXTURE_2D);
      glTextureStorage2D(locks_.get(), 1, GL_R32UI, width_, height_);
      stats_ = gl::make_buffer();
      glNamedBufferStorage(stats_.get(), sizeof(unsigned), nullptr, GL_DYNAMIC_STORAGE_BIT);
      insert_ = ctx.build({{GL_VERTEX_SHADER, "scene/scene.vert"}, {GL_FRAGMENT_SHADER, "approx/insert.frag"}}, d);
      set_view_proj(insert_, vp);
      if (at_family_ || ht_) {
        const char* pass2 = ht_ ? "approx/ht_tail.frag" : "approx/at_blend.frag";
        blend_ = ctx.build({{GL_VERTEX_SHADER, "scene/scene.vert"}, {GL_FRAGMENT_SHADER, pass2}}, d);
        set_view_proj(blend_, vp);
      }
      if (ht_) {  // the tail's fragment count beside its sums
        reveal_ = gl::make_texture(GL_TEXTURE_2D);
        glTextureStorage2D(reveal_.get(), 1, GL_R32F, width_, height_);
        glNamedFramebufferTexture(accum_.framebuffer(), GL_COLOR_ATTACHMENT1, reveal_.get(), 0);
      }
      bytes_per_pixel_ += slots * 8.0 + 4.0 + (at_family_ || ht_ ? 16.0 : 0.0) + (ht_ ? 4.0 : 0.0);
      resolve_ =
          ctx.build({{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "approx/resolve.frag"}}, d);
    } else if (tech == T::Wboit) {
      d.push_back({"WEIGHT_" + upper(settings_.weight), ""});
      blend_ = ctx.build({{GL_VERTEX_SHADER, "scene/scene.vert"}, {GL_FRAGMENT_SHADER, "approx/wboit_accum.frag"}}, d);
      set_view_proj(blend_, vp);
      glProgramUniform2f(blend_.get(), glGetUniformLocation(blend_.get(), "nearFar"), settings_.near_far.x,
                         settings_.near_far.y);
      reveal_ = gl::make_texture(GL_TEXTURE_2D);
      glTextureStorage2D(reveal_.get(), 1, GL_R32F, width_, height_);
      glNamedFramebufferTexture(accum_.framebuffer(), GL_COLOR_ATTACHMENT1, reveal_.get(), 0);
      resolve_ = ctx.build(
          {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "approx/wboit_resolve.frag"}}, d);
      bytes_per_pixel_ = 16.0 + 4.0;
    } else {
      const char* blend = early_stop_ ? "approx/global_stop.frag" : "approx/unsorted.frag";
      blend_ = ctx.build({{GL_VERTEX_SHADER, "scene/scene.vert"}, {GL_FRAGMENT_SHADER, blend}}, d);
      set_view_proj(blend_, vp);
    }
  }

  // GLOBAL-SORT (Kerbl et al. 2023): every frame a compute pass keys each splat by its centre's view depth
  // (shaders/splats/keys.comp) and the primitive radix sort orders them back to front; the blend pass then
  // draws the splats in that order (SPLAT_ORDERED) with "over" blending, as `unsorted` draws them in theirs.
  // WINDOW-SORT (`near_first`) sorts them front to back and inserts them in that order into its windows.
  // With early_stop, near to far too, composited front to back and stopped early (approx/global_stop.frag).
  // A scene without splats never gets here: the technique table says it draws only splats (make_oit_case).
  void build_global_sort(CaseContext& ctx, const std::string& technique, Defines& d, const glm::mat4& vp,
                         bool near_first) {
    const GpuSplats* splats = passes_.splats();
    if (!splats) throw std::logic_error(technique + ": scene '" + scene_.name + "' has no splats");
    d.push_back({"SPLAT_ORDERED", ""});
    sort_ = std::make_unique<RadixSort>(ctx, splats->size(), 32);
    early_stop_ = settings_.early_stop > 0;
    if (early_stop_) {
      if (ctx.gl().has_extension("GL_ARB_fragment_shader_interlock"))
        d.push_back({"GLOBAL_STOP_INTERLOCK", ""});
      else if (!ctx.gl().is_software_renderer())
        throw Unsupported(technique +
                          " with early_stop reads and writes each pixel's transmittance in submission order: it needs "
                          "GL_ARB_fragment_shader_interlock on a hardware driver");
      for (auto& x : early_stop_defines(settings_.early_stop, ctx.fault())) d.push_back(x);
      reveal_ = gl::make_texture(GL_TEXTURE_2D);  // each pixel's transmittance
      glTextureStorage2D(reveal_.get(), 1, GL_R32F, width_, height_);
      resolve_ = ctx.build(
          {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "approx/global_stop_resolve.frag"}}, d);
    }
    keys_ = ctx.build({{GL_COMPUTE_SHADER, "splats/keys.comp"}},
                      near_first || early_stop_ ? Defines{{"SPLAT_KEYS_NEAR_FIRST", ""}} : Defines{});
    set_view_proj(keys_, vp);
    bytes_per_pixel_ = static_cast<double>(sort_->bytes()) / (static_cast<double>(width_) * height_);
    if (early_stop_) bytes_per_pixel_ += 16.0 + 4.0;  // the accumulated colour and the transmittance
  }
  // GLOBAL-SORT's early_stop, and its memory: the sort's buffers beside the scene's splats (with early_stop,
  // the accumulated colour and the transmittance per pixel too), refused before the reference capture.
  void plan_global_sort(const CaseContext& ctx, const ParamSet& p) {
    settings_.early_stop = static_cast<float>(early_stop_of(p));
    const std::string technique = p.get("technique");
    const size_t splats = passes_.mesh().splats.size();
    const unsigned long long pixels = static_cast<unsigned long long>(width_) * height_;
    MemoryNeed need;
    need.gpu_bytes = RadixSort::bytes_for(splats) + (settings_.early_stop > 0 ? pixels * 20 : 0);
    need.gpu_what = "the radix sort's keys and indices (" + format_count(splats) + " splats x 28 B)";
    require_memory(combined(need, scene_held_memory(passes_.mesh())), ctx.memory(), technique + "'s sort:");
  }
  // The technique's own storage: the nodes' 8 bytes, the lock, and the AT family's and HT's accumulation targets.
  void require_array_memory(const ParamSet& p, const CaseContext& ctx) const {
    const unsigned long long slots = static_cast<unsigned long long>(array_slots());
    const unsigned long long pixels = static_cast<unsigned long long>(width_) * height_;
    MemoryNeed need;
    need.gpu_bytes = pixels * (slots * 8 + 4 + (at_family_ || ht_ ? 16 : 0) + (ht_ ? 4 : 0));
    need.gpu_what = "the node arrays (" + format_count(pixels) + " pixels x " + std::to_string(slots) +
                    " nodes x 8 B, the locks and accumulation targets)";
    require_memory(need, ctx.memory(), p.get("technique") + "'s node arrays:");
  }
  // Node slots per pixel: LAAT keeps its list head in one more, WINDOW-SORT its blended colour in two.
  int array_slots() const {
    using T = ApproxTechnique;
    return settings_.nodes + (settings_.technique == T::Laat ? 1 : 0) + (settings_.technique == T::WindowSort ? 2 : 0);
  }
  void sort_pass(PassTimer& timer) {
    if (!sort_) return;
    auto t = timer.pass("sort");
    sort_splats();
  }
  void sort_splats() {
    const GLuint count = static_cast<GLuint>(sort_->size());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SPLATS_BINDING, passes_.splats()->buffer());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SPLAT_KEYS_BINDING, sort_->keys_in().get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SPLAT_KEY_INDICES_BINDING, sort_->indices_in().get());
    glUseProgram(keys_.get());
    glUniform1ui(glGetUniformLocation(keys_.get(), "count"), count);
    glDispatchCompute((count + 255) / 256, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    sort_->sort();
  }
  // GLOBAL-SORT's CPU model blends each pixel's fragments in the order of their splats' centres: the
  // fragments captured with the centre key (splat_depth=centre), stably sorted far to near. With
  // splat_depth=ray-max the reference's fragments carry the other key, so the model's are captured apart.
  void global_sort_model_view(const ParamSet& p, CaseContext& ctx, const glm::mat4& vp) {
    if (p.get("splat_depth") == "centre") return;
    std::vector<std::pair<std::string, std::string>> values = p.values();
    for (auto& [k, v] : values)
      if (k == "splat_depth") v = "centre";
    ParamSet centre(values);
    ScenePasses fx(centre, ctx);
    centre_host_ = std::make_unique<HostLists>(std::move(capture_visible_fragments(fx, vp, centre, ctx).host));
  }

  GLuint opaque_texture() const override { return passes_.opaque_texture(); }
  std::map<std::string, std::string> resolved_params() const override { return passes_.resolved_params(); }
  void set_view_projection(const glm::mat4& view_proj) override {
    passes_.set_view_projection(view_proj);
    for (const gl::Program* prog : {&insert_, &blend_, &keys_})
      if (*prog) set_view_proj(*prog, view_proj);
  }
  GLuint result_texture() override { return out_.color_texture(); }
  unsigned max_frags() const override { return arrays_ ? static_cast<unsigned>(settings_.nodes) : 0; }

  void run(PassTimer& timer) override {
    using T = ApproxTechnique;
    passes_.run_before(timer);
    for (const gl::Program* prog : {&insert_, &blend_})
      if (*prog) passes_.bind_geometry(prog->get());
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    if (!passes_.transparency()) {  // nothing transparent: the image is the backdrop
      passes_.fill_with_backdrop(out_.framebuffer(), out_.color_texture());
    } else if (arrays_) {
      sort_pass(timer);
      {
        auto t = timer.pass("insert");
        storage_->clear();
        glClearTexImage(locks_.get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
        glClearNamedBufferData(stats_.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
        out_.bind();
        glDisable(GL_BLEND);
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        storage_->bind();
        glBindImageTexture(APPROX_LOCK_IMAGE_UNIT, locks_.get(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, APPROX_STATS_BINDING, stats_.get());
        draw_transparent(insert_);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        StorageResources::barrier();
      }
      if (at_family_ || ht_) {
        auto t = timer.pass(ht_ ? "tail" : "blend");
        accum_.bind();
        const GLenum bufs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
        glNamedFramebufferDrawBuffers(accum_.framebuffer(), ht_ ? 2 : 1, bufs);
        const float zero[4] = {0, 0, 0, 0}, one[4] = {1, 1, 1, 1};
        glClearNamedFramebufferfv(accum_.framebuffer(), GL_COLOR, 0, zero);
        if (ht_) glClearNamedFramebufferfv(accum_.framebuffer(), GL_COLOR, 1, settings_.htgs ? one : zero);
        glEnable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);
        glBlendFunc(GL_ONE, GL_ONE);
        if (settings_.htgs) glBlendFunci(1, GL_ZERO, GL_ONE_MINUS_SRC_COLOR);  // the tail's transmittance product
        draw_transparent(blend_);
        glDisable(GL_BLEND);
      }
      resolve(timer, ht_);
    } else if (settings_.technique == T::Wboit) {
      {
        auto t = timer.pass("accumulate");
        accum_.bind();
        const GLenum bufs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
        glNamedFramebufferDrawBuffers(accum_.framebuffer(), 2, bufs);
        const float zero[4] = {0, 0, 0, 0}, one[4] = {1, 1, 1, 1};
        glClearNamedFramebufferfv(accum_.framebuffer(), GL_COLOR, 0, zero);
        glClearNamedFramebufferfv(accum_.framebuffer(), GL_COLOR, 1, one);
        glEnable(GL_BLEND);
        glBlendFunci(0, GL_ONE, GL_ONE);
        glBlendFunci(1, GL_ZERO, GL_ONE_MINUS_SRC_COLOR);
        draw_transparent(blend_);
        glDisable(GL_BLEND);
      }
      resolve(timer, true);
    } else {
      sort_pass(timer);
      if (early_stop_) {
        blend_front_to_back(timer);
        resolve(timer, true);
      } else {
        auto t = timer.pass("blend");
        out_.bind();
        passes_.fill_with_backdrop(out_.framebuffer(), out_.color_texture());
        glEnable(GL_BLEND);
        glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
        draw_transparent(blend_);
        glDisable(GL_BLEND);
      }
    }
    // Outside the timed passes: the frames the flicker metric compares.
    if (flicker_runs_ > 0) {
      frames_.push_back(rgb_of(out_.read_rgba32f()));
      if (static_cast<int>(frames_.size()) > flicker_runs_) frames_.erase(frames_.begin());
    }
  }

  // GLOBAL-SORT's early stop: the sorted splats front to back, T alpha c added up in accum_, each pixel's
  // transmittance (from 1) in reveal_.
  void blend_front_to_back(PassTimer& timer) {
    auto t = timer.pass("blend");
    accum_.bind();
    const GLenum first = GL_COLOR_ATTACHMENT0;
    glNamedFramebufferDrawBuffers(accum_.framebuffer(), 1, &first);
    const float zero[4] = {0, 0, 0, 0}, one = 1.0f;
    glClearNamedFramebufferfv(accum_.framebuffer(), GL_COLOR, 0, zero);
    glClearTexImage(reveal_.get(), 0, GL_RED, GL_FLOAT, &one);
    glBindImageTexture(APPROX_TRANSMITTANCE_IMAGE_UNIT, reveal_.get(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32F);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    draw_transparent(blend_);
    glDisable(GL_BLEND);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  }
  // The transparent geometry through `program`, between the effects' geometry set-up and tear-down.
  void draw_transparent(const gl::Program& program) {
    glUseProgram(program.get());
    passes_.begin_geometry();
    if (sort_)
      passes_.splats()->draw_ordered(sort_->sorted_indices().get());
    else
      passes_.transparent().draw();
    passes_.end_geometry();
  }
  // The full-screen resolve of the accumulated colour (and the revealage, where `reveal`) over the backdrop.
  void resolve(PassTimer& timer, bool reveal) {
    auto t = timer.pass("resolve");
    out_.bind();
    glBindTextureUnit(APPROX_ACCUM_UNIT, accum_.color_texture());
    if (reveal) glBindTextureUnit(APPROX_REVEAL_UNIT, reveal_.get());
    passes_.bind_backdrop(resolve_.get());
    glUseProgram(resolve_.get());
    quad_.draw();
  }

  Validation validate() override {
    Validation v;
    auto& m = v.metrics;
    auto reading = PhaseClock::Scope(phases_, Phase::Readback);
    std::vector<float> rgb = rgb_of(out_.read_rgba32f());
    reading.end();
    const ListStats& stats = ref_->stats;
    const std::vector<double>& ref = ref_->composite;
    auto referencing = PhaseClock::Scope(phases_, Phase::Reference);
    const HostLists& order = centre_host_ ? *centre_host_ : ref_->host;
    ApproxModel model = settings_.technique == ApproxTechnique::WindowSort
                            ? window_sort_model(order, ref_->host, ref_->backdrop, settings_.nodes)
                            : approx_model(order, ref_->backdrop, settings_);
    referencing.end();
    if (passes_.opaque()) m["hidden_fragments"] = std::to_string(ref_->hidden);
    ApproxError err = approx_error(rgb, ref);
    m["total_fragments"] = std::to_string(stats.total_fragments);
    m["peak_depth"] = std::to_string(stats.peak_depth);
    m["mean_depth"] = fmt(stats.mean_depth);
    m["polygons"] = std::to_string(passes_.mesh().polygons());
    m["rmse"] = fmt(err.rmse);
    m["psnr"] = fmt(err.psnr);
    m["max_abs_error"] = fmt(err.max_abs_error);
    m["frac_pixels_off"] = fmt(err.frac_pixels_off);
    m["bytes_per_pixel"] = fmt(bytes_per_pixel_);
    m["model_rmse"] = fmt(approx_error(model.rgb, std::vector<double>(ref.begin(), ref.end())).rmse);

    size_t nonfinite = 0, out_of_range = 0, model_off = 0;
    double model_max = 0;
    std::string first_off;
    for (size_t i = 0; i < rgb.size(); ++i) {
      if (!std::isfinite(rgb[i]))
        ++nonfinite;
      else if (rgb[i] < -1.0 / 255.0 || rgb[i] > 1.0 + 2.0 / 255.0)
        ++out_of_range;
      double d = std::abs(static_cast<double>(rgb[i]) - model.rgb[i]);
      if (!std::isfinite(d) && std::isfinite(rgb[i]) != std::isfinite(model.rgb[i])) d = 1.0;
      if (!std::isfinite(d)) d = 0.0;  // both non-finite: the model predicts the failure
      model_max = std::max(model_max, d);
      if (d > kModelTolerance && model_off++ == 0) {
        size_t px = i / 3;
        first_off = "pixel (" + std::to_string(px % width_) + "," + std::to_string(px / width_) + ") channel " +
                    std::to_string(i % 3) + ": GPU " + fmt(rgb[i]) + ", model " + fmt(model.rgb[i]);
      }
    }
    m["nonfinite"] = std::to_string(nonfinite);
    m["out_of_range_pixels"] = std::to_string(image_range(rgb, 3).out_of_range_pixels);
    if (geometry_) {
      std::vector<float> rgba(rgb.size() / 3 * 4, 1.0f);  // as the geometric check reads an image
      for (size_t i = 0; i < rgb.size() / 3; ++i)
        for (int k = 0; k < 3; ++k) rgba[i * 4 + k] = rgb[i * 3 + k];
      GeometricCheck g = check_against_geometry(*geometry_, rgba, {}, scene_.background, 1.0);
      m["truth_rmse"] = fmt(g.truth_rmse);
      m["truth_max_abs_error"] = fmt(g.truth_max_abs_error);
    }
    // Splat scenes: the error against the analytic reference, reported (an approximation is not held to it).
    // Every pass here shades RGBA8 fragments (scene_fragment_rgba8), so the reference rounds its fragments the
    // same way, as it does for an exact case's RGBA8 capture: the error left is the approximation's own.
    report_splat_check(
        check_against_splats(passes_, rgb, 3, width_, height_, kModelTolerance, true, settings_.early_stop),
        kModelTolerance, m, nullptr);
    m["model_max_diff"] = fmt(model_max);
    unsigned capped = 0;
    if (arrays_) {
      glGetNamedBufferSubData(stats_.get(), 0, sizeof(unsigned), &capped);
      m["capped_updates"] = std::to_string(capped);
    }
    if (frames_.size() >= 2) {
      Flicker f = flicker_of(frames_);
      m["flicker"] = fmt(f.mean);
      m["flicker_max"] = fmt(f.peak);
      m["flicker_pixels"] = std::to_string(f.changed);
    }
    if (!dump_.empty()) write_result_images(dump_, rgb, std::vector<double>(ref.begin(), ref.end()), width_, height_);

    std::vector<std::string> problems;
    if (!stats.error.empty()) problems.push_back(stats.error);
    if (!model.error.empty()) problems.push_back("the CPU model: " + model.error);
    if (nonfinite) problems.push_back(std::to_string(nonfinite) + " non-finite channel value(s) (NaN or Inf)");
    if (out_of_range) problems.push_back(std::to_string(out_of_range) + " channel value(s) outside [0, 1]");
    if (capped) problems.push_back(std::to_string(capped) + " insertion(s) gave up on the spinlock (lost)");
    if (model_off)
      problems.push_back(std::to_string(model_off) +
                         " channel value(s) differ from the technique's CPU model by more "
                         "than 3/255; first: " +
                         first_off);
    merge_shadow_check(m, problems, passes_.validate_shadow());
    conclude(v, problems);
    return v;
  }

 private:
  PhaseClock* phases_ = nullptr;  // the run's time account (core/phases.hpp); null: none
  // The colour behind the transparent layers: one place, for the scene effects to replace.
  static std::string upper(std::string s) {
    for (auto& ch : s) ch = ch == '-' ? '_' : static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    return s;
  }
  static void set_view_proj(const gl::Program& prog, const glm::mat4& vp) {
    glProgramUniformMatrix4fv(prog.get(), glGetUniformLocation(prog.get(), "viewProj"), 1, GL_FALSE, &vp[0][0]);
  }
  static std::vector<float> rgb_of(const std::vector<float>& rgba) {
    std::vector<float> rgb(rgba.size() / 4 * 3);
    for (size_t p = 0; p < rgba.size() / 4; ++p)
      for (int k = 0; k < 3; ++k) rgb[p * 3 + k] = rgba[p * 4 + k];
    return rgb;
  }

  int width_, height_;
  ScenePasses passes_;
  const SceneDesc& scene_;
  std::shared_ptr<const GeometricReference> geometry_;  // analytic scenes; shared by the run
  RenderTarget out_, accum_;
  FullscreenTriangle quad_;
  std::shared_ptr<const ReferenceView> ref_;
  ApproxSettings settings_;
  bool arrays_ = false, at_family_ = false, ht_ = false;
  bool splat_order_ = false;  // GLOBAL-SORT, WINDOW-SORT: the splats drawn in their centres' order
  bool early_stop_ = false;   // GLOBAL-SORT with early_stop: front to back, stopped early
  double bytes_per_pixel_ = 0;
  StorageLayout layout_;
  std::unique_ptr<StorageResources> storage_;
  gl::Texture locks_, reveal_;
  gl::Buffer stats_;
  gl::Program insert_, blend_, resolve_, keys_;
  std::unique_ptr<RadixSort> sort_;         // GLOBAL-SORT, WINDOW-SORT
  std::unique_ptr<HostLists> centre_host_;  // the splat orders with splat_depth=ray-max: the model's order
  int flicker_runs_;
  std::string dump_;
  std::vector<std::vector<float>> frames_;
};

}  // namespace

std::unique_ptr<OitCase> make_approx_case(const ParamSet& p, CaseContext& ctx) {
  return std::make_unique<ApproxCase>(p, ctx);
}

}  // namespace oitbench::oit
