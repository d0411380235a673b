#include "oit/splats/splat_scene.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "oit/scene/generator_support.hpp"

namespace oitbench::oit {

// The numeric parameters read by name, each left at its default when the object does not name it
// (nlohmann's reader: one value(key, default) a member). The offset, a vector, is read below.
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(SplatGeneratorParams, count, clusters, half_size, depth, spread,
                                                scale_min, scale_max, anisotropy, opacity_min, opacity_max,
                                                opacity_shape, colour_mix, seed)

SplatGeneratorParams splat_generator_params(const nlohmann::json& p) {
  SplatGeneratorParams s = p.get<SplatGeneratorParams>();
  if (p.contains("offset"))
    for (int k = 0; k < 3; ++k) s.offset[k] = p["offset"][k].get<float>();
  return s;
}

std::optional<std::pair<std::string, std::string>> splat_params_problem(const nlohmann::json& p) {
  const SplatGeneratorParams s = splat_generator_params(p);
  if (s.clusters < 1) return std::pair<std::string, std::string>{"clusters", "expected at least 1 cluster"};
  if (s.scale_min > s.scale_max)
    return std::pair<std::string, std::string>{"scale_min", "scale_min is above scale_max"};
  if (s.anisotropy < 1)
    return std::pair<std::string, std::string>{"anisotropy",
                                               "expected 1 or more (the largest standard deviation over the smallest)"};
  if (s.opacity_min > s.opacity_max)
    return std::pair<std::string, std::string>{"opacity_min", "opacity_min is above opacity_max"};
  if (s.opacity_max > 1) return std::pair<std::string, std::string>{"opacity_max", "expected an opacity in [0, 1]"};
  if (s.opacity_shape <= 0) return std::pair<std::string, std::string>{"opacity_shape", "expected an exponent above 0"};
  return std::nullopt;
}

namespace {

// A rotation uniform over the sphere of unit quaternions (four normal deviates, normalised).
glm::quat random_rotation(Rng& rng) {
  for (;;) {
    glm::dvec4 q(rng.normal(), rng.normal(), rng.normal(), rng.normal());
    const double l = glm::length(q);
    if (l > 1e-6)
      return glm::quat(static_cast<float>(q.x / l), static_cast<float>(q.y / l), static_cast<float>(q.z / l),
                       static_cast<float>(q.w / l));
  }
}

}  // namespace

SplatList generate_splats(const SplatGeneratorParams& p, const Material& m) {
  const size_t count = static_cast<size_t>(p.count), clusters = std::max<size_t>(1, static_cast<size_t>(p.clusters));
  Rng rng(static_cast<unsigned long long>(p.seed));
  SplatList out;
  out.reserve(count);
  const double log_lo = std::log(p.scale_min), log_hi = std::log(p.scale_max);
  for (size_t c = 0; c < clusters; ++c) {
    const glm::vec3 centre = p.offset + glm::vec3(rng.range(-p.half_size, p.half_size),
                                                  rng.range(-p.half_size, p.half_size), rng.range(-0.5, 0.5) * p.depth);
    const glm::vec3 colour = glm::mix(m.colour, hue(rng.uniform()), static_cast<float>(p.colour_mix));
    // Cluster c holds splats [c * count / clusters, (c + 1) * count / clusters).
    const size_t end = (c + 1) * count / clusters;
    while (out.size() < end) {
      Splat s;
      s.position = centre + glm::vec3(rng.normal(), rng.normal(), rng.normal()) * static_cast<float>(p.spread);
      const double largest = std::exp(rng.range(log_lo, log_hi)), smallest = largest / p.anisotropy;
      const double middle = std::exp(rng.range(std::log(smallest), std::log(largest)));
      s.scale = glm::vec3(largest, middle, smallest);
      s.rotation = random_rotation(rng);
      s.opacity = static_cast<float>(p.opacity_min +
                                     (p.opacity_max - p.opacity_min) * std::pow(rng.uniform(), p.opacity_shape));
      s.colour = glm::clamp(colour * static_cast<float>(0.85 + 0.15 * rng.range(-1, 1)), 0.0f, 1.0f);
      out.push_back(s);
    }
  }
  return out;
}

void order_splats(SplatList& splats, const View& view) {
  if (view.order == SubmitOrder::AsGenerated) return;
  std::vector<float> dist(splats.size());
  for (size_t i = 0; i < splats.size(); ++i) dist[i] = glm::length(splats[i].position - view.eye);
  std::vector<size_t> order(splats.size());
  std::iota(order.begin(), order.end(), size_t{0});
  const bool front_to_back = view.order == SubmitOrder::FrontToBack;
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return front_to_back ? dist[a] < dist[b] : dist[a] > dist[b]; });
  SplatList sorted;
  sorted.reserve(splats.size());
  for (size_t i : order) sorted.push_back(splats[i]);
  splats = std::move(sorted);
}

}  // namespace oitbench::oit
