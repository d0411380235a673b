#include "oit/splats/popping.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>

#include "core/shared_cache.hpp"
#include "core/timer.hpp"
#include "oit/case_support.hpp"
#include "oit/scene/scene_passes.hpp"
#include "oit/splats/gpu_splats.hpp"
#include "oit/splats/splat_reference.hpp"
#include "oit/techniques.hpp"

namespace oitbench::oit {

View path_view(const View& view, const CameraPath& path, int k) {
  const double angle = glm::radians((k - path.steps / 2.0) * path.step_deg);
  const glm::dvec3 axis = glm::normalize(glm::dvec3(view.up));
  const glm::dvec3 arm = glm::dvec3(view.eye) - glm::dvec3(view.target);
  // Rodrigues' rotation of the eye's arm about the up axis
  const glm::dvec3 turned = arm * std::cos(angle) + glm::cross(axis, arm) * std::sin(angle) +
                            axis * glm::dot(axis, arm) * (1.0 - std::cos(angle));
  View v = view;
  v.eye = glm::vec3(glm::dvec3(view.target) + turned);
  return v;
}

void PoppingMeter::add(std::vector<float> image, std::vector<float> reference, const std::vector<char>& skip) {
  const size_t n = static_cast<size_t>(width_) * height_;
  if (image.size() != n * 3 || reference.size() != n * 3)
    throw std::invalid_argument("popping: a frame of " + std::to_string(image.size()) + " values and a reference of " +
                                std::to_string(reference.size()) + " for " + std::to_string(n) + " RGB pixels");
  if (frame_++ > 0)
    for (size_t p = 0; p < n; ++p) {
      double pop = 0;
      for (size_t c = p * 3; c < p * 3 + 3; ++c) {
        const double change = std::abs(double(image[c]) - image_[c]);
        const double truth = std::abs(double(reference[c]) - reference_[c]);
        // a NaN in the image is the largest change there is
        pop = std::max(pop, std::isfinite(change) ? std::max(0.0, change - truth) : 1.0);
      }
      sum_ += pop;
      const bool counted = skip.empty() || !skip[p];
      if (pop > kPoppingTolerance) popped_[p] |= counted ? 1 : 2;
      p_.peak = std::max(p_.peak, pop);
      if (counted && pop > largest_counted_) {
        largest_counted_ = pop;
        const int x = static_cast<int>(p % width_), y = static_cast<int>(p / width_);
        p_.first = "pixel (" + std::to_string(x) + "," + std::to_string(y) + ") frames " + std::to_string(frame_ - 2) +
                   "-" + std::to_string(frame_ - 1) + ": " + fmt(image_[p * 3]) + " " + fmt(image_[p * 3 + 1]) + " " +
                   fmt(image_[p * 3 + 2]) + " to " + fmt(image[p * 3]) + " " + fmt(image[p * 3 + 1]) + " " +
                   fmt(image[p * 3 + 2]) + ", analytic " + fmt(reference_[p * 3]) + " " + fmt(reference_[p * 3 + 1]) +
                   " " + fmt(reference_[p * 3 + 2]) + " to " + fmt(reference[p * 3]) + " " + fmt(reference[p * 3 + 1]) +
                   " " + fmt(reference[p * 3 + 2]);
      }
    }
  image_ = std::move(image);
  reference_ = std::move(reference);
}

Popping PoppingMeter::result() const {
  Popping r = p_;
  const double samples = static_cast<double>(width_) * height_ * std::max(0, frame_ - 1);
  r.mean = samples > 0 ? sum_ / samples : 0.0;
  for (const char f : popped_) {
    r.pixels += (f & 1) != 0;
    r.left_out += f == 2;
  }
  return r;
}

std::vector<ParamSpec> popping_params() {
  ParamSpec steps = ParamSpec::integer(
      "popping_steps",
      "splat scenes: steps of the popping metric's camera path (popping_steps + 1 frames orbiting the view's target "
      "about its up axis, centred on the view), run after validation, outside the timed passes; 0: no path",
      0, 64, {"8"});
  ParamSpec step_deg{"popping_step_deg",
                     "splat scenes: the popping path's angle between neighbouring frames, degrees",
                     {"1"},
                     {},
                     {},
                     ParamSpec::Kind::Number,
                     0.001,
                     10.0};
  // read only where the case's scene holds splats, like splat_depth
  const ParamSpec scope = splat_depth_param();
  for (ParamSpec* s : {&steps, &step_deg}) {
    s->applies_if = scope.applies_if;
    s->applies_if_text = scope.applies_if_text;
    s->applies_if_reads = scope.applies_if_reads;
  }
  return {steps, step_deg};
}

namespace {

// One path frame's analytic image (RGB floats) and fragment counts, shared by every case of the run
// that draws the same scene, view, size and quantisation (CaseContext::shared()).
struct PathReference {
  std::vector<float> rgb;
  std::vector<std::uint32_t> fragments;
  std::vector<std::uint8_t> tied;  // splat_reference.hpp: the order a float key may not decide
};

struct PathSetup {
  SceneDesc scene;
  View view;
  std::string detail;
  std::shared_ptr<const Mesh> mesh;
  CameraPath path;
  int width = 0, height = 0;
  SharedCache* shared = nullptr;
  bool quantise = false;         // the case's fragments are RGBA8: the reference rounds them the same way
  double early_stop = 0;         // the case's early_stop: the reference stops where it does (3DGS's rule)
  bool must_not_pop = false;     // an exact per-pixel technique sorting by the ray maximum
  bool fault_pop = false;        // fault=path-pop
  bool empty_is_alpha0 = false;  // the exact resolves leave an uncovered pixel at alpha 0 (the others composite)
};

class PoppingCase final : public OitCase {
 public:
  PoppingCase(std::unique_ptr<OitCase> inner, PathSetup s) : inner_(std::move(inner)), s_(std::move(s)) {}

  void run(PassTimer& timer) override { inner_->run(timer); }
  Validation validate() override {
    Validation v = inner_->validate();
    const auto t0 = std::chrono::steady_clock::now();
    const Popping pop = measure();
    v.metrics["popping"] = fmt(pop.mean);
    v.metrics["popping_max"] = fmt(pop.peak);
    v.metrics["popping_pixels"] = std::to_string(pop.pixels);
    v.metrics["popping_ms"] =
        fmt(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    if (s_.must_not_pop && pop.left_out > 0)
      v.reason += (v.reason.empty() ? "" : "; ") + std::string("popping: ") + std::to_string(pop.left_out) +
                  " pixel(s) that pop by more than " + fmt(kPoppingTolerance) +
                  " are left out of the exact check: their order is a float tie of two keys, or deeper than MAX_FRAGS";
    if (s_.must_not_pop && pop.pixels > 0) {
      v.valid = false;
      v.reason += (v.reason.empty() ? "" : "; ") + std::to_string(pop.pixels) + " pixel(s) pop by more than " +
                  fmt(kPoppingTolerance) +
                  " over the camera path (an exact per-pixel "
                  "technique must change only as the analytic reference does); largest: " +
                  pop.first;
    }
    return v;
  }
  std::map<std::string, std::string> metrics() const override { return inner_->metrics(); }
  std::map<std::string, std::string> resolved_params() const override { return inner_->resolved_params(); }
  int nominal_units() const override { return inner_->nominal_units(); }
  void set_units(int units) override { inner_->set_units(units); }
  void set_view_projection(const glm::mat4& view_proj) override { inner_->set_view_projection(view_proj); }
  GLuint result_texture() override { return inner_->result_texture(); }
  GLuint opaque_texture() const override { return inner_->opaque_texture(); }
  const FragmentStorage* fragments() const override { return inner_->fragments(); }
  unsigned max_frags() const override { return inner_->max_frags(); }

 private:
  std::unique_ptr<OitCase> inner_;
  PathSetup s_;

  glm::mat4 view_projection_of(const View& v) const {
    return view_projection(v, *s_.mesh, static_cast<float>(s_.width) / static_cast<float>(s_.height));
  }

  Popping measure() {
    PoppingMeter meter(s_.width, s_.height);
    PassTimer timer(false);
    const size_t n = static_cast<size_t>(s_.width) * s_.height;
    // Measured everywhere, but not held against an exact technique: pixels whose order is a float tie
    // (splat_reference.hpp) and those deeper than its MAX_FRAGS (a path frame deeper than its own view)
    // in either frame of a pair. Every other technique's popping_pixels counts them.
    const unsigned limit = inner_->max_frags();
    std::vector<char> unsure_before;
    for (int k = 0; k <= s_.path.steps; ++k) {
      const View v = path_view(s_.view, s_.path, k);
      inner_->set_view_projection(view_projection_of(v));
      timer.begin_repetition();
      inner_->run(timer);
      timer.end_repetition();
      const auto ref = reference(v);
      std::vector<char> unsure(n, 0), skip(n, 0);
      for (size_t p = 0; p < n && s_.must_not_pop; ++p) {
        unsure[p] = ref->tied[p] || (limit > 0 && ref->fragments[p] > limit);
        skip[p] = unsure[p] || (!unsure_before.empty() && unsure_before[p]);
      }
      meter.add(read_rgb(k), ref->rgb, s_.must_not_pop ? skip : std::vector<char>{});
      unsure_before = std::move(unsure);
    }
    inner_->set_view_projection(view_projection_of(s_.view));
    if (const GLenum err = glGetError(); err != GL_NO_ERROR)
      throw std::runtime_error("GL error " + std::to_string(err) + " on the popping path");
    return meter.result();
  }

  // The case's image over the background, RGB, as its own validation reads it.
  std::vector<float> read_rgb(int k) {
    const size_t n = static_cast<size_t>(s_.width) * s_.height;
    std::vector<float> rgba(n * 4);
    glGetTextureImage(inner_->result_texture(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(rgba.size() * sizeof(float)),
                      rgba.data());
    std::vector<float> rgb = rgb_of(rgba);
    for (size_t p = 0; p < n && s_.empty_is_alpha0; ++p)
      if (rgba[p * 4 + 3] == 0.0f)
        for (int c = 0; c < 3; ++c) rgb[p * 3 + c] = s_.scene.background[c];
    if (s_.fault_pop && k % 2 == 1)  // a block that jumps in every other frame: the check must fail
      for (int y = s_.height / 2 - 4; y < s_.height / 2 + 4; ++y)
        for (int x = s_.width / 2 - 4; x < s_.width / 2 + 4; ++x)
          if (x >= 0 && y >= 0) rgb[(static_cast<size_t>(y) * s_.width + x) * 3] += 4.0f / 255.0f;
    return rgb;
  }

  std::shared_ptr<const PathReference> reference(const View& v) const {
    auto make = [&]() -> std::shared_ptr<const PathReference> {
      SplatReferenceOptions options;
      options.order = SplatOrder::RayMaximum;  // the exact image, whatever the case's own key
      options.background = glm::dvec3(s_.scene.background);
      options.quantise_rgba8 = s_.quantise;
      options.min_transmittance = s_.early_stop;
      const glm::vec2 planes = near_far(v, *s_.mesh);  // the GPU's clip-z test culls outside them
      const SplatImage img =
          splat_reference(s_.mesh->splats, splat_camera(v, s_.width, s_.height, planes.x, planes.y), options);
      auto r = std::make_shared<PathReference>();
      r->rgb.resize(img.rgba.size() * 3);
      for (size_t p = 0; p < img.rgba.size(); ++p)
        for (int c = 0; c < 3; ++c) r->rgb[p * 3 + c] = static_cast<float>(img.rgba[p][c]);
      r->fragments = img.fragments;
      r->tied = img.tied;
      return r;
    };
    if (!s_.shared) return make();
    const auto& e = v.eye;
    const std::string key = s_.scene.path + "\n" + s_.view.name + "\n" + s_.detail + "\n" + std::to_string(s_.width) +
                            "x" + std::to_string(s_.height) + (s_.quantise ? " rgba8" : "") + "\nstop " +
                            fmt_exact(static_cast<float>(s_.early_stop)) + "\neye " + fmt_exact(e.x) + " " +
                            fmt_exact(e.y) + " " + fmt_exact(e.z);
    // as many frames as 512 MiB hold (at least a pair), so that the cases of an interleaved group share them
    const size_t frame_bytes = static_cast<size_t>(s_.width) * s_.height * (3 * sizeof(float) + sizeof(std::uint32_t));
    const size_t keep = std::clamp<size_t>((size_t(512) << 20) / std::max<size_t>(1, frame_bytes), 2, 130);
    return s_.shared->get<PathReference>(key, make, keep);
  }

  static std::string fmt_exact(float x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(x));
    return buf;
  }
};

}  // namespace

std::unique_ptr<OitCase> with_popping(std::unique_ptr<OitCase> inner, const ParamSet& p, CaseContext& ctx) {
  if (!p.has("popping_steps") || p.get_int("popping_steps") <= 0) return inner;
  PathSetup s;
  s.scene = load_scene(p.get("scene"));
  if (!scene_has_splats(s.scene) || select_effects(s.scene, p.has("effects") ? p.get("effects") : "scene") !=
                                        std::vector<std::string>{"transparency"})
    return inner;  // the analytic reference knows splats alone
  s.view = s.scene.view(p.get("view"));
  s.detail = p.get("detail");
  const Detail detail = s.detail == "small" ? Detail::Small : Detail::Full;
  if (ctx.shared()) {  // the case's own geometry (built already): its mesh
    auto g = scene_geometry(ctx, s.scene, s.view, detail, false, true);
    s.mesh = std::shared_ptr<const Mesh>(g, &g->mesh);
  } else {
    s.mesh = std::make_shared<const Mesh>(build_mesh(s.scene, s.view, detail));
  }
  s.path = {static_cast<int>(p.get_int("popping_steps")), p.get_double("popping_step_deg")};
  s.width = ctx.width();
  s.height = ctx.height();
  s.shared = ctx.shared();
  const Technique& t = technique(p.get("technique"));
  s.quantise = t.reads("frag_colour") && p.get("frag_colour") == "rgba8";
  s.early_stop = t.reads("early_stop") ? early_stop_of(p) : 0.0;
  s.must_not_pop = t.family == TechniqueFamily::Exact && p.get("splat_depth") == "ray-max";
  s.fault_pop = ctx.fault() == "path-pop";
  s.empty_is_alpha0 = t.family == TechniqueFamily::Exact;
  return std::make_unique<PoppingCase>(std::move(inner), std::move(s));
}

}  // namespace oitbench::oit
