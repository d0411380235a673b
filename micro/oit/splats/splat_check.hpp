#pragma once
// A splat case's image against the analytic reference of its splats (splat_reference.hpp: every splat's
// alpha evaluated at every pixel centre on the CPU from the splat list, sorted by the key, composited in
// double), a reference that shares nothing with the captured fragments. Every technique's case on a
// splat scene reports its error against it in the truth_* metrics and geometric_bad_pixels (the planes
// scenes' geometric reference's columns: the truth of an analytic scene); the exact techniques must
// match it within their tolerance.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "oit/scene/scene_passes.hpp"

namespace oitbench::oit {

struct SplatCheck {
  double rmse = 0, max_abs_error = 0;  // over every colour channel
  size_t bad_pixels = 0;               // a channel more than the tolerance (plus the pixel's tie slack) off
  size_t tied_pixels = 0;              // pixels whose order is a float tie (splat_reference.hpp): their
                                       // tolerance grows by what swapping the tied pairs moves them
  std::string first_bad;
};

// `image`: the case's image (`channels` floats a pixel, the colour first, glReadPixels' order),
// composited over the scene's background (with 4 channels, a pixel at alpha 0 is uncovered: the background). Nothing
// where the scene has no splats or runs another effect than transparency (the reference knows no opaque pass). The
// reference's order is the case's splat_depth key. `rgba8_fragments`: the case captured its fragments in RGBA8
// (frag_colour=rgba8), so the reference rounds each splat fragment the same way (splat_reference.hpp).
// `min_transmittance`: the case's early_stop threshold (3DGS's early termination; 0: off), the reference's too.
std::optional<SplatCheck> check_against_splats(const ScenePasses& fx, const std::vector<float>& image, int channels,
                                               int width, int height, double tolerance, bool rgba8_fragments = false,
                                               double min_transmittance = 0);

// The metrics of a check (nothing without one), and its problem where `problems` is given (the exact
// techniques: they must match it).
void report_splat_check(const std::optional<SplatCheck>& check, double tolerance,
                        std::map<std::string, std::string>& metrics, std::vector<std::string>* problems);

}  // namespace oitbench::oit
