// occupancy: local array size vs time (Knowles, Leach, Zambetta 2013, figure 3).
// A full-screen pass whose fragment shader holds `vec4 myArray[SIZE]`, drawn `draws` times. Where the driver
// offers GL_NV_shader_thread_group, validation also measures the warps resident per SM in one untimed pass.
#include "experiments/occupancy.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "core/registry.hpp"
#include "gl/render_target.hpp"
#include "models/occupancy_model.hpp"
#include "shaders/occupancy/bindings.h"

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

// GL_NV_shader_thread_group's queries (the extension's enums; the generated loader does not carry them).
constexpr GLenum kWarpsPerSmNV = 0x933A, kSmCountNV = 0x933B;
constexpr const char* kThreadGroupExtension = "GL_NV_shader_thread_group";

}  // namespace

std::string occupancy_measure_unavailable(const GlInfo& gl) {
  if (gl.has_extension(kThreadGroupExtension)) return "";
  return std::string("not measured: the driver does not offer ") + kThreadGroupExtension;
}

OccupancyMeasurement count_warp_slots(const std::vector<unsigned>& slots, int sm_count, int warps_per_sm) {
  OccupancyMeasurement m;
  m.warps_per_sm = warps_per_sm;
  const size_t words = (static_cast<size_t>(warps_per_sm) + 31) / 32;
  if (sm_count <= 0 || warps_per_sm <= 0 || slots.size() < 1 + words * static_cast<size_t>(sm_count)) return m;
  m.out_of_range = slots[0];
  long total = 0;
  for (int sm = 0; sm < sm_count; ++sm) {
    int seen = 0;
    for (size_t w = 0; w < words; ++w) seen += std::popcount(slots[1 + sm * words + w]);
    if (seen == 0) continue;
    ++m.sms_with_warps;
    total += seen;
    m.max_slots = std::max(m.max_slots, seen);
  }
  if (m.sms_with_warps > 0) {
    m.mean_slots = static_cast<double>(total) / m.sms_with_warps;
    m.occupancy = static_cast<double>(m.max_slots) / warps_per_sm;
  }
  return m;
}

std::string OccupancyMeasurement::note() const {
  if (sms_with_warps == 0) return "no warp marked a slot (the measuring draw produced no fragments?)";
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "warp slots seen in one untimed pass: at most %d of %d on an SM (mean %.1f over %d SMs)", max_slots,
                warps_per_sm, mean_slots, sms_with_warps);
  std::string s = buf;
  if (out_of_range > 0) s += "; " + std::to_string(out_of_range) + " warp(s) gave an SM or warp id out of range";
  return s;
}

namespace {

class OccupancyCase final : public CaseInstance {
 public:
  OccupancyCase(const ParamSet& p, CaseContext& ctx)
      : size_(static_cast<int>(p.get_int("size"))),
        draws_(static_cast<int>(p.get_int("draws"))),
        dynamic_(p.get("variant") == "dynamic"),
        target_(ctx.width(), ctx.height()) {
    const std::vector<ShaderStage> stages = {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                             {GL_FRAGMENT_SHADER, "occupancy/occupancy.frag"}};
    Defines defines = {{"SIZE", std::to_string(size_)}, {dynamic_ ? "VARIANT_DYNAMIC" : "VARIANT_UNROLLED", ""}};
    program_ = ctx.build(stages, defines);
    glProgramUniform1i(program_.get(), glGetUniformLocation(program_.get(), "zero"), 0);
    // The measuring variant exists only where the extension does; a driver that refuses it leaves the
    // timed case alone and says why in measured_occupancy_note.
    measure_note_ = occupancy_measure_unavailable(ctx.gl());
    if (measure_note_.empty()) {
      defines.emplace_back("OCCUPANCY_MEASURE", "");
      try {
        measure_program_ = ctx.build(stages, defines);
        glProgramUniform1i(measure_program_.get(), glGetUniformLocation(measure_program_.get(), "zero"), 0);
      } catch (const ShaderError& e) {
        std::string what = e.what();
        measure_note_ = "not measured: the OCCUPANCY_MEASURE shader did not build: " + what.substr(0, what.find('\n'));
      }
    }
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
    for (int i = 0; i < run_draws_; ++i) quad_.draw();
  }

  int nominal_units() const override { return draws_; }
  void set_units(int units) override { run_draws_ = units; }

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
    measure(v.metrics);  // after the read-back: the timed repetitions and their image are untouched
    return v;
  }

  std::map<std::string, std::string> metrics() const override { return metrics_; }

 private:
  // One untimed pass of `draws` draws with the measuring variant: which warp slots each SM used.
  void measure(std::map<std::string, std::string>& out) {
    if (!measure_program_) {
      out["measured_occupancy_note"] = measure_note_;
      return;
    }
    GLint sm_count = 0, warps_per_sm = 0;
    glGetIntegerv(kSmCountNV, &sm_count);
    glGetIntegerv(kWarpsPerSmNV, &warps_per_sm);
    if (sm_count <= 0 || warps_per_sm <= 0) {
      out["measured_occupancy_note"] = "not measured: the driver reports " + std::to_string(sm_count) + " SMs and " +
                                       std::to_string(warps_per_sm) + " warps per SM";
      return;
    }
    const size_t words = (static_cast<size_t>(warps_per_sm) + 31) / 32;
    std::vector<unsigned> slots(1 + words * static_cast<size_t>(sm_count), 0u);
    auto buffer = gl::make_buffer();
    const auto bytes = static_cast<GLsizeiptr>(slots.size() * sizeof(unsigned));
    glNamedBufferData(buffer.get(), bytes, slots.data(), GL_DYNAMIC_READ);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OCCUPANCY_SLOTS_BINDING, buffer.get());
    target_.bind();
    glUseProgram(measure_program_.get());
    for (int i = 0; i < draws_; ++i) quad_.draw();
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(buffer.get(), 0, bytes, slots.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OCCUPANCY_SLOTS_BINDING, 0);
    if (GLenum err = glGetError(); err != GL_NO_ERROR) {
      char hex[16];
      std::snprintf(hex, sizeof hex, "0x%04x", err);
      out["measured_occupancy_note"] = std::string("not measured: GL error ") + hex + " in the measuring pass";
      return;
    }
    auto m = count_warp_slots(slots, sm_count, warps_per_sm);
    if (m.sms_with_warps > 0) out["measured_occupancy"] = std::to_string(m.occupancy);
    out["measured_occupancy_note"] = m.note();
  }

  int size_, draws_;
  int run_draws_ = draws_;  // draws per timed run: fewer where the framework scales the work down
  bool dynamic_;
  RenderTarget target_;
  FullscreenTriangle quad_;
  gl::Program program_, measure_program_;
  std::string measure_note_;  // why measure_program_ is empty
  std::map<std::string, std::string> metrics_;
};

class OccupancyExperiment final : public ExperimentOf<OccupancyCase> {
 public:
  OccupancyExperiment()
      : ExperimentOf("occupancy",
                     "local array size vs time (Knowles 2013 BMA, fig. 3): a full-screen pass holding vec4 "
                     "myArray[SIZE], drawn `draws` times; ms for all draws",
                     {800, 600}, {200, 150}) {}
  std::vector<ParamSpec> params() const override {
    std::vector<std::string> models = {"auto"};
    for (const auto& g : gpu_budgets()) models.push_back(g.key);
    return {ParamSpec::choice("variant",
                              "dynamic: indexed by a uniform (local/scratch memory); unrolled: constant indices "
                              "after unrolling (registers where the compiler can)",
                              {"dynamic", "unrolled"}),
            ParamSpec::integer("size", "elements in vec4 myArray[SIZE]", 1, 1024, default_sizes(),
                               {"1", "8", "32", "33", "64"}),
            ParamSpec::integer("draws", "full-screen draws per repetition", 1, 100000, {"64"}, {"8"}),
            ParamSpec::choice("model_gpu",
                              "GPU budget for predicted_occupancy: auto (from GL_RENDERER), or one of the table",
                              models, {"auto"})};
  }
  std::vector<MetricSpec> metric_specs() const override {
    return {{"predicted_occupancy", ValueType::Number, "",
             "resident warps or waves per SM / CU over the maximum, from "
             "the analytic model (model_gpu)"},
            {"predicted_threads_per_sm", ValueType::Integer, "", "resident threads per SM the model predicts"},
            {"model_gpu_used", ValueType::Text, "", "the GPU whose budgets the model used, or unknown"},
            {"measured_occupancy", ValueType::Number, "",
             "distinct warp slots seen on the busiest SM over gl_WarpsPerSMNV, from one untimed pass of the "
             "measuring variant at validation (GL_NV_shader_thread_group); empty where not measured"},
            {"measured_occupancy_note", ValueType::Text, "",
             "how measured_occupancy was measured (slots, SMs), or why it is empty (e.g. the driver lacks "
             "GL_NV_shader_thread_group)"},
            {"mismatched_pixels", ValueType::Integer, "", "pixels that differ from the CPU reference"}};
  }
};

}  // namespace

void register_occupancy(Registry& registry) { registry.add(std::make_unique<OccupancyExperiment>()); }

}  // namespace oitbench
