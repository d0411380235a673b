// Exact order-independent transparency: per-pixel linked lists captured from a scene file and
// resolved by the sorts of Knowles, Leach, Zambetta 2013 (BMA) and 2014 (register-based block
// sort, RBS), on the GPU or on the CPU (CPU-NATIVE). Validated against the CPU reference
// compositor working on the same fragments read back from the GPU.
#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>

#include "core/stats.hpp"
#include "gl/render_target.hpp"
#include "oit/approx/approx.hpp"
#include "oit/capture/fragment_counts.hpp"
#include "oit/capture/fragment_storage.hpp"
#include "oit/capture/packed_arrays.hpp"
#include "oit/case_support.hpp"
#include "oit/oit_case.hpp"
#include "oit/peel/peel.hpp"
#include "oit/reference/geometric_reference.hpp"
#include "oit/reference/image_compare.hpp"
#include "oit/reference/image_io.hpp"
#include "oit/reference/reference.hpp"
#include "oit/resolve/bma_auto.hpp"
#include "oit/resolve/compute_resolve.hpp"
#include "oit/resolve/resolve_sort.hpp"
#include "oit/scene/coverage_estimate.hpp"
#include "oit/scene/gpu_mesh.hpp"
#include "oit/scene/scene.hpp"
#include "oit/scene/scene_passes.hpp"
#include "oit/splats/splat_check.hpp"
#include "oit/techniques.hpp"
#include "shaders/resolve/bindings.h"

namespace oitbench::oit {

namespace {

// rgba8: 2/255: a fragment's colour is packed to RGBA8 for both the GPU and the reference, so what
// is left is float vs double blending and the order of equal-depth fragments. The float formats
// keep their colours to 2^-11 (rgba16f) and 2^-24 (rgba32f), so what is left is float blending:
// 1e-3 and 1e-4 (5000 layers of float mix() stay well inside; docs/precision.md).
double tolerance_of(FragColour c) {
  return c == FragColour::RGBA8 ? 2.0 / 255.0 : c == FragColour::RGBA16F ? 1e-3 : 1e-4;
}
constexpr int kFirstInterval = 8;  // BMA intervals: 1-8, 9-16, 17-32, ... (Knowles 2014, section 4)
// Pool sizings a run keeps for its cases to share (each a few numbers): more than the views of a preset.
constexpr size_t kSharedPoolSizings = 64;

class ExactCase final : public OitCase {
 public:
  ExactCase(const ParamSet& p, CaseContext& ctx)
      : dump_(ctx.image_stem()),
        ctx_(ctx),
        width_(ctx.width()),
        height_(ctx.height()),
        wrong_result_(ctx.fault() == "wrong-result"),
        technique_(technique(p.get("technique"))),
        bma_(technique_.scheme == ResolveScheme::Bma),
        native_(technique_.scheme == ResolveScheme::Cpu),
        compute_(technique_.scheme == ResolveScheme::Compute),
        auto_(bma_ && !technique_.resolve_sort),  // BMA-AUTO: the sort chosen per interval
        use_auto_cache_(p.get("bma_auto_cache") == "on"),
        block_(static_cast<int>(p.get_int("block"))),
        block_sort_(parse_block_sort(p.has("block_sort") ? p.get("block_sort") : "insertion")),
        order_check_(p.has("order_check") && p.get("order_check") == "on"),
        early_stop_(technique_.reads("early_stop") ? early_stop_of(p) : 0.0),
        format_(parse_frag_format(p.get("frag_colour"), p.get("frag_depth"))),
        tolerance_(tolerance_of(format_.colour)),
        passes_(p, ctx),
        scene_(passes_.scene()),
        target_(ctx.width(), ctx.height(), GL_RGBA32F, true) {
    if (passes_.opaque() && format_.depth == FragDepth::View)
      throw Unsupported(
          "the opaque effect's checks compare window depths (the CPU's depth test against the opaque depth); "
          "frag_depth=view stores view distances: run it with effects=transparency");
    passes_.attach_opaque_depth(target_.framebuffer());
    view_proj_ = passes_.view_projection();
    view_ = passes_.view();
    detail_ = p.get("detail") == "small" ? Detail::Small : Detail::Full;
    near_far_ = near_far(passes_.view(), passes_.mesh());
    // The view's peak depth sets MAX_FRAGS (the next power of two at or above it, as the paper does)
    // before anything is compiled.
    const std::shared_ptr<const PoolSizing> sizing = size_pool(p, ctx);
    long long forced = p.get_int("max_frags");
    max_frags_ = forced > 0 ? static_cast<unsigned>(forced)
                            : std::max<unsigned>(kFirstInterval, std::bit_ceil(sizing->peak_depth));
    if (native_) return;
    if (compute_) {
      auto [gx, gy] = parse_group(p.get("cs_group"));
      note_sort(technique_choice(), max_frags_);
      compute_resolve_ = std::make_unique<ComputeResolve>(ctx, resolve_defines(technique_choice(), max_frags_),
                                                          passes_.scene().background, gx, gy);
      return;
    }
    if (bma_) {
      count_ = ctx.build({{GL_COMPUTE_SHADER, "resolve/bma_count.comp"}}, lists_->defines());
      mask_ = ctx.build({{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "resolve/bma_mask.frag"}},
                        lists_->defines());
      histogram_ = gl::make_buffer();
      glNamedBufferStorage(histogram_.get(), 32 * sizeof(unsigned), nullptr, GL_DYNAMIC_STORAGE_BIT);
      for (unsigned top = kFirstInterval; top <= max_frags_; top *= 2) interval_tops_.push_back(top);
      // Compile the intervals this view uses now (compile time is not frame time); others on demand.
      std::vector<bool> used(interval_tops_.size(), false);
      for (unsigned d : sizing->depths) used[interval_of(d)] = true;
      interval_programs_.resize(interval_tops_.size());
      if (auto_) calibrate_bma_auto();
      for (size_t i = 0; i < used.size(); ++i)
        if (used[i]) interval_program(i);
    } else {
      base_ = build_resolve(technique_choice(), max_frags_);
      note_sort(technique_choice(), max_frags_);
    }
  }

  GLuint opaque_texture() const override { return passes_.opaque_texture(); }
  std::map<std::string, std::string> resolved_params() const override { return passes_.resolved_params(); }
  void set_view_projection(const glm::mat4& view_proj) override {
    view_proj_ = view_proj;
    passes_.set_view_projection(view_proj);
    for (const auto& prog : capture_)
      glProgramUniformMatrix4fv(prog.get(), glGetUniformLocation(prog.get(), "viewProj"), 1, GL_FALSE,
                                &view_proj_[0][0]);
  }
  GLuint result_texture() override {
    if (native_ && !native_out_.empty())  // CPU-NATIVE's image lives on the CPU: upload it for display
      glTextureSubImage2D(target_.color_texture(), 0, 0, 0, width_, height_, GL_RGBA, GL_FLOAT, native_out_.data());
    return target_.color_texture();
  }
  const FragmentStorage* fragments() const override { return lists_.get(); }
  // sort_source: the library files of the sorts the resolve programs run, with their hashes
  // ("sorts/insertion.glsl@1a2b3c4d+sorts/merge.glsl@..."); empty for CPU-NATIVE.
  std::map<std::string, std::string> metrics() const override {
    std::string s;
    for (const auto& id : sort_sources_) s += (s.empty() ? "" : "+") + id;
    return {{"sort_source", s}};
  }
  unsigned max_frags() const override { return max_frags_; }

  void run(PassTimer& timer) override {
    passes_.run_before(timer);
    if (!passes_.transparency()) {  // nothing transparent: the image is the backdrop, no capture or resolve
      passes_.fill_with_backdrop(target_.framebuffer(), target_.color_texture());
      return;
    }
    target_.bind();
    {
      auto t = timer.pass("capture");
      auto start = std::chrono::steady_clock::now();
      overflow_rerenders_ += capture();
      capture_ms_.push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
      if (const auto* packed = dynamic_cast<const PackedArrays*>(lists_.get()))
        count_ms_.push_back(packed->last_count_ms());
    }
    if (native_) {
      {
        auto t = timer.cpu_pass("readback");  // a transfer the CPU waits for: the CPU clock times it
        host_ = lists_->read_back();
        native_backdrop_ = passes_.read_backdrop();
      }
      auto t = timer.cpu_pass("resolve");  // C++ threads: no GL work for a query to time
      const bool stops = ctx_.fault() != "no-early-stop";
      resolve_native(host_, native_backdrop_, 0, wrong_result_, native_out_,
                     stops ? static_cast<float>(early_stop_) : 0);
      return;
    }
    if (compute_) {
      auto t = timer.pass("resolve");
      passes_.bind_backdrop(compute_resolve_->program());
      compute_resolve_->run(*lists_, target_);
      return;
    }
    if (!bma_) {
      auto t = timer.pass("resolve");
      begin_resolve();
      draw_resolve(base_);
      end_resolve();
      return;
    }
    std::vector<unsigned> pixels;
    {
      auto t = timer.pass("count");
      pixels = count_intervals();
    }
    {
      auto t = timer.pass("mask");
      mask_intervals(pixels);
    }
    auto t = timer.pass("resolve");
    begin_resolve();
    glEnable(GL_STENCIL_TEST);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    intervals_run_ = 0;
    for (size_t i = 0; i < interval_tops_.size(); ++i) {
      if (!pixels[i]) continue;  // no pixels: the interval's program never runs
      glStencilFunc(GL_EQUAL, static_cast<GLint>(i + 1), 0xFF);
      draw_resolve(interval_program(i));
      ++intervals_run_;
    }
    glDisable(GL_STENCIL_TEST);
    end_resolve();
    interval_pixels_ = pixels;
  }

  // BMA's count pass: pixels per depth interval (pixels deeper than MAX_FRAGS in the last one).
  std::vector<unsigned> count_intervals() {
    std::vector<unsigned> hist(32, 0);
    glNamedBufferSubData(histogram_.get(), 0, 32 * sizeof(unsigned), hist.data());
    lists_->bind();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BMA_HISTOGRAM_BINDING, histogram_.get());
    glUseProgram(count_.get());
    glDispatchCompute((width_ + 7) / 8, (height_ + 7) / 8, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(histogram_.get(), 0, 32 * sizeof(unsigned), hist.data());
    // Pixels deeper than MAX_FRAGS belong to the last interval (truncated there, and counted).
    std::vector<unsigned> pixels(interval_tops_.size(), 0);
    for (size_t i = 0; i < hist.size(); ++i) pixels[std::min(i, pixels.size() - 1)] += hist[i];
    return pixels;
  }

  // BMA's mask pass: stencil value i + 1 on the pixels of interval i.
  void mask_intervals(const std::vector<unsigned>& pixels) {
    {
      glClearNamedFramebufferiv(target_.framebuffer(), GL_STENCIL, 0, std::array<GLint, 1>{0}.data());
      glEnable(GL_STENCIL_TEST);
      glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
      glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
      glUseProgram(mask_.get());
      lists_->bind();
      for (size_t i = 0; i < interval_tops_.size(); ++i) {
        if (!pixels[i]) continue;
        unsigned lo = i == 0 ? 1 : interval_tops_[i] / 2 + 1;
        unsigned hi = i + 1 == interval_tops_.size() ? 0xFFFFFFFFu : interval_tops_[i];
        glUniform1ui(glGetUniformLocation(mask_.get(), "lo"), lo);
        glUniform1ui(glGetUniformLocation(mask_.get(), "hi"), hi);
        glStencilFunc(GL_ALWAYS, static_cast<GLint>(i + 1), 0xFF);
        quad_.draw();
      }
      glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
      glDisable(GL_STENCIL_TEST);
    }
  }

  Validation validate() override {
    Validation v;
    auto& m = v.metrics;
    m["polygons"] = std::to_string(passes_.mesh().polygons());
    if (!passes_.transparency()) return validate_backdrop_only();
    auto reading = ctx_.phase(Phase::Readback);
    HostLists host = native_ ? std::move(host_) : lists_->read_back();
    const Backdrop backdrop = passes_.read_backdrop();
    std::vector<float> rgba = native_ ? native_out_ : target_.read_rgba32f();
    reading.end();
    ListStats stats = list_stats(host);
    size_t truncated = 0;
    for (unsigned d : stats.depth) truncated += d > max_frags_;
    record_storage_metrics(m, stats, truncated);
    m["tied_pixels"] = std::to_string(stats.tied_pixels);
    std::vector<std::string> problems = list_problems(host, stats, truncated);
    HostLists reference_lists;
    if (passes_.opaque()) reference_lists = opaque_reference(host, stats, backdrop, m, problems);
    const HostLists& ref_host = passes_.opaque() ? reference_lists : host;
    std::vector<double> ref;
    {
      const auto referencing = ctx_.phase(Phase::Reference);
      ref = composite_reference(ref_host, backdrop, early_stop_);
    }
    auto err = compare_with_reference(rgba, ref, stats, backdrop, width_, tolerance_);
    m["max_abs_error"] = fmt(err.max_abs_error);
    m["rmse"] = fmt(err.rmse);
    ImageRange range = image_range(rgba, 4);
    m["nonfinite"] = std::to_string(range.nonfinite);
    m["out_of_range_pixels"] = std::to_string(range.out_of_range_pixels);
    m["bad_pixels"] = std::to_string(err.bad_pixels);
    m["visit_errors"] = std::to_string(err.visit_errors);
    if (!dump_.empty()) write_images(rgba, ref, stats, backdrop);
    if (err.visit_errors)
      problems.push_back(std::to_string(err.visit_errors) +
                         " pixel(s) not resolved exactly once (covered) or resolved "
                         "though uncovered");
    if (err.bad_pixels)
      problems.push_back(std::to_string(err.bad_pixels) + " pixel(s) differ from the CPU reference by more than " +
                         fmt(tolerance_) + "; first: " + err.first_bad);
    // Analytic scenes: the image against the scene's own planes, composited in double in their true
    // order (geometric_reference.hpp), so a capture that loses precision, a fragment or the order is
    // caught even though the reference above, built from the same captured fragments, agrees.
    // (Only where transparency is the one effect: the geometry knows no opaque pass or shading.)
    check_against_planes(rgba, stats, m, problems);
    check_against_splat_list(rgba, m, problems);
    explain_loop_limit(stats, problems);
    merge_shadow_check(m, problems, passes_.validate_shadow());
    conclude(v, problems);
    return v;
  }
  // What the lists must be whatever the image shows: every captured fragment kept, BMA's counts equal
  // to the list lengths, no pixel deeper than MAX_FRAGS (the CPU resolve has no MAX_FRAGS).
  std::vector<std::string> list_problems(const HostLists& host, const ListStats& stats, size_t truncated) {
    std::vector<std::string> problems;
    if (!host.error.empty()) problems.push_back(host.error);
    if (!stats.error.empty()) problems.push_back(stats.error);
    if (stats.total_fragments != lists_->fragments())
      problems.push_back("the lists hold " + std::to_string(stats.total_fragments) + " fragments but " +
                         std::to_string(lists_->fragments()) + " were captured (fragments lost)");
    if (bma_) {
      size_t wrong = 0;
      for (size_t p = 0; p < stats.depth.size(); ++p) wrong += host.counts[p] != stats.depth[p];
      if (wrong) problems.push_back(std::to_string(wrong) + " pixel(s) whose BMA count differs from their list length");
    }
    if (truncated && !native_)
      problems.push_back(std::to_string(truncated) + " pixel(s) deeper than MAX_FRAGS=" + std::to_string(max_frags_) +
                         " were truncated");
    return problems;
  }
  // With the opaque effect the reference does not trust the capture's depth test: every
  // transparent fragment captured again without it, hidden on the CPU by the opaque depth.
  HostLists opaque_reference(const HostLists& host, const ListStats& stats, const Backdrop& backdrop,
                             std::map<std::string, std::string>& m, std::vector<std::string>& problems) {
    if (size_t behind = hidden_fragments(host, backdrop))
      problems.push_back(std::to_string(behind) +
                         " captured fragment(s) lie at or behind the opaque depth (the capture's depth test failed)");
    size_t hidden = 0;
    const auto referencing = ctx_.phase(Phase::Reference);
    HostLists reference_lists = visible_fragments(capture_unoccluded(), backdrop, hidden);
    m["hidden_fragments"] = std::to_string(hidden);
    ListStats ref_stats = list_stats(reference_lists);
    if (ref_stats.total_fragments != stats.total_fragments)
      problems.push_back("the capture kept " + std::to_string(stats.total_fragments) +
                         " fragments, the CPU's depth test of an unoccluded capture keeps " +
                         std::to_string(ref_stats.total_fragments));
    return reference_lists;
  }
  // llvmpipe ends a shader invocation's loops after 65535 iterations in total (gallivm's
  // LP_MAX_TGSI_LOOP_ITERATIONS): deep reverse insertion sorts and wide k-way merges pass it. Where a
  // case failed there, the likely cause joins its problems.
  void explain_loop_limit(const ListStats& stats, std::vector<std::string>& problems) {
    double loop_steps = std::max(0.5 * stats.peak_depth * stats.peak_depth,
                                 static_cast<double>(stats.peak_depth) * max_frags_ / std::max(1, block_));
    if (!problems.empty() && !native_ && ctx_.gl().is_software_renderer() && loop_steps > 65535)
      problems.push_back(
          "likely cause: llvmpipe stops a shader invocation's loops after 65535 iterations in total "
          "(gallivm's LP_MAX_TGSI_LOOP_ITERATIONS), and this resolve may need ~" +
          fmt(loop_steps) + " per pixel");
  }
  // What the capture held: sizes, storage, BMA's intervals and BMA-AUTO's choice.
  void record_storage_metrics(std::map<std::string, std::string>& m, const ListStats& stats, size_t truncated) {
    m["total_fragments"] = std::to_string(stats.total_fragments);
    m["peak_depth"] = std::to_string(stats.peak_depth);
    m["mean_depth"] = fmt(stats.mean_depth);
    m["max_frags_used"] = std::to_string(max_frags_);
    m["node_pool"] = std::to_string(lists_->pool());
    m["node_pool_bytes"] = std::to_string(lists_->bytes());
    m["node_buffers"] = std::to_string(lists_->buffers());
    m["bytes_per_pixel"] = fmt(static_cast<double>(lists_->bytes()) / (static_cast<double>(width_) * height_));
    if (!count_ms_.empty()) m["capture_count_ms"] = fmt(median_of(count_ms_));
    if (auto_) {
      m["bma_auto_choice"] = describe_choice(interval_tops_, auto_choice_);
      m["bma_auto_source"] = auto_choice_.source;
      m["bma_auto_timings"] = auto_choice_.timings;
    }
    m["overflow_rerenders"] = std::to_string(overflow_rerenders_);
    m["truncated_pixels"] = std::to_string(truncated);
    if (!capture_ms_.empty()) m["fragments_per_s"] = fmt(stats.total_fragments / (median_of(capture_ms_) / 1000.0));
    if (bma_) {
      std::string s;
      for (size_t i = 0; i < interval_tops_.size(); ++i)
        if (i < interval_pixels_.size() && interval_pixels_[i])
          s += (s.empty() ? "" : " ") + std::to_string(interval_tops_[i]) + ":" + std::to_string(interval_pixels_[i]);
      m["bma_intervals"] = s;
    }
  }

  // Splat scenes: the image against the analytic reference of the splat list (splat_check.hpp).
  void check_against_splat_list(const std::vector<float>& rgba, std::map<std::string, std::string>& m,
                                std::vector<std::string>& problems) {
    auto referencing = ctx_.phase(Phase::Reference);
    auto check = check_against_splats(passes_, rgba, 4, width_, height_, tolerance_,
                                      format_.colour == FragColour::RGBA8, early_stop_);
    referencing.end();
    report_splat_check(check, tolerance_, m, &problems);
  }
  // Analytic scenes: the image against the scene's own planes (a reference that shares nothing with
  // the captured fragments).
  void check_against_planes(const std::vector<float>& rgba, const ListStats& stats,
                            std::map<std::string, std::string>& m, std::vector<std::string>& problems) {
    auto referencing = ctx_.phase(Phase::Reference);
    // Once per run for a scene, view, size and format (shared_geometric_reference's key).
    auto geo = passes_.effects() == std::vector<std::string>{"transparency"}
                   ? shared_geometric_reference(ctx_.shared(), scene_, view_, detail_, near_far_, width_, height_,
                                                format_.colour)
                   : nullptr;
    referencing.end();
    if (geo) {
      GeometricCheck g = check_against_geometry(*geo, rgba, stats.depth, scene_.background, tolerance_);
      m["truth_rmse"] = fmt(g.truth_rmse);
      m["truth_max_abs_error"] = fmt(g.truth_max_abs_error);
      m["geometric_bad_pixels"] = std::to_string(g.bad_pixels);
      m["ambiguous_pixels"] = std::to_string(geo->ambiguous_pixels);
      if (g.layer_mismatches)
        problems.push_back(std::to_string(g.layer_mismatches) +
                           " pixel(s) hold another number of fragments than the scene's planes put there; first: " +
                           g.first_layer_mismatch);
      if (g.bad_pixels) {
        std::string why = std::to_string(g.bad_pixels) + " pixel(s) differ from the geometric reference by more than " +
                          fmt(tolerance_) + "; first: " + g.first_bad;
        if (stats.tied_pixels && geo->coplanar_pixels < stats.tied_pixels)
          why += " (the captured depths tie in " + std::to_string(stats.tied_pixels) +
                 " pixel(s) where the planes lie apart: frag_depth=" +
                 std::string(format_.depth == FragDepth::View ? "view" : "window") +
                 " cannot separate them, so equal depths went in colour order)";
        problems.push_back(why);
      }
    }
  }

 private:
  // `oitbench render --out PATH.png`: PATH.png and PATH.pfm (the resolve, 8-bit and float), PATH-diff8.png (|image -
  // reference| x 8), PATH-depth.png (depth complexity in false colour, black = empty, log scale up to the peak) and
  // PATH-depth-histogram.csv (pixels per depth complexity).
  void write_images(const std::vector<float>& rgba, const std::vector<double>& ref, const ListStats& stats,
                    const Backdrop& backdrop) const {
    const size_t pixels = stats.depth.size();
    std::vector<float> rgb(pixels * 3), depth(pixels * 3);
    std::vector<size_t> histogram(stats.peak_depth + 1, 0);
    const double peak = std::log2(1.0 + std::max(1u, stats.peak_depth));
    for (size_t p = 0; p < pixels; ++p) {
      for (int k = 0; k < 3; ++k) rgb[p * 3 + k] = rgba[p * 4 + 3] == 0.0f ? backdrop.at(p)[k] : rgba[p * 4 + k];
      ++histogram[stats.depth[p]];
      // blue (1 fragment) -> green -> red (peak), on a log scale; black where nothing landed
      float t = stats.depth[p] ? static_cast<float>(std::log2(1.0 + stats.depth[p]) / peak) : 0.0f;
      glm::vec3 c = stats.depth[p] == 0 ? glm::vec3(0)
                    : t < 0.5f          ? glm::mix(glm::vec3(0, 0, 1), glm::vec3(0, 1, 0), t * 2)
                                        : glm::mix(glm::vec3(0, 1, 0), glm::vec3(1, 0, 0), t * 2 - 1);
      for (int k = 0; k < 3; ++k) depth[p * 3 + k] = c[k];
    }
    write_result_images(dump_, rgb, ref, width_, height_);
    write_png(dump_ + "-depth.png", depth, width_, height_);
    std::ofstream csv(dump_ + "-depth-histogram.csv");
    csv << "depth_complexity,pixels\n";
    for (size_t d = 0; d < histogram.size(); ++d)
      if (histogram[d]) csv << d << "," << histogram[d] << "\n";
  }

  // The technique's capture: with the opaque effect, against the opaque depth (early fragment
  // tests in capture.frag: a hidden fragment is never stored).
  // What sizing the pool found: the fragments captured, the peak depth and the depths that occur.
  struct PoolSizing {
    size_t fragments = 0;
    unsigned peak_depth = 0;
    std::vector<unsigned> depths;  // the distinct non-zero pixel depths, ascending
  };

  // Makes the fragment storage and sizes its pool before anything else is compiled: a count pass of the
  // geometry (FragmentCounter: each pixel's fragments, stored nowhere) and a read-back of 4 bytes a pixel
  // give the exact pool, the peak depth that sets MAX_FRAGS and the depths BMA's intervals need, so the
  // first capture never overflows (no re-render, no read-back of the fragments). The run's cases that
  // capture the same fragments (the same size, the same parameters but the resolve's and the storage's:
  // pool_key) share the counts: only the first pays the count pass. BMA-AUTO, whose calibration resolves
  // the captured lists, captures once here into the pool the counts sized. A pool set by initial_pool is
  // sized by a capture, as a frame would be: its overflow re-renders are what such a case measures.
  // Validation reads each case's own capture back, as before.
  std::shared_ptr<const PoolSizing> size_pool(const ParamSet& p, const CaseContext& ctx) {
    const auto sizing_phase = ctx.phase(Phase::Pool);
    const long long init = p.get_int("initial_pool");
    const CaptureStorage kind = parse_capture_storage(p.get("capture"));
    // The opaque effect's validation holds three read-backs at once: the capture, the unoccluded
    // capture and its visible fragments.
    const int host_copies = passes_.opaque() ? 3 : 1;
    auto make_storage = [&](size_t pool, const FragmentBudget& budget) {
      lists_ = make_fragment_storage(kind, ctx, pool, bma_, format_, budget);
      build_capture();
    };
    if (init > 0) {
      make_storage(static_cast<size_t>(init), capture_budget(passes_.mesh(), view_proj_, ctx, host_copies));
      passes_.draw_opaque();
      overflow_rerenders_ += capture();
      const ListDepths d = list_depths(lists_->read_back());
      FragmentCounts c;
      c.depth = d.depth;
      c.peak_depth = d.peak_depth;
      return std::make_shared<const PoolSizing>(PoolSizing{lists_->fragments(), d.peak_depth, c.depths()});
    }
    auto count = [&] {
      // The scene's estimate first: nothing is drawn for a case that cannot be held.
      require_fragment_budget(kind, ctx, bma_, format_, capture_budget(passes_.mesh(), view_proj_, ctx, host_copies));
      const FragmentCounts c = count_fragments(ctx);
      if (c.total_fragments >= kListEnd)
        throw Unsupported(format_count(c.total_fragments) + " fragments (counted): the capture indexes fragments " +
                          "with 32 bits (at most " + format_count(kListEnd - 1) + ")");
      return std::make_shared<const PoolSizing>(PoolSizing{c.total_fragments, c.peak_depth, c.depths()});
    };
    const std::shared_ptr<const PoolSizing> s =
        ctx.shared() ? ctx.shared()->get<PoolSizing>(pool_key(p, ctx), count, kSharedPoolSizings) : count();
    // The counts are exact: the pool is checked against the memory as it is (make_fragment_storage's
    // guard), with the 1/32 a steady capture keeps to spare.
    make_storage(s->fragments + s->fragments / 32 + 1,
                 FragmentBudget{0, host_copies, scene_held_memory(passes_.mesh())});
    if (auto_) {
      passes_.draw_opaque();
      overflow_rerenders_ += capture();
    }
    return s;
  }

  // The count pass: the capture's shaders as PPPA's count program, under the capture's state (the
  // opaque pass drawn first for its depth test, no culling, no colour).
  FragmentCounts count_fragments(const CaseContext& ctx) {
    FragmentCounter counter(ctx, capture_stages(), format_, passes_.geometry_defines());
    glProgramUniformMatrix4fv(counter.program(), glGetUniformLocation(counter.program(), "viewProj"), 1, GL_FALSE,
                              &view_proj_[0][0]);
    passes_.draw_opaque();
    target_.bind();
    passes_.begin_geometry();
    glDisable(GL_CULL_FACE);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    passes_.bind_geometry(counter.program());
    FragmentCounts c = counter.count([&] { passes_.transparent().draw(); });
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    passes_.end_geometry();
    return c;
  }

  static std::vector<ShaderStage> capture_stages() {
    return {{GL_VERTEX_SHADER, "scene/scene.vert"}, {GL_FRAGMENT_SHADER, "capture/capture.frag"}};
  }

  // Everything the captured fragments depend on: the size and every parameter but those only the resolve
  // or the storage reads (a parameter added later is in the key until listed here). The counts do not
  // depend on the layout (capture) nor on whether it keeps counts (BMA): both store every fragment that
  // reaches store_fragment(), which is what the count pass counts.
  std::string pool_key(const ParamSet& p, const CaseContext& ctx) const {
    constexpr std::array<std::string_view, 9> kNotCounted = {"technique",      "block",      "block_sort",
                                                             "cs_group",       "max_frags",  "order_check",
                                                             "bma_auto_cache", "early_stop", "capture"};
    std::string key = std::to_string(ctx.width()) + "x" + std::to_string(ctx.height());
    for (const auto& [k, v] : p.values())
      if (std::find(kNotCounted.begin(), kNotCounted.end(), k) == kNotCounted.end()) key += " " + k + "=" + v;
    return key;
  }

  void build_capture() {
    capture_ = build_capture_programs(*lists_, ctx_, capture_stages(), passes_.geometry_defines());
    set_view_projection(view_proj_);
  }

  int capture(bool depth_test = true) {
    target_.bind();
    if (depth_test)
      passes_.begin_geometry();
    else
      glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    for (const auto& prog : capture_) passes_.bind_geometry(prog.get());
    // Where the pool grows into more chunks than the programs were built for, they are rebuilt for the
    // new layout and the frame captured again (the first capture, in prepare, before any resolve is built).
    int r = capture_complete(
        *lists_, capture_,
        [&] {
          build_capture();
          for (const auto& prog : capture_) passes_.bind_geometry(prog.get());
          return std::move(capture_);
        },
        [&] { passes_.transparent().draw(); });
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    passes_.end_geometry();
    return r;
  }
  // Validation only: every transparent fragment, the opaque depth test off.
  HostLists capture_unoccluded() {
    capture(false);
    return lists_->read_back();
  }
  // No transparency effect: no capture and no resolve ran; the image must be the backdrop.
  Validation validate_backdrop_only() {
    Validation v;
    v.metrics["polygons"] = std::to_string(passes_.mesh().polygons());
    v.metrics["total_fragments"] = "0";
    std::vector<float> rgba = target_.read_rgba32f();
    const Backdrop b = passes_.read_backdrop();
    size_t off = 0;
    for (size_t p = 0; p < rgba.size() / 4; ++p)
      for (int k = 0; k < 3; ++k) off += std::abs(rgba[p * 4 + k] - b.at(p)[k]) > tolerance_;
    v.valid = off == 0;
    if (off) v.reason = std::to_string(off) + " channel value(s) differ from the opaque pass's image";
    return v;
  }

  size_t interval_of(unsigned depth) const {
    size_t i = 0;
    while (i + 1 < interval_tops_.size() && depth > interval_tops_[i]) ++i;
    return i;
  }

  // The sort's defines plus the storage layout's.
  // The technique's sort with its parameters (block_sort, order_check).
  SortChoice technique_choice() const { return {technique_.resolve_sort.value(), block_sort_, order_check_}; }

  // The sort's defines plus the storage layout's. A network block sort compares the fragment as one
  // 64-bit key where it packs into one (rgba8) and the driver has int64.
  Defines resolve_defines(const SortChoice& sort, unsigned max_frags) const {
    bool packed = format_.colour == FragColour::RGBA8 && ctx_.gl().has_extension("GL_ARB_gpu_shader_int64");
    Defines d = sort_defines(sort, max_frags, static_cast<unsigned>(block_), packed);
    for (auto& x : early_stop_defines(early_stop_, ctx_.fault())) d.push_back(x);
    for (auto& x : lists_->defines()) d.push_back(x);
    for (auto& x : passes_.defines()) d.push_back(x);
    return d;
  }

  gl::Program build_resolve(const SortChoice& sort, unsigned max_frags) {
    Defines d = resolve_defines(sort, max_frags);
    auto prog =
        ctx_.build({{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "resolve/resolve.frag"}}, d);
    glProgramUniform1i(prog.get(), glGetUniformLocation(prog.get(), "zero"), 0);
    return prog;
  }

  const gl::Program& interval_program(size_t i) {
    if (!interval_programs_[i]) {
      interval_programs_[i] = build_resolve(interval_sort(i), interval_tops_[i]);
      note_sort(interval_sort(i), interval_tops_[i]);
    }
    return *interval_programs_[i];
  }

  // Records the library files a resolve program built with these settings runs (sort_source),
  // hashed as read now, each once, in the order first used.
  void note_sort(const SortChoice& sort, unsigned max_frags) {
    for (const auto& file : sort_files(sort.sort, max_frags, sort.block)) {
      std::string id = ctx_.shaders().source_id(file);
      if (std::find(sort_sources_.begin(), sort_sources_.end(), id) == sort_sources_.end()) sort_sources_.push_back(id);
    }
  }

  SortChoice interval_sort(size_t i) const {
    if (auto_) return i < auto_choice_.sort.size() && auto_choice_.sort[i] ? *auto_choice_.sort[i] : SortChoice{};
    return technique_choice();
  }

  // BMA-AUTO (oit/bma_auto.hpp): each used interval's sort, from the cache or timed here on the
  // lists of the first capture under that interval's stencil mask. Runs inside prepare, so it is
  // counted in compile_ms and never in a timed pass.
  void calibrate_bma_auto() {
    target_.bind();
    std::vector<unsigned> pixels = count_intervals();
    HostLists host = lists_->read_back();
    ListStats stats = list_stats(host);
    std::vector<double> ref;  // computed on the first calibrated candidate only
    SortChoiceCache cache(bma_auto_cache_path());
    // The median of kReps draws after a warm-up, on the run's primary clock: the CPU clock around
    // glFinish on software renderers, GL_TIME_ELAPSED on hardware drivers, where a draw of a few
    // hundred microseconds would otherwise be decided by launch overhead.
    constexpr int kReps = 5;
    gl::Query query = gl::make_query(GL_TIME_ELAPSED);
    auto measure = [&](size_t i, const SortChoice& sort) {
      gl::Program prog = build_resolve(sort, interval_tops_[i]);
      mask_intervals(pixels);
      std::vector<double> ms;
      for (int r = 0; r <= kReps; ++r) {  // r == 0: the warm-up that pays the JIT
        glFinish();
        auto start = std::chrono::steady_clock::now();
        if (ctx_.gpu_clock()) glBeginQuery(GL_TIME_ELAPSED, query.get());
        begin_resolve();
        glEnable(GL_STENCIL_TEST);
        glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
        glStencilFunc(GL_EQUAL, static_cast<GLint>(i + 1), 0xFF);
        draw_resolve(prog);
        glDisable(GL_STENCIL_TEST);
        end_resolve();
        if (ctx_.gpu_clock()) glEndQuery(GL_TIME_ELAPSED);
        glFinish();
        double cpu_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        GLuint64 ns = 0;
        if (ctx_.gpu_clock()) glGetQueryObjectui64v(query.get(), GL_QUERY_RESULT, &ns);
        if (r) ms.push_back(ctx_.gpu_clock() ? static_cast<double>(ns) * 1e-6 : cpu_ms);
      }
      std::sort(ms.begin(), ms.end());
      if (ref.empty()) ref = composite_reference(host, passes_.read_backdrop());
      unsigned lo = i == 0 ? 1 : interval_tops_[i] / 2 + 1;
      unsigned hi = i + 1 == interval_tops_.size() ? max_frags_ : interval_tops_[i];
      bool valid = interval_matches_reference(target_.read_rgba32f(), ref, stats, lo, hi, tolerance_);
      return CandidateResult{ms[ms.size() / 2], valid};
    };
    auto_choice_ = choose_interval_sorts(interval_tops_, pixels, interval_orders(host, stats, interval_tops_),
                                         ctx_.gl(), static_cast<unsigned>(block_), cache, use_auto_cache_, measure);
  }

  void begin_resolve() {
    const float clear[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(target_.framebuffer(), GL_COLOR, 0, clear);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);  // alpha accumulates the number of resolves of each pixel
    lists_->bind();
  }
  void draw_resolve(const gl::Program& prog) {
    passes_.bind_backdrop(prog.get());
    glUseProgram(prog.get());
    quad_.draw();
  }
  void end_resolve() { glDisable(GL_BLEND); }

  std::string dump_;  // write the image, the x8 diff and the depth complexity (PNG, histogram CSV) here
  CaseContext ctx_;   // a copy: the runner's shader library outlives the case (intervals compile on demand)
  int width_, height_;
  bool wrong_result_;
  const Technique& technique_;
  bool bma_, native_, compute_, auto_, use_auto_cache_;
  int block_;
  BlockSort block_sort_;
  bool order_check_;
  double early_stop_;  // 3DGS's early termination threshold (0: off); the resolve's EARLY_STOP
  FragFormat format_;
  double tolerance_;
  ScenePasses passes_;
  const SceneDesc& scene_;
  View view_;
  Detail detail_ = Detail::Full;
  glm::vec2 near_far_{0.0f};
  RenderTarget target_;
  FullscreenTriangle quad_;
  glm::mat4 view_proj_;
  std::unique_ptr<FragmentStorage> lists_;
  std::vector<gl::Program> capture_;  // one program per capture pass of the storage
  gl::Program base_, count_, mask_;
  gl::Buffer histogram_;
  std::vector<unsigned> interval_tops_, interval_pixels_;
  std::vector<std::optional<gl::Program>> interval_programs_;
  std::unique_ptr<ComputeResolve> compute_resolve_;
  BmaAutoChoice auto_choice_;
  unsigned max_frags_ = 0;
  int overflow_rerenders_ = 0, intervals_run_ = 0;
  std::vector<double> capture_ms_, count_ms_;  // PPPA: count_ms_ is the count pass + prefix sum
  std::vector<std::string> sort_sources_;      // ShaderLibrary::source_id of each library sort file run
  HostLists host_;
  Backdrop native_backdrop_;
  std::vector<float> native_out_;
};

}  // namespace

std::unique_ptr<OitCase> make_exact_case(const ParamSet& p, CaseContext& ctx) {
  return std::make_unique<ExactCase>(p, ctx);
}

}  // namespace oitbench::oit
