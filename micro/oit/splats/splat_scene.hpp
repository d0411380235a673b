#pragma once
// The "splats" scene generator: clusters of anisotropic Gaussians, deterministic (the scenes' own
// generator, oit/scene/generator_support.hpp), with the count, the number of clusters, their extent
// along z (the depth a view along z sees), the anisotropy, the scales and the opacity distribution as
// parameters. scenes/README.md lists them; build_mesh() (scene.cpp) calls it for a "splats" object.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "oit/scene/scene.hpp"
#include "oit/splats/splat.hpp"

namespace oitbench::oit {

// The generator's parameters, defaults filled in (the scene parser has checked each one's range).
struct SplatGeneratorParams {
  double count = 100000;       // splats
  double clusters = 16;        // clusters, generated one after the other
  double half_size = 1.0;      // cluster centres lie in [-half_size, half_size] in x and y
  double depth = 1.0;          // and in [-depth/2, depth/2] in z (around offset)
  double spread = 0.2;         // a splat's distance from its cluster's centre: normal, this deviation per axis
  double scale_min = 0.005;    // a splat's largest standard deviation: log-uniform in [scale_min, scale_max]
  double scale_max = 0.03;     //
  double anisotropy = 4.0;     // largest over smallest standard deviation (1: spheres)
  double opacity_min = 0.05;   // opacity = min + (max - min) * u^shape, u uniform in [0, 1)
  double opacity_max = 0.95;   //
  double opacity_shape = 1.0;  // above 1 favours faint splats, below 1 dense ones
  double colour_mix = 0.7;     // the cluster's hue's share against the material's colour
  double seed = 1;
  glm::vec3 offset{0.0f};
};
SplatGeneratorParams splat_generator_params(const nlohmann::json& p);

// What is wrong with a "splats" object's parameters taken together (scale_min above scale_max, ...):
// the key to blame and the message, or nothing.
std::optional<std::pair<std::string, std::string>> splat_params_problem(const nlohmann::json& p);

// The splats, cluster by cluster (their generation order); colours do not depend on the view.
SplatList generate_splats(const SplatGeneratorParams& p, const Material& m);

// Orders a list by the splat centres' distance to the eye (stable: ties keep their order), as a view's
// "order" orders every other primitive.
void order_splats(SplatList& splats, const View& view);

}  // namespace oitbench::oit
