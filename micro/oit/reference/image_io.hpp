#pragma once
// Writing a case's result images, the one place for exact and approximate cases and the viewer:
// 8-bit PNG (stb), float PFM, and the |image - reference| x 8 difference.
#include <string>
#include <vector>

namespace oitbench::oit {

// 8-bit sRGB-less PNG of an RGB float image (rows bottom-up as GL reads them), values * scale.
void write_png(const std::string& path, const std::vector<float>& rgb, int width, int height, float scale = 1.0f);

// Portable Float Map of an RGB float image (rows bottom-up as GL reads them, little endian).
void write_pfm(const std::string& path, const std::vector<float>& rgb, int width, int height);
// STEM.png and STEM.pfm (the image) and STEM-diff8.png (|image - reference| x 8); `reference` is RGB
// doubles per pixel. Throws std::runtime_error naming a file it cannot write.
void write_result_images(const std::string& stem, const std::vector<float>& rgb, const std::vector<double>& reference,
                         int width, int height);

}  // namespace oitbench::oit
