// occupancy: local array size vs time (Knowles, Leach, Zambetta 2013, figure 3).
// A full-screen pass whose fragment shader holds `vec4 myArray[SIZE]`, drawn `draws` times.
#include <cmath>
#include <memory>
#include <string>

#include "core/registry.hpp"
#include "gl/render_target.hpp"
#include "models/occupancy_model.hpp"

namespace oitbench {

namespace {

std::vector<std::string> default_sizes() {
  // Powers of two and both sides of each, 1 to 256: the steps of figure 3 and llvmpipe's 32/33 cliff.
  std::vector<std::string> s = {"1", "2", "3", "4", "5"};
  for (int p = 8; p <= 256; p *= 2) {
    s.push_back(std::to_string(p - 1));
    s.push_back(std::to_string(p));
    if (p < 256) s.push_back(std::to_string(p + 1));
  }
  return s;
}

// The CPU reference of shaders/occupancy/occupancy.frag.
struct Element {
  float v[4];
};
Element element(int x, int y, int i) {
  return {{static_cast<float>((x * (i + 1) + y) & 1023), static_cast<float>((y * (i + 3)) & 511), static_cast<float>(i),
           static_cast<float>((x ^ i) & 63)}};
}

class OccupancyCase final : public CaseInstance {
 public:
  OccupancyCase(const ParamSet& p, CaseContext& ctx)
      : size_(static_cast<int>(p.get_int("size"))),
        draws_(static_cast<int>(p.get_int("draws"))),
        dynamic_(p.get("variant") == "dynamic"),
        target_(ctx.width(), ctx.height()) {
    program_ =
        ctx.build({{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "occupancy/occupancy.frag"}},
                  {{"SIZE", std::to_string(size_)}, {dynamic_ ? "VARIANT_DYNAMIC" : "VARIANT_UNROLLED", ""}});
    glProgramUniform1i(program_.get(), glGetUniformLocation(program_.get(), "zero"), 0);
    if (auto budget = find_budget(p.get("model_gpu"), ctx.gl().renderer)) {
      auto pred = predict_occupancy(*budget, size_, dynamic_);
      metrics_["model_gpu_used"] = budget->key;
      metrics_["predicted_occupancy"] = std::to_string(pred.occupancy);
      metrics_["predicted_threads_per_sm"] = std::to_string(pred.threads_per_sm);
    } else {
      metrics_["model_gpu_used"] = "unknown";
    }
  }

  void run(PassTimer& timer) override {
    target_.bind();
    glUseProgram(program_.get());
    auto pass = timer.pass("draw");
    for (int i = 0; i < draws_; ++i) quad_.draw();
  }

  Validation validate() override {
    auto px = target_.read_rgba32f();
    Validation v;
    long bad = 0;
    std::string first;
    for (int y = 0; y < target_.height(); ++y)
      for (int x = 0; x < target_.width(); ++x) {
        float ref[4] = {0, 0, 0, 0};
        if (dynamic_) {
          auto a = element(x, y, x % size_), b = element(x, y, y % size_);
          for (int k = 0; k < 4; ++k) ref[k] = a.v[k] + b.v[k];
        } else {
          for (int i = 0; i < size_; ++i) {
            auto e = element(x, y, i);
            for (int k = 0; k < 4; ++k) ref[k] += e.v[k] * static_cast<float>(i % 3 + 1);
          }
        }
        const float* got = &px[(static_cast<size_t>(y) * target_.width() + x) * 4];
        for (int k = 0; k < 4; ++k)
          if (got[k] != ref[k]) {
            if (bad++ == 0)
              first = "pixel (" + std::to_string(x) + "," + std::to_string(y) + ")[" + std::to_string(k) +
                      "] = " + std::to_string(got[k]) + ", CPU reference " + std::to_string(ref[k]);
            break;
          }
      }
    v.valid = bad == 0;
    v.metrics["mismatched_pixels"] = std::to_string(bad);
    if (!v.valid) v.reason = std::to_string(bad) + " pixel(s) differ from the CPU reference; first: " + first;
    return v;
  }

  std::map<std::string, std::string> metrics() const override { return metrics_; }

 private:
  int size_, draws_;
  bool dynamic_;
  RenderTarget target_;
  FullscreenTriangle quad_;
  gl::Program program_;
  std::map<std::string, std::string> metrics_;
};

class OccupancyExperiment final : public Experiment {
 public:
  std::string name() const override { return "occupancy"; }
  std::string description() const override {
    return "local array size vs time (Knowles 2013 BMA, fig. 3): a full-screen pass holding vec4 myArray[SIZE], "
           "drawn `draws` times; ms for all draws";
  }
  std::vector<ParamSpec> params() const override {
    ParamSpec variant{"variant",
                      "dynamic: indexed by a uniform (local/scratch memory); unrolled: constant "
                      "indices after unrolling (registers where the compiler can)",
                      {"dynamic", "unrolled"},
                      {},
                      {"dynamic", "unrolled"}};
    ParamSpec size{"size",
                   "elements in vec4 myArray[SIZE]",
                   default_sizes(),
                   {"1", "8", "32", "33", "64"},
                   {},
                   ParamSpec::Kind::Integer,
                   1,
                   1024};
    ParamSpec draws{"draws", "full-screen draws per repetition", {"64"}, {"8"},
                    {},      ParamSpec::Kind::Integer,           1,      100000};
    ParamSpec model{"model_gpu",
                    "GPU budget for predicted_occupancy: auto (from GL_RENDERER), or one of the table",
                    {"auto"},
                    {},
                    {"auto"}};
    for (const auto& g : gpu_budgets()) model.allowed.push_back(g.key);
    return {variant, size, draws, model};
  }
  std::vector<MetricSpec> metric_specs() const override {
    return {{"predicted_occupancy", ValueType::Number, "",
             "resident warps or waves per SM / CU over the maximum, from "
             "the analytic model (model_gpu)"},
            {"predicted_threads_per_sm", ValueType::Integer, "", "resident threads per SM the model predicts"},
            {"model_gpu_used", ValueType::Text, "", "the GPU whose budgets the model used, or unknown"},
            {"mismatched_pixels", ValueType::Integer, "", "pixels that differ from the CPU reference"}};
  }
  Resolution default_resolution() const override { return {800, 600}; }
  Resolution quick_resolution() const override { return {200, 150}; }
  std::unique_ptr<CaseInstance> prepare(const ParamSet& p, CaseContext& ctx) override {
    return std::make_unique<OccupancyCase>(p, ctx);
  }
};

}  // namespace

void register_occupancy(Registry& registry) { registry.add(std::make_unique<OccupancyExperiment>()); }

}  // namespace oitbench
