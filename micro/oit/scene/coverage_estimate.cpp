#include "oit/scene/coverage_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>
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

// One splat's fragments as the splat rasteriser makes them (splat_reference.hpp's projection): the 2D
// covariance from the perspective's Jacobian at its centre (taken from view_proj, without 3DGS's 1.3
// clamp) plus the 0.3-pixel low-pass; its fragments are the pixels where opacity exp(-d'conic d / 2) >=
// 1/255, an ellipse of area pi q sqrt(det cov2) with q = 2 ln(255 opacity), at most the 3-sigma quad, and
// the quad's share that lies on the screen.
double splat_fragments(const Splat& s, const glm::mat4& vp, int width, int height) {
  const glm::dvec4 c = glm::dmat4(vp) * glm::dvec4(glm::dvec3(s.position), 1.0);
  if (!(c.w > 0) || c.z < -c.w || c.z > c.w || s.opacity * 255.0f <= 1.0f) return 0;
  // d(pixel)/d(world): rows of view_proj over w, less the perspective division's term.
  glm::dmat3 j(0.0);  // column-major: j[col][row]; the third row stays zero
  const double half[2] = {0.5 * width, 0.5 * height};
  for (int r = 0; r < 2; ++r)
    for (int k = 0; k < 3; ++k) j[k][r] = half[r] * (vp[k][r] * c.w - c[r] * vp[k][3]) / (c.w * c.w);
  const glm::dmat3 rot = glm::mat3_cast(glm::dquat(s.rotation.w, s.rotation.x, s.rotation.y, s.rotation.z));
  const glm::dvec3 sd(s.scale);
  const glm::dmat3 cov =
      rot * glm::dmat3(sd.x * sd.x, 0, 0, 0, sd.y * sd.y, 0, 0, 0, sd.z * sd.z) * glm::transpose(rot);
  const glm::dmat3 cov2 = j * cov * glm::transpose(j);
  const double a = cov2[0][0] + 0.3, b = cov2[1][0], d = cov2[1][1] + 0.3;
  const double lambda = 0.5 * (a + d) + std::sqrt(std::max(0.0, 0.25 * (a - d) * (a - d) + b * b));
  const double radius = std::ceil(3.0 * std::sqrt(lambda));
  const double q = 2.0 * std::log(255.0 * s.opacity);
  const double ellipse = 3.14159265358979 * q * std::sqrt(std::max(0.0, a * d - b * b));
  const double mx = (c.x / c.w * 0.5 + 0.5) * width, my = (c.y / c.w * 0.5 + 0.5) * height;
  const double on_x = std::clamp(std::min(mx + radius, double(width)) - std::max(mx - radius, 0.0), 0.0, 2 * radius);
  const double on_y = std::clamp(std::min(my + radius, double(height)) - std::max(my - radius, 0.0), 0.0, 2 * radius);
  return std::min(ellipse, 4 * radius * radius) * (on_x * on_y) / (4 * radius * radius);
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
  for (const Splat& s : mesh.splats) fragments += splat_fragments(s, view_proj, width, height);
  return fragments;
}

MemoryNeed scene_held_memory(const Mesh& mesh) {
  MemoryNeed held;
  const unsigned long long splats = mesh.splats.size();
  if (!splats) return held;
  held.cpu_bytes = splats * sizeof(Splat);
  held.cpu_what = "the scene's splats (" + format_count(splats) + " x " + std::to_string(sizeof(Splat)) + " B)";
  held.gpu_bytes = splats * kGpuSplatBytes;
  held.gpu_what = "the splats' GPU copy (" + format_count(splats) + " x " + std::to_string(kGpuSplatBytes) + " B)";
  return held;
}

MemoryNeed splat_scene_memory(double splats) {
  MemoryNeed need;
  const auto n = static_cast<unsigned long long>(splats);
  // build_mesh's list, its reordered copy, a distance and an index per splat; the GPU buffer and its staging copy.
  const unsigned long long building = 2 * sizeof(Splat) + sizeof(float) + sizeof(size_t);
  need.cpu_bytes = n * building;
  need.cpu_what = "building the scene's splats (" + format_count(n) + " x " + std::to_string(building) + " B)";
  need.gpu_bytes = n * 2 * kGpuSplatBytes;
  need.gpu_what = "uploading them (" + format_count(n) + " x " + std::to_string(2 * kGpuSplatBytes) + " B)";
  return need;
}

}  // namespace oitbench::oit
