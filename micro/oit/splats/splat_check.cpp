#include "oit/splats/splat_check.hpp"

#include <algorithm>
#include <cmath>

#include "oit/case_support.hpp"
#include "oit/splats/splat_reference.hpp"

namespace oitbench::oit {

std::optional<SplatCheck> check_against_splats(const ScenePasses& fx, const std::vector<float>& image, int channels,
                                               int width, int height, double tolerance, bool rgba8_fragments,
                                               double min_transmittance) {
  if (!fx.splats() || fx.effects() != std::vector<std::string>{"transparency"}) return std::nullopt;
  const Mesh& mesh = fx.mesh();
  SplatReferenceOptions options;
  options.order = fx.splat_depth() == "centre" ? SplatOrder::Centre : SplatOrder::RayMaximum;
  options.background = glm::dvec3(fx.scene().background);
  options.quantise_rgba8 = rgba8_fragments;  // the fragments rounded as the capture stores them
  options.min_transmittance = min_transmittance;
  const glm::vec2 planes = near_far(fx.view(), mesh);  // the GPU's clip-z test culls outside them
  const SplatCamera camera = splat_camera(fx.view(), width, height, planes.x, planes.y);
  const SplatImage ref = splat_reference(mesh.splats, camera, options);
  SplatCheck c;
  double sum = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t p = static_cast<size_t>(y) * width + x;
      // an exact resolve leaves an uncovered pixel at alpha 0: the background shows there
      const bool empty = channels == 4 && image[p * 4 + 3] == 0.0f;
      double got[3];
      for (int k = 0; k < 3; ++k) got[k] = empty ? options.background[k] : image[p * channels + k];
      double worst = 0;
      for (int k = 0; k < 3; ++k) {
        const double d = std::abs(got[k] - ref.rgba[p][k]);
        sum += d * d;
        worst = std::max(worst, std::isfinite(d) ? d : 1.0);
      }
      c.max_abs_error = std::max(c.max_abs_error, worst);
      // a float tie may be ordered either way by the GPU's float keys: the swap's effect is allowed too
      c.tied_pixels += ref.tied[p];
      if (worst > tolerance + ref.tie_slack[p] && c.bad_pixels++ == 0)
        c.first_bad = "pixel (" + std::to_string(x) + "," + std::to_string(y) + "): " + fmt(got[0]) + " " +
                      fmt(got[1]) + " " + fmt(got[2]) + ", analytic " + fmt(ref.rgba[p].r) + " " + fmt(ref.rgba[p].g) +
                      " " + fmt(ref.rgba[p].b) + " (" + std::to_string(ref.fragments[p]) + " splat fragment(s))";
    }
  c.rmse = std::sqrt(sum / std::max<double>(1.0, 3.0 * width * height));
  return c;
}

void report_splat_check(const std::optional<SplatCheck>& check, double tolerance,
                        std::map<std::string, std::string>& metrics, std::vector<std::string>* problems) {
  if (!check) return;
  metrics["truth_rmse"] = fmt(check->rmse);
  metrics["truth_max_abs_error"] = fmt(check->max_abs_error);
  metrics["geometric_bad_pixels"] = std::to_string(check->bad_pixels);
  if (check->tied_pixels) metrics["splat_tied_pixels"] = std::to_string(check->tied_pixels);
  if (problems && check->bad_pixels)
    problems->push_back(std::to_string(check->bad_pixels) +
                        " pixel(s) differ from the analytic splat reference by more than " + fmt(tolerance) +
                        "; first: " + check->first_bad);
}

}  // namespace oitbench::oit
