#include "oit/reference/image_io.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>

// The one translation unit that compiles stb's PNG writer (a Debian header, not vendored).
#define STB_IMAGE_WRITE_IMPLEMENTATION
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wsign-compare"
#include <stb_image_write.h>
#pragma GCC diagnostic pop

namespace oitbench::oit {

void write_png(const std::string& path, const std::vector<float>& rgb, int width, int height, float scale) {
  std::vector<unsigned char> bytes(static_cast<size_t>(width) * height * 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int k = 0; k < 3; ++k) {
        float v = rgb[(static_cast<size_t>(height - 1 - y) * width + x) * 3 + k] * scale;
        bytes[(static_cast<size_t>(y) * width + x) * 3 + k] =
            static_cast<unsigned char>(std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f : 255.0f);
      }
  if (!stbi_write_png(path.c_str(), width, height, 3, bytes.data(), width * 3))
    throw std::runtime_error("cannot write " + path);
}
void write_pfm(const std::string& path, const std::vector<float>& rgb, int width, int height) {
  std::ofstream pfm(path, std::ios::binary);
  pfm << "PF\n" << width << " " << height << "\n-1.0\n";
  pfm.write(reinterpret_cast<const char*>(rgb.data()), static_cast<std::streamsize>(rgb.size() * sizeof(float)));
  if (!pfm) throw std::runtime_error("cannot write " + path);
}

void write_result_images(const std::string& stem, const std::vector<float>& rgb, const std::vector<double>& reference,
                         int width, int height) {
  std::vector<float> diff(rgb.size());
  for (size_t i = 0; i < rgb.size(); ++i) diff[i] = static_cast<float>(std::abs(rgb[i] - reference[i]));
  write_png(stem + ".png", rgb, width, height);
  write_pfm(stem + ".pfm", rgb, width, height);
  write_png(stem + "-diff8.png", diff, width, height, 8.0f);
}

}  // namespace oitbench::oit
