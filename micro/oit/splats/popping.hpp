#pragma once
// Popping (issue 29, item 5): how much a technique's image jumps between neighbouring frames of a short
// camera path beyond what the exact image does. The 3DGS global sort orders whole splats by their centres'
// depths, so where two centres swap order as the camera moves every pixel they share changes at once,
// while the exact per-pixel order (the ray maximum's, StopThePop) changes only where that order does, one
// pixel at a time. The path: popping_steps + 1 frames orbiting the view's target about its up axis,
// popping_step_deg apart and centred on the case's own view (docs/splats.md#popping).
//
// Per pixel, per neighbouring pair of frames (k, k+1) and per colour channel c:
//   pop = max(0, |f(k+1) - f(k)| - |r(k+1) - r(k)|)
// f the technique's image, r the analytic reference's (splat_reference.hpp: the ray-maximum order,
// RGBA8-quantised where the case's fragments are RGBA8); a pixel's pop is its largest channel's. A
// technique that changes less than the reference (a smoothing approximation) pops 0 there: its error is
// truth_rmse's to report, not popping's. Every technique gets it (a decorator around its OitCase):
// stochastic ones' per-frame noise counts as popping (their flicker column is that noise at one view).
// Outside every timed pass: after the case's own validation, and the case's view is restored afterwards.
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

#include "core/registry.hpp"
#include "oit/oit_case.hpp"
#include "oit/scene/scene.hpp"

namespace oitbench::oit {

// A pop above this (per channel, colours in [0, 1]) counts its pixel in popping_pixels; an exact
// per-pixel technique (splat_depth=ray-max) with any such pixel is invalid.
inline constexpr double kPoppingTolerance = 2.0 / 255.0;

struct CameraPath {
  int steps = 0;          // frames - 1; 0: no path
  double step_deg = 1.0;  // the orbit's angle between neighbouring frames
};
// Frame k (0..steps) of the path: the view's eye turned by (k - steps / 2) * step_deg about the axis
// through its target along its up vector (up and target kept).
View path_view(const View& view, const CameraPath& path, int k);

struct Popping {
  double mean = 0;      // over every pixel of every neighbouring pair
  double peak = 0;      // the largest pixel
  size_t pixels = 0;    // pixels whose pop passes kPoppingTolerance in at least one pair
  size_t left_out = 0;  // pixels that pass it only in pairs where `skip` left them out
  std::string first;    // the largest pop `skip` did not leave out: "pixel (x,y) frames k-k+1: ..."
};
// Accumulates the popping of a path one frame at a time (RGB, 3 floats a pixel, glReadPixels' order;
// the reference in the same layout), holding only the previous frame. `skip`: pixels left out of
// `pixels` (not of mean and peak) in this pair, e.g. where the reference's order is a float tie.
class PoppingMeter {
 public:
  PoppingMeter(int width, int height) : width_(width), height_(height), popped_(size_t(width) * height, 0) {}
  void add(std::vector<float> image, std::vector<float> reference, const std::vector<char>& skip = {});
  Popping result() const;

 private:
  int width_, height_, frame_ = 0;
  std::vector<float> image_, reference_;  // the previous frame's
  std::vector<char> popped_;
  double sum_ = 0, largest_counted_ = 0;
  Popping p_;
};

// The path's parameters (popping_steps, popping_step_deg), scoped to splat scenes.
std::vector<ParamSpec> popping_params();

// The case with the popping path run after its validation (popping, popping_max, popping_pixels,
// popping_ms in the metrics), or the case itself where there is no path (a scene without splats, an
// effect beside transparency, popping_steps=0).
std::unique_ptr<OitCase> with_popping(std::unique_ptr<OitCase> inner, const ParamSet& p, CaseContext& ctx);

// The oit experiment's popping columns (splat scenes; empty elsewhere).
inline std::vector<MetricSpec> popping_metrics() {
  return {{"popping", ValueType::Number, "",
           "splat scenes: the image's change between neighbouring frames of the popping path beyond the analytic "
           "reference's, max(0, |f(k+1) - f(k)| - |r(k+1) - r(k)|) of the largest channel, mean over pixels and pairs "
           "(stochastic techniques: their per-frame noise included)"},
          {"popping_max", ValueType::Number, "", "splat scenes: the largest pixel's popping"},
          {"popping_pixels", ValueType::Integer, "",
           "splat scenes: pixels whose popping passes 2/255 in some pair of frames (exact per-pixel techniques with "
           "splat_depth=ray-max: any is invalid)"},
          {"popping_ms", ValueType::Number, "ms",
           "splat scenes: wall time of the popping path (its frames, read-backs and analytic references; after "
           "validation, outside the timed passes)"}};
}

}  // namespace oitbench::oit
