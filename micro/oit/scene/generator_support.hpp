#pragma once
// What the procedural generators share (scene.cpp's and the splat generator's, splats/splat_scene.cpp):
// the deterministic random numbers and the hues. A scene must not depend on the standard library's
// distributions (they differ between implementations), so a scene file plus a view is the same geometry
// on every machine.
#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

namespace oitbench::oit {

// A deterministic generator: xorshift64* over a seed mixed by an LCG step.
struct Rng {
  unsigned long long s;
  explicit Rng(unsigned long long seed) : s(seed * 6364136223846793005ULL + 1442695040888963407ULL) {}
  double uniform() {  // [0, 1)
    s ^= s >> 12;
    s ^= s << 25;
    s ^= s >> 27;
    return static_cast<double>((s * 2685821657736338717ULL) >> 11) * (1.0 / 9007199254740992.0);
  }
  double range(double a, double b) { return a + (b - a) * uniform(); }
  glm::vec3 unit() {
    for (;;) {
      glm::vec3 v(range(-1, 1), range(-1, 1), range(-1, 1));
      float l = glm::length(v);
      if (l > 0.05f && l <= 1.0f) return v / l;
    }
  }
  double normal() {
    double u = std::max(uniform(), 1e-12), v = uniform();
    return std::sqrt(-2.0 * std::log(u)) * std::cos(6.283185307179586 * v);
  }
};

// A fully saturated hue, h in [0, 1) around the colour wheel.
inline glm::vec3 hue(double h) {
  h = h - std::floor(h);
  glm::vec3 c(std::abs(h * 6 - 3) - 1, 2 - std::abs(h * 6 - 2), 2 - std::abs(h * 6 - 4));
  return glm::clamp(c, 0.0f, 1.0f);
}

}  // namespace oitbench::oit
