// The oit experiment's case for the approximate techniques (approx.hpp): captures the view's
// fragments once for the exact reference and the CPU model, then times the technique's own passes.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <sstream>
#include <stdexcept>

#include "gl/render_target.hpp"
#include "oit/approx.hpp"
#include "oit/approx_model.hpp"
#include "oit/gpu_mesh.hpp"
#include "oit/image_compare.hpp"
#include "oit/image_io.hpp"
#include "oit/moments.hpp"
#include "oit/reference.hpp"
#include "oit/scene.hpp"
#include "oit/storage_layout.hpp"
#include "shaders/approx/bindings.h"

namespace oitbench::oit {

namespace {

// The GPU and its model differ by float rounding (fused multiply-adds, exp/log/pow), and MLAB's
// RGBA8 nodes can round the other way at a half step and carry that through later merges.
constexpr double kModelTolerance = 3.0 / 255.0;
constexpr int kSpinCap = 1 << 16;

const std::vector<std::string> kNames = {"MLAB", "UMLAB", "AT", "HAT", "UAT", "UHAT", "LAAT", "WBOIT", "unsorted"};

std::string fmt(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}
}  // namespace

const std::vector<std::string>& approx_technique_names() { return kNames; }
bool is_approx_technique(const std::string& name) {
  const auto& moments = moment_technique_names();
  return std::find(kNames.begin(), kNames.end(), name) != kNames.end() ||
         std::find(moments.begin(), moments.end(), name) != moments.end();
}
ApproxTechnique parse_approx_technique(const std::string& name) {
  auto it = std::find(kNames.begin(), kNames.end(), name);
  if (it == kNames.end()) throw std::invalid_argument("unknown approximate technique '" + name + "'");
  return static_cast<ApproxTechnique>(it - kNames.begin());
}
std::vector<ParamSpec> approx_params() {
  using K = ParamSpec::Kind;
  const std::vector<std::string> arrays = {"MLAB", "UMLAB", "AT", "HAT", "UAT", "UHAT", "LAAT"};
  const std::vector<std::string> guarded = {"AT", "HAT", "UAT", "UHAT", "LAAT", "WBOIT"};
  std::vector<ParamSpec> ps = {
      {"nodes",
       "nodes per pixel of MLAB, UMLAB, AT, HAT, UAT, UHAT, LAAT (the thesis: 4-16)",
       {"8"},
       {},
       {},
       K::Integer,
       2,
       64},
      {"storage",
       "node storage of the per-pixel array techniques (shaders/storage/)",
       {"ssbo"},
       {},
       {"ssbo", "texture3d", "interleaved"}},
      {"wboit_weight",
       "WBOIT depth weight: none (weighted average), eq7 (view distance), eq10 (window depth)",
       {"eq7"},
       {},
       {"none", "eq7", "eq10"}},
      {"sync",
       "per-pixel insertion: spinlock (Listing 4.3, capped) or interlock (ARB_fragment_shader_interlock)",
       {"spinlock"},
       {},
       {"spinlock", "interlock"}},
      {"guard",
       "numeric guards of the AT family and WBOIT (off: the deliberately unguarded variant the hard-case "
       "tests use)",
       {"on"},
       {},
       {"on", "off"}},
      {"flicker_runs",
       "frames kept for the flicker metric (per-pixel variance across runs; 0: off)",
       {"4"},
       {},
       {},
       K::Integer,
       0,
       64},
  };
  ps[0].only_when("technique", arrays);
  ps[1].only_when("technique", arrays);
  ps[2].only_when("technique", {"WBOIT"});
  ps[3].only_when("technique", arrays);
  ps[4].only_when("technique", guarded);
  std::vector<std::string> all = approx_technique_names();
  for (const auto& t : moment_technique_names()) all.push_back(t);
  ps[5].only_when("technique", all);
  return ps;
}
namespace {

class ApproxCase final : public OitCase {
 public:
  ApproxCase(const ParamSet& p, CaseContext& ctx)
      : width_(ctx.width()),
        height_(ctx.height()),
        scene_(load_scene(p.get("scene"))),
        out_(ctx.width(), ctx.height(), GL_RGBA32F),
        accum_(ctx.width(), ctx.height(), GL_RGBA32F),
        flicker_runs_(static_cast<int>(p.get_int("flicker_runs"))),
        dump_(ctx.image_stem()) {
    settings_.technique = parse_approx_technique(p.get("technique"));
    settings_.nodes = static_cast<int>(p.get_int("nodes"));
    settings_.weight = p.get("wboit_weight");
    settings_.unguarded = p.get("guard") == "off";
    using T = ApproxTechnique;
    const T tech = settings_.technique;
    arrays_ = tech != T::Wboit && tech != T::Unsorted;
    at_family_ = arrays_ && tech != T::Mlab && tech != T::Umlab;
    bool interlock = p.get("sync") == "interlock";
    if (arrays_ && interlock && !ctx.gl().has_extension("GL_ARB_fragment_shader_interlock"))
      throw Unsupported("sync=interlock needs GL_ARB_fragment_shader_interlock");

    const View& view = scene_.view(p.get("view"));
    Mesh mesh = build_mesh(scene_, view, p.get("detail") == "small" ? Detail::Small : Detail::Full);
    mesh_ = std::make_unique<GpuMesh>(mesh);
    glm::mat4 vp = view_projection(view, mesh, static_cast<float>(width_) / height_);
    // The planes back out of the perspective matrix (glm::perspective's layout).
    glm::mat4 pm = vp * glm::inverse(glm::lookAt(view.eye, view.target, view.up));
    settings_.near_far = {pm[3][2] / (pm[2][2] - 1.0f), pm[3][2] / (pm[2][2] + 1.0f)};

    // The fragments, once: the exact reference and every model work on these.
    size_t pixels = static_cast<size_t>(width_) * height_;
    lists_ = make_fragment_storage(parse_capture_storage(p.get("capture")), ctx, pixels * 4, false);
    auto capture = build_capture_programs(
        *lists_, ctx, {{GL_VERTEX_SHADER, "oit/capture.vert"}, {GL_FRAGMENT_SHADER, "oit/capture.frag"}});
    for (const auto& prog : capture) set_view_proj(prog, vp);
    out_.bind();
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    lists_->capture(ids(capture), [&] { mesh_->draw(); });
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    host_ = lists_->read_back();
    lists_.reset();  // its pool is not needed for timing

    Defines d = {{"TECH_" + upper(p.get("technique")), ""}, {"SPIN_CAP", std::to_string(kSpinCap)}};
    if (settings_.unguarded) d.push_back({"APPROX_UNGUARDED", ""});
    if (interlock) d.push_back({"SYNC_INTERLOCK", ""});
    if (arrays_) {
      std::string storage = p.get("storage");
      layout_ = StorageLayout::parse(storage == "interleaved" ? "interleaved-4x4-a4" : storage);
      // LAAT keeps its list head in one more slot per pixel.
      int slots = settings_.nodes + (tech == T::Laat ? 1 : 0);
      if (layout_.kind == StorageLayout::Kind::Interleaved && slots % layout_.align) layout_.align = 1;
      for (const auto& x : layout_.defines(width_, height_, slots)) d.push_back(x);
      storage_ = std::make_unique<StorageResources>(layout_, width_, height_, slots);
      locks_ = gl::make_texture(GL_TEXTURE_2D);
      glTextureStorage2D(locks_.get(), 1, GL_R32UI, width_, height_);
      stats_ = gl::make_buffer();
      glNamedBufferStorage(stats_.get(), sizeof(unsigned), nullptr, GL_DYNAMIC_STORAGE_BIT);
      insert_ = ctx.build({{GL_VERTEX_SHADER, "oit/capture.vert"}, {GL_FRAGMENT_SHADER, "approx/insert.frag"}}, d);
      set_view_proj(insert_, vp);
      if (at_family_) {
        blend_ = ctx.build({{GL_VERTEX_SHADER, "oit/capture.vert"}, {GL_FRAGMENT_SHADER, "approx/at_blend.frag"}}, d);
        set_view_proj(blend_, vp);
      }
      resolve_ =
          ctx.build({{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "approx/resolve.frag"}}, d);
    } else if (tech == T::Wboit) {
      d.push_back({"WEIGHT_" + upper(settings_.weight), ""});
      blend_ = ctx.build({{GL_VERTEX_SHADER, "oit/capture.vert"}, {GL_FRAGMENT_SHADER, "approx/wboit_accum.frag"}}, d);
      set_view_proj(blend_, vp);
      glProgramUniform2f(blend_.get(), glGetUniformLocation(blend_.get(), "nearFar"), settings_.near_far.x,
                         settings_.near_far.y);
      reveal_ = gl::make_texture(GL_TEXTURE_2D);
      glTextureStorage2D(reveal_.get(), 1, GL_R32F, width_, height_);
      glNamedFramebufferTexture(accum_.framebuffer(), GL_COLOR_ATTACHMENT1, reveal_.get(), 0);
      resolve_ = ctx.build(
          {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "approx/wboit_resolve.frag"}}, d);
    } else {
      blend_ = ctx.build({{GL_VERTEX_SHADER, "oit/capture.vert"}, {GL_FRAGMENT_SHADER, "approx/unsorted.frag"}}, d);
      set_view_proj(blend_, vp);
    }
    if (resolve_) {
      glProgramUniform3f(resolve_.get(), glGetUniformLocation(resolve_.get(), "background"), scene_.background.r,
                         scene_.background.g, scene_.background.b);
    }
  }

  void set_view_projection(const glm::mat4& view_proj) override {
    for (const gl::Program* prog : {&insert_, &blend_})
      if (*prog) set_view_proj(*prog, view_proj);
  }
  GLuint result_texture() override { return out_.color_texture(); }
  unsigned max_frags() const override { return arrays_ ? static_cast<unsigned>(settings_.nodes) : 0; }

  void run(PassTimer& timer) override {
    using T = ApproxTechnique;
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    if (arrays_) {
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
        glUseProgram(insert_.get());
        mesh_->draw();
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        StorageResources::barrier();
      }
      if (at_family_) {
        auto t = timer.pass("blend");
        accum_.bind();
        const float zero[4] = {0, 0, 0, 0};
        glClearNamedFramebufferfv(accum_.framebuffer(), GL_COLOR, 0, zero);
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ONE);
        glUseProgram(blend_.get());
        mesh_->draw();
        glDisable(GL_BLEND);
      }
      auto t = timer.pass("resolve");
      out_.bind();
      glBindTextureUnit(APPROX_ACCUM_UNIT, accum_.color_texture());
      glUseProgram(resolve_.get());
      quad_.draw();
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
        glUseProgram(blend_.get());
        mesh_->draw();
        glDisable(GL_BLEND);
      }
      auto t = timer.pass("resolve");
      out_.bind();
      glBindTextureUnit(APPROX_ACCUM_UNIT, accum_.color_texture());
      glBindTextureUnit(APPROX_REVEAL_UNIT, reveal_.get());
      glUseProgram(resolve_.get());
      quad_.draw();
    } else {
      auto t = timer.pass("blend");
      out_.bind();
      const float bg[4] = {scene_.background.r, scene_.background.g, scene_.background.b, 1.0f};
      glClearNamedFramebufferfv(out_.framebuffer(), GL_COLOR, 0, bg);
      glEnable(GL_BLEND);
      glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
      glUseProgram(blend_.get());
      mesh_->draw();
      glDisable(GL_BLEND);
    }
    // Outside the timed passes: the frames the flicker metric compares.
    if (flicker_runs_ > 0) {
      frames_.push_back(rgb_of(out_.read_rgba32f()));
      if (static_cast<int>(frames_.size()) > flicker_runs_) frames_.erase(frames_.begin());
    }
  }

  Validation validate() override {
    Validation v;
    auto& m = v.metrics;
    std::vector<float> rgb = rgb_of(out_.read_rgba32f());
    ListStats stats = list_stats(host_);
    auto ref = composite_reference(host_, scene_.background);
    ApproxModel model = approx_model(host_, scene_.background, settings_);
    ApproxError err = approx_error(rgb, ref);
    m["total_fragments"] = std::to_string(stats.total_fragments);
    m["peak_depth"] = std::to_string(stats.peak_depth);
    m["mean_depth"] = fmt(stats.mean_depth);
    m["polygons"] = std::to_string(mesh_->polygons());
    m["rmse"] = fmt(err.rmse);
    m["psnr"] = fmt(err.psnr);
    m["max_abs_error"] = fmt(err.max_abs_error);
    m["frac_pixels_off"] = fmt(err.frac_pixels_off);
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
    m["model_max_diff"] = fmt(model_max);
    unsigned capped = 0;
    if (arrays_) {
      glGetNamedBufferSubData(stats_.get(), 0, sizeof(unsigned), &capped);
      m["capped_updates"] = std::to_string(capped);
    }
    if (frames_.size() >= 2) {
      // Per-pixel variance across the frames (mean over channels), averaged and at its peak.
      double sum = 0, peak = 0;
      size_t changed = 0;
      size_t k = frames_.size();
      for (size_t i = 0; i < rgb.size(); i += 3) {
        double var_px = 0;
        for (int c = 0; c < 3; ++c) {
          double mean = 0, sq = 0;
          for (const auto& f : frames_) mean += f[i + c];
          mean /= k;
          for (const auto& f : frames_) sq += (f[i + c] - mean) * (f[i + c] - mean);
          var_px += sq / k / 3.0;
        }
        sum += var_px;
        peak = std::max(peak, var_px);
        changed += var_px > 0;
      }
      m["flicker"] = fmt(sum / (rgb.size() / 3));
      m["flicker_max"] = fmt(peak);
      m["flicker_pixels"] = std::to_string(changed);
    }
    if (!dump_.empty()) write_result_images(dump_, rgb, std::vector<double>(ref.begin(), ref.end()), width_, height_);

    std::vector<std::string> problems;
    if (!stats.error.empty()) problems.push_back(stats.error);
    if (nonfinite) problems.push_back(std::to_string(nonfinite) + " non-finite channel value(s) (NaN or Inf)");
    if (out_of_range) problems.push_back(std::to_string(out_of_range) + " channel value(s) outside [0, 1]");
    if (capped) problems.push_back(std::to_string(capped) + " insertion(s) gave up on the spinlock (lost)");
    if (model_off)
      problems.push_back(std::to_string(model_off) +
                         " channel value(s) differ from the technique's CPU model by more "
                         "than 3/255; first: " +
                         first_off);
    v.valid = problems.empty();
    for (const auto& s : problems) v.reason += (v.reason.empty() ? "" : "; ") + s;
    return v;
  }

 private:
  static std::string upper(std::string s) {
    for (auto& ch : s) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
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
  SceneDesc scene_;
  RenderTarget out_, accum_;
  FullscreenTriangle quad_;
  std::unique_ptr<GpuMesh> mesh_;
  std::unique_ptr<FragmentStorage> lists_;
  HostLists host_;
  ApproxSettings settings_;
  bool arrays_ = false, at_family_ = false;
  StorageLayout layout_;
  std::unique_ptr<StorageResources> storage_;
  gl::Texture locks_, reveal_;
  gl::Buffer stats_;
  gl::Program insert_, blend_, resolve_;
  int flicker_runs_;
  std::string dump_;
  std::vector<std::vector<float>> frames_;
};

}  // namespace

std::unique_ptr<OitCase> make_approx_case(const ParamSet& p, CaseContext& ctx) {
  if (p.get("technique") == "MBOIT") return make_mboit_case(p, ctx);
  if (p.get("technique") == "STOCHASTIC") return make_stochastic_case(p, ctx);
  return std::make_unique<ApproxCase>(p, ctx);
}

}  // namespace oitbench::oit
