#pragma once
// Comparing an image with the exact reference composite, for every OIT case: the exact resolves'
// validation (ImageError: tolerance, resolve counts) and the error statistics every approximate
// technique and the lines experiment report as data (ApproxError).
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "oit/reference/reference.hpp"

namespace oitbench::oit {

struct ImageError {
  double max_abs_error = 0, rmse = 0;
  size_t bad_pixels = 0;    // above the tolerance
  size_t visit_errors = 0;  // covered pixels not resolved exactly once, or uncovered ones resolved
  std::string first_bad;    // "pixel (x,y): got (r,g,b), reference (r,g,b)"
};
// Compares a resolve's RGBA output (see above) with the reference; `tolerance` per channel.
ImageError compare_with_reference(const std::vector<float>& rgba, const std::vector<double>& reference,
                                  const ListStats& stats, const Backdrop& backdrop, int width, double tolerance);

// Image statistics against the exact reference (double RGB per pixel).
struct ApproxError {
  double rmse = 0, psnr = 0, max_abs_error = 0, frac_pixels_off = 0;  // off: by more than 1/255
};
ApproxError approx_error(const std::vector<float>& rgb, const std::vector<double>& reference);

// The flicker metric of every technique with per-frame randomness or races (RGB frames of one
// case): per-pixel variance across frames (mean over channels), averaged over pixels and at its
// peak, and the pixels that changed at all.
struct Flicker {
  double mean = 0, peak = 0;
  size_t changed = 0;
};
Flicker flicker_of(const std::vector<std::vector<float>>& frames);

// What an image holds outside displayable colours (the PFM keeps it; the PNG cannot show it):
// channel values that are NaN or infinite, and pixels with a finite colour channel outside [0, 1].
// `channels` 3 (RGB) or 4 (RGBA as the exact resolves write it; alpha is not a colour there).
struct ImageRange {
  size_t nonfinite = 0, out_of_range_pixels = 0;
};
ImageRange image_range(const std::vector<float>& image, int channels);

}  // namespace oitbench::oit
