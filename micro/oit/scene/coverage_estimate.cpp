#include "oit/scene/coverage_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace oitbench::oit {

namespace {

// Clips a convex polygon in clip space to the half-space dot(plane, v) >= 0 (Sutherland-Hodgman).
void clip(std::vector<glm::vec4>& poly, const glm::vec4& plane, std::vector<glm::vec4>& scratch) {
  scratch.clear();
  for (size_t i = 0; i < poly.size(); ++i) {
    const glm::vec4 a = poly[i], b = poly[(i + 1) % poly.size()];
    const float da = glm::dot(plane, a), db = glm::dot(plane, b);
    if (da >= 0) scratch.push_back(a);
    if ((da >= 0) != (db >= 0)) scratch.push_back(a + (b - a) * (da / (da - db)));
  }
  poly.swap(scratch);
}

// The frustum's six planes in clip space: -w <= x, y, z <= w.
const glm::vec4 kFrustum[6] = {{1, 0, 0, 1}, {-1, 0, 0, 1}, {0, 1, 0, 1}, {0, -1, 0, 1}, {0, 0, 1, 1}, {0, 0, -1, 1}};

// The clipped polygon's vertices in pixels.
void to_pixels(std::vector<glm::vec4>& poly, int width, int height) {
  for (auto& v : poly) v = {(v.x / v.w * 0.5f + 0.5f) * width, (v.y / v.w * 0.5f + 0.5f) * height, 0, 1};
}

double polygon_area(std::vector<glm::vec4>& poly, std::vector<glm::vec4>& scratch, int width, int height) {
  for (const auto& plane : kFrustum) {
    if (poly.size() < 3) return 0;
    clip(poly, plane, scratch);
  }
  if (poly.size() < 3) return 0;
  to_pixels(poly, width, height);
  double twice = 0;
  for (size_t i = 0; i < poly.size(); ++i) {
    const glm::vec4 a = poly[i], b = poly[(i + 1) % poly.size()];
    twice += static_cast<double>(a.x) * b.y - static_cast<double>(b.x) * a.y;
  }
  return std::abs(twice) / 2;
}

double segment_length(std::vector<glm::vec4>& seg, std::vector<glm::vec4>& scratch, int width, int height) {
  for (const auto& plane : kFrustum) {
    // A segment as a two-vertex polygon: clipping it keeps the part inside (its closing edge is itself).
    clip(seg, plane, scratch);
    if (seg.size() < 2) return 0;
  }
  to_pixels(seg, width, height);
  double longest = 0;
  for (size_t i = 0; i + 1 < seg.size(); ++i)
    longest = std::max(
        longest, static_cast<double>(std::max(std::abs(seg[i + 1].x - seg[i].x), std::abs(seg[i + 1].y - seg[i].y))));
  return longest;
}

}  // namespace

double estimate_fragments(const Mesh& mesh, const glm::mat4& view_proj, int width, int height) {
  std::vector<glm::vec4> poly, scratch;
  poly.reserve(9);
  scratch.reserve(9);
  auto clip_space = [&](unsigned index) { return view_proj * glm::vec4(mesh.vertices.at(index).position, 1.0f); };
  double fragments = 0;
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    poly.assign({clip_space(mesh.indices[t]), clip_space(mesh.indices[t + 1]), clip_space(mesh.indices[t + 2])});
    fragments += polygon_area(poly, scratch, width, height);
  }
  for (size_t s = 0; s + 1 < mesh.line_indices.size(); s += 2) {
    poly.assign({clip_space(mesh.line_indices[s]), clip_space(mesh.line_indices[s + 1])});
    fragments += segment_length(poly, scratch, width, height);
  }
  return fragments;
}

}  // namespace oitbench::oit
