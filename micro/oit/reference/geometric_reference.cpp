#include "oit/reference/geometric_reference.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>

#include "core/parallel_rows.hpp"
#include "oit/capture/packed_fragment.hpp"

namespace oitbench::oit {

namespace {

// The words equal depths are ordered by, as node_tie_key() reads them from a stored node.
std::array<unsigned, 4> tie_key(glm::vec4 c, FragColour format) {
  if (format == FragColour::RGBA8) {
    unsigned packed = 0;
    for (int k = 0; k < 4; ++k)
      packed |= static_cast<unsigned>(std::lround(std::clamp(c[k], 0.0f, 1.0f) * 255.0f)) << (8 * k);
    return {packed, 0, 0, 0};
  }
  if (format == FragColour::RGBA16F) {
    auto pair = [&](int a, int b) {
      return static_cast<unsigned>(float_to_half(c[a])) | (static_cast<unsigned>(float_to_half(c[b])) << 16);
    };
    return {pair(2, 3), pair(0, 1), 0, 0};
  }
  return {std::bit_cast<unsigned>(c.a), std::bit_cast<unsigned>(c.b), std::bit_cast<unsigned>(c.g),
          std::bit_cast<unsigned>(c.r)};
}

struct Hit {
  double t;
  std::array<unsigned, 4> key;
  glm::dvec4 exact, quantised;
};

}  // namespace

glm::dvec4 quantise_colour(glm::vec4 c, FragColour format) {
  glm::dvec4 q;
  for (int k = 0; k < 4; ++k) {
    if (format == FragColour::RGBA8)
      q[k] = std::lround(std::clamp(c[k], 0.0f, 1.0f) * 255.0f) / 255.0;
    else if (format == FragColour::RGBA16F)
      q[k] = half_to_float(float_to_half(c[k]));
    else
      q[k] = c[k];
  }
  return q;
}

std::optional<GeometricReference> geometric_reference(const SceneDesc& scene, const View& view, Detail detail,
                                                      glm::vec2 near_far, int width, int height, FragColour format) {
  auto planes = analytic_planes(scene, detail);
  if (!planes) return std::nullopt;
  GeometricReference r;
  r.width = width;
  r.height = height;
  const size_t pixels = static_cast<size_t>(width) * height;
  r.exact.assign(pixels * 3, 0.0);
  r.quantised.assign(pixels * 3, 0.0);
  r.layers.assign(pixels, 0);
  r.ambiguous.assign(pixels, false);
  // The camera in double: a ray through each pixel centre, parametrised by its distance t along the
  // view axis (what clip w, and so the near/far clipping, measures).
  const glm::dvec3 eye(view.eye), forward = glm::normalize(glm::dvec3(view.target) - eye);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(view.up)));
  const glm::dvec3 up = glm::cross(right, forward);
  const double tan_half = std::tan(static_cast<double>(view.fov_deg) * 3.14159265358979323846 / 360.0);
  const double aspect = static_cast<double>(width) / height;
  const double near_plane = near_far.x, far_plane = near_far.y;
  const glm::dvec3 bg(scene.background);
  // Rows over the cores (pixels are independent); each thread its own hits and counts, and the
  // ambiguity flags in bytes (vector<bool>'s bits would share words across threads).
  struct Scratch {
    std::vector<Hit> hits;
    size_t coplanar = 0, ambiguous = 0;
  };
  const size_t row = static_cast<size_t>(std::max(1, width));
  std::vector<Scratch> scratch(parallel_row_threads(static_cast<size_t>(std::max(0, height))));
  std::vector<char> ambiguous_flags(pixels, 0);
  parallel_rows(pixels, row, 0, [&](unsigned thread, size_t p) {
    const int x = static_cast<int>(p % row), y = static_cast<int>(p / row);
    std::vector<Hit>& hits = scratch[thread].hits;
    const double nx = (x + 0.5) / width * 2 - 1, ny = (y + 0.5) / height * 2 - 1;
    const glm::dvec3 dir = forward + right * (nx * tan_half * aspect) + up * (ny * tan_half);
    const double pixel_world = 2 * tan_half / height;  // a pixel's size per unit of t
    hits.clear();
    bool ambiguous = false;
    for (const AnalyticPlane& pl : *planes) {
      if (std::abs(dir.z) < 1e-300) continue;  // a plane seen edge-on covers no pixel centre
      const double t = (pl.centre.z - eye.z) / dir.z;
      if (t <= 0) continue;
      const glm::dvec3 hit = eye + dir * t;
      const double edge = std::max(std::abs(hit.x - pl.centre.x), std::abs(hit.y - pl.centre.y)) - pl.half_size;
      const double slack = t * pixel_world / 256.0;
      const bool near_edge = std::abs(edge) <= slack,
                 clip_edge = std::abs(t - near_plane) <= 1e-5 * t || std::abs(t - far_plane) <= 1e-5 * t;
      if (near_edge || (edge < 0 && clip_edge)) ambiguous = true;
      if (edge >= 0 || t < near_plane || t > far_plane) continue;
      hits.push_back({t, tie_key(pl.colour, format), glm::dvec4(pl.colour), quantise_colour(pl.colour, format)});
    }
    // Near to far; equal depths by the tie key, smaller nearer (the resolves' FRAG_FARTHER).
    std::sort(hits.begin(), hits.end(),
              [](const Hit& a, const Hit& b) { return a.t != b.t ? a.t < b.t : a.key < b.key; });
    for (size_t i = 1; i < hits.size(); ++i)
      if (hits[i].t == hits[i - 1].t) {
        ++scratch[thread].coplanar;
        break;
      }
    glm::dvec3 ce(0), cq(0);
    double te = 1, tq = 1;
    for (const Hit& h : hits) {
      ce += te * h.exact.a * glm::dvec3(h.exact);
      te *= 1 - h.exact.a;
      cq += tq * h.quantised.a * glm::dvec3(h.quantised);
      tq *= 1 - h.quantised.a;
    }
    ce += te * bg;
    cq += tq * bg;
    for (int k = 0; k < 3; ++k) {
      r.exact[p * 3 + k] = ce[k];
      r.quantised[p * 3 + k] = cq[k];
    }
    r.layers[p] = static_cast<unsigned>(hits.size());
    ambiguous_flags[p] = ambiguous;
    scratch[thread].ambiguous += ambiguous;
  });
  for (size_t p = 0; p < pixels; ++p) r.ambiguous[p] = ambiguous_flags[p] != 0;
  for (const Scratch& sc : scratch) {
    r.coplanar_pixels += sc.coplanar;
    r.ambiguous_pixels += sc.ambiguous;
  }
  return r;
}

std::string geometric_reference_key(const SceneDesc& scene, const View& view, Detail detail, glm::vec2 near_far,
                                    int width, int height, FragColour format) {
  auto planes = analytic_planes(scene, detail);
  if (!planes) return {};
  std::string key;
  char buf[64];
  auto num = [&](double v) {
    std::snprintf(buf, sizeof buf, "%a ", v);
    key += buf;
  };
  key += std::to_string(width) + "x" + std::to_string(height) + " format " + std::to_string(static_cast<int>(format)) +
         " near/far ";
  num(near_far.x);
  num(near_far.y);
  key += "eye ";
  for (int k = 0; k < 3; ++k) num(view.eye[k]);
  key += "target ";
  for (int k = 0; k < 3; ++k) num(view.target[k]);
  key += "up ";
  for (int k = 0; k < 3; ++k) num(view.up[k]);
  key += "fov ";
  num(view.fov_deg);
  key += "background ";
  for (int k = 0; k < 3; ++k) num(scene.background[k]);
  key += "planes " + std::to_string(planes->size()) + ":";
  for (const AnalyticPlane& pl : *planes) {
    for (int k = 0; k < 3; ++k) num(pl.centre[k]);
    num(pl.half_size);
    for (int k = 0; k < 4; ++k) num(pl.colour[k]);
    key += ';';
  }
  return key;
}

std::shared_ptr<const GeometricReference> shared_geometric_reference(SharedCache* cache, const SceneDesc& scene,
                                                                     const View& view, Detail detail,
                                                                     glm::vec2 near_far, int width, int height,
                                                                     FragColour format) {
  auto make = [&]() -> std::shared_ptr<const GeometricReference> {
    auto r = geometric_reference(scene, view, detail, near_far, width, height, format);
    return r ? std::make_shared<const GeometricReference>(std::move(*r)) : nullptr;
  };
  if (!cache) return make();
  const std::string key = geometric_reference_key(scene, view, detail, near_far, width, height, format);
  if (key.empty()) return nullptr;  // not analytic
  // A few kept up to 1024x1024 (a reference is ~57 bytes a pixel, and a preset's requests come back to a
  // view), one above.
  return cache->get<GeometricReference>(key, make, static_cast<size_t>(width) * height <= 1024 * 1024 ? 4 : 1);
}

GeometricCheck check_against_geometry(const GeometricReference& ref, const std::vector<float>& rgba,
                                      const std::vector<unsigned>& captured_depth, glm::vec3 background,
                                      double tolerance) {
  GeometricCheck c;
  double sum = 0;
  size_t counted = 0;
  const size_t pixels = ref.layers.size();
  for (size_t p = 0; p < pixels; ++p) {
    if (ref.ambiguous[p]) continue;
    const float* g = &rgba[p * 4];
    const glm::dvec3 got = g[3] == 0.0f ? glm::dvec3(background) : glm::dvec3(g[0], g[1], g[2]);
    double worst_q = 0;
    for (int k = 0; k < 3; ++k) {
      double de = std::abs(got[k] - ref.exact[p * 3 + k]), dq = std::abs(got[k] - ref.quantised[p * 3 + k]);
      if (std::isnan(de)) de = 1.0;
      if (std::isnan(dq)) dq = std::numeric_limits<double>::infinity();
      sum += de * de;
      c.truth_max_abs_error = std::max(c.truth_max_abs_error, de);
      worst_q = std::max(worst_q, dq);
    }
    ++counted;
    const int x = static_cast<int>(p % ref.width), y = static_cast<int>(p / ref.width);
    if (worst_q > tolerance && c.bad_pixels++ == 0) {
      char buf[240];
      std::snprintf(buf, sizeof buf, "pixel (%d,%d): got (%.6f,%.6f,%.6f), geometry (%.6f,%.6f,%.6f)", x, y, got[0],
                    got[1], got[2], ref.quantised[p * 3], ref.quantised[p * 3 + 1], ref.quantised[p * 3 + 2]);
      c.first_bad = buf;
    }
    if (p < captured_depth.size() && captured_depth[p] != ref.layers[p] && c.layer_mismatches++ == 0)
      c.first_layer_mismatch = "pixel (" + std::to_string(x) + "," + std::to_string(y) + ") holds " +
                               std::to_string(captured_depth[p]) + " fragment(s), the geometry " +
                               std::to_string(ref.layers[p]);
  }
  c.truth_rmse = counted ? std::sqrt(sum / (counted * 3.0)) : 0.0;
  return c;
}

}  // namespace oitbench::oit
