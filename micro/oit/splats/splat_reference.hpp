#pragma once
// The analytic reference of a splat scene (issue 29, item 4), and the specification of the splat
// rasteriser in shaders/splats/, which must compute exactly this (in float where this computes in double).
//
// Projection of one splat (Kerbl et al. 2023, "3D Gaussian Splatting for Real-Time Radiance Field
// Rendering", and Zwicker et al.'s EWA splatting), project_splat():
//   - view space is glm::lookAt(eye, target, up)'s: the camera looks along -z; a point's view depth is
//     t = -z_view. A splat whose centre has t <= near_plane or t > far_plane is skipped (3DGS skips
//     t <= 0.2; the GPU culls the centres its clip z puts outside [-w, w], the same planes).
//   - window coordinates are OpenGL's: pixels from the bottom-left, pixel (i, j)'s centre at (i + 0.5, j + 0.5);
//     a view point (x, y, -t) lands at (cx + fx x / t, cy + fy y / t), cx = width / 2, cy = height / 2,
//     fy = height / (2 tan(fov_y / 2)), fx = fy (square pixels; tan_fovx = tan_fovy * width / height).
//   - the 3D covariance is Σ = R S Sᵀ Rᵀ, R the splat's rotation (local axes to world), S = diag(scale);
//     in view space Σv = W Σ Wᵀ, W the view matrix's rotation.
//   - the perspective's Jacobian at the centre (x, y, -t), with 3DGS's clamp of x/t and y/t to 1.3 times
//     the frustum's tangents (x' = clamp(x / t, -1.3 tan_fovx, 1.3 tan_fovx) t, the same for y):
//       J = [ fx / t   0        fx x' / t² ]
//           [ 0        fy / t   fy y' / t² ]
//     (+ signs: z_view = -t, so d(x / t)/dz_view = x / t²).
//   - Σ' = J Σv Jᵀ + 0.3 I (the low-pass filter, in pixels²); conic = Σ'⁻¹ = (a, b, c) (a the xx term,
//     b the xy term, c the yy term); a splat with det Σ' <= 0 is skipped.
//   - radius = ceil(3 sqrt(λmax)), λmax = (Σ'xx + Σ'yy) / 2 + sqrt(((Σ'xx - Σ'yy) / 2)² + Σ'xy²): the
//     GPU's quad covers [mean - radius, mean + radius] on both axes; a pixel takes part when its centre
//     lies strictly inside (|dx| < radius and |dy| < radius).
// A pixel's fragment of a splat, splat_alpha(): d = pixel centre - mean,
//   power = -(a dx² + c dy²) / 2 - b dx dy; skipped when power > 0 (only by rounding);
//   alpha = min(0.99, opacity exp(power)); skipped when alpha < 1/255. Its colour is the splat's.
// Its depth keys:
//   - the centre's view depth (the 3DGS global sort's key: one per splat), SplatProjection::centre_depth;
//   - the depth of the Gaussian's maximum along the pixel's ray (StopThePop, Radl et al. 2024),
//     ray_max_depth(): the ray from the eye through the pixel centre, o + s v in view space with
//     v = ((px - cx) / fx, (py - cy) / fy, -1) (view depth s), has its maximum of the 3D Gaussian at
//     s* = vᵀ Σv⁻¹ μv / vᵀ Σv⁻¹ v (μv the centre in view space); s* is the key.
// The image, splat_reference(): per pixel, its fragments sorted front to back by the chosen key (ties by
// splat index, the submission order), composited in double precision, C += T alpha colour, T *= 1 - alpha,
// then over the background: rgb = C + T background, a = 1 - T. With min_transmittance > 0, 3DGS's early
// termination: the fragment that would take T below it is not blended, nor any after it.
// Work and memory are bounded: splats are binned to 16x16 tiles by their quads and the tiles composited
// one at a time per worker thread, so only one tile's fragments per worker are ever held.
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "oit/scene/scene.hpp"
#include "oit/splats/splat.hpp"

namespace oitbench::oit {

struct SplatCamera {
  glm::dmat3 rotation{1.0};     // W: world to view
  glm::dvec3 translation{0.0};  // view = W world + translation
  double fx = 1, fy = 1, cx = 0, cy = 0, tan_fovx = 1, tan_fovy = 1, near_plane = 0.01;
  double far_plane = std::numeric_limits<double>::infinity();
  int width = 1, height = 1;
};
// The camera of a view for an image of width x height and the GPU's near and far planes (near_far(view, mesh)).
SplatCamera splat_camera(const View& view, int width, int height, double near_plane,
                         double far_plane = std::numeric_limits<double>::infinity());

struct SplatProjection {
  glm::dvec2 mean{0.0};            // window coordinates of the centre
  glm::dvec3 conic{0.0};           // (a, b, c) of Σ'⁻¹
  int radius = 0;                  // the quad's half side, pixels
  double centre_depth = 0;         // view depth of the centre
  glm::dvec3 view_centre{0.0};     // μv
  glm::dmat3 inv_cov{1.0};         // Σv⁻¹ (symmetric)
  glm::dvec3 inv_cov_centre{0.0};  // Σv⁻¹ μv
  double opacity = 0;
  glm::dvec3 colour{0.0};
};
// Nothing when the splat is skipped (behind the near plane, or a degenerate 2D covariance).
std::optional<SplatProjection> project_splat(const Splat& splat, const SplatCamera& camera);
// The fragment's alpha at the window point `pixel` (a pixel centre), 0 when it is skipped (outside the
// quad, power > 0, alpha below 1/255).
double splat_alpha(const SplatProjection& p, glm::dvec2 pixel);
// The view depth of the Gaussian's maximum along the ray through `pixel`.
double ray_max_depth(const SplatProjection& p, glm::dvec2 pixel, const SplatCamera& camera);

enum class SplatOrder {
  RayMaximum,  // the exact reference: per pixel by ray_max_depth
  Centre,      // the 3DGS global sort: by centre_depth (one order for the whole image)
};

struct SplatReferenceOptions {
  SplatOrder order = SplatOrder::RayMaximum;
  double min_transmittance = 0;  // 3DGS's early termination at 1e-4; 0 blends every fragment
  glm::dvec3 background{1.0};
  // Each fragment's colour and alpha rounded to 8 bits as the GPU's RGBA8 fragments are (frag_colour=RGBA8):
  // over many layers that rounding alone moves a pixel by more than 2/255, so an RGBA8 case is compared
  // with the quantised reference (the unquantised one is the scene's true image).
  bool quantise_rgba8 = false;
  unsigned threads = 0;  // workers over the tiles; 0: one per hardware thread (the image is the same)
};

// A pixel whose order a float key may not decide: two neighbouring fragments (in the reference's order) whose
// keys are within kSplatKeyTie of each other, relative, and whose swap would move the pixel by more than
// kSplatTieEffect in a channel (T a_i a_j |c_i - c_j|). The GPU's float32 keys (a few ulps, 1e-7 relative,
// apart) can order such a pair either way: scenes/splats.json seen 1 degree off its view has one at pixel
// (187,70), keys 3.1542271 and 3.1542277, whose swap moves the pixel by 0.021.
inline constexpr double kSplatKeyTie = 1e-5;
inline constexpr double kSplatTieEffect = 1.0 / 255.0;

struct SplatImage {
  int width = 0, height = 0;
  std::vector<glm::dvec4> rgba;          // row-major from the bottom row (glReadPixels' order)
  std::vector<std::uint32_t> fragments;  // per pixel: its fragments (alpha >= 1/255), early termination or not
  std::vector<std::uint8_t> tied;        // per pixel: 1 where its order is a float tie (above)
  std::vector<float> tie_slack;          // per pixel: the sum of its tied pairs' swap effects (0: none)
  glm::dvec4 at(int x, int y) const { return rgba[static_cast<size_t>(y) * width + x]; }
};
SplatImage splat_reference(const SplatList& splats, const SplatCamera& camera, const SplatReferenceOptions& options);

}  // namespace oitbench::oit
