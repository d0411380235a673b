#pragma once
// The geometric reference of analytic scenes (scenes made only by the planes generator): each
// pixel's composite computed from the scene description itself (plane positions, colours, alphas,
// the camera), in double precision, independent of anything the GPU captured. The ray through the
// pixel centre is intersected with every plane, the hits are sorted by their true distance along the
// view axis and composited with "over". Two references come out: `exact`, with the colours as
// described (the truth a format's precision is measured against: truth_rmse), and `quantised`, with
// each colour as the fragment format stores it (what a right capture and resolve must give).
//
// Ties: planes at exactly the same depth are ordered as every resolve orders equal depths, by the
// stored colour's tie key (alpha, blue, green, red; larger farther), so the answer does not depend
// on the submission order. Pixels whose centre lies within 1/256 pixel of a plane's edge, or whose hit
// lies within 1e-5 (relative) of the near or far plane, are ambiguous (the rasterizer's snapping
// decides them) and left out of every comparison (counted in ambiguous_pixels).
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/shared_cache.hpp"
#include "oit/capture/fragment_storage.hpp"
#include "oit/scene/scene.hpp"

namespace oitbench::oit {

struct GeometricReference {
  int width = 0, height = 0;
  std::vector<double> exact, quantised;  // RGB per pixel, rows from the bottom
  std::vector<unsigned> layers;          // planes the pixel's ray hits between near and far
  std::vector<bool> ambiguous;
  size_t ambiguous_pixels = 0;
  size_t coplanar_pixels = 0;  // pixels with two planes at exactly the same depth (ordered by the tie rule)
};

// Quantises a colour as the fragment format stores it (rgba8: packUnorm4x8's steps of 1/255;
// rgba16f: binary16, round to nearest even; rgba32f: unchanged).
glm::dvec4 quantise_colour(glm::vec4 c, FragColour format);

// nullopt when the scene is not analytic (an object of another generator). `near_far`: the planes
// view_projection() put in the matrix the capture used.
std::optional<GeometricReference> geometric_reference(const SceneDesc& scene, const View& view, Detail detail,
                                                      glm::vec2 near_far, int width, int height, FragColour format);
// The same through the run's shared cache (`cache` null: computed here), so the run's cases of one scene,
// view, size and format share one (the rows are spread over the cores). Keyed by everything it reads:
// the planes themselves (not the scene's name), the background, the camera, near/far, the size and the
// format, each number exactly (hex floats), so a changed scene file or parameter can never hit a stale
// entry. Null when the scene is not analytic.
std::shared_ptr<const GeometricReference> shared_geometric_reference(SharedCache* cache, const SceneDesc& scene,
                                                                     const View& view, Detail detail,
                                                                     glm::vec2 near_far, int width, int height,
                                                                     FragColour format);
// The key shared_geometric_reference() stores under (empty when the scene is not analytic).
std::string geometric_reference_key(const SceneDesc& scene, const View& view, Detail detail, glm::vec2 near_far,
                                    int width, int height, FragColour format);

// The image of a case against both references (colours in [0, 1], RGBA as the resolves write it:
// alpha 0 = nothing resolved, the background shows).
struct GeometricCheck {
  double truth_rmse = 0, truth_max_abs_error = 0;  // against `exact`, over the unambiguous pixels
  size_t bad_pixels = 0;                           // off `quantised` by more than the tolerance
  size_t layer_mismatches = 0;                     // captured fragments != planes hit
  std::string first_bad, first_layer_mismatch;
};
GeometricCheck check_against_geometry(const GeometricReference& ref, const std::vector<float>& rgba,
                                      const std::vector<unsigned>& captured_depth, glm::vec3 background,
                                      double tolerance);

}  // namespace oitbench::oit
