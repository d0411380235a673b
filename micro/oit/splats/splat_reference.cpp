#include "oit/splats/splat_reference.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <thread>

namespace oitbench::oit {

namespace {

constexpr int kTile = 16;
constexpr double kMinAlpha = 1.0 / 255.0;

// What packUnorm4x8 keeps of a channel (the capture's RGBA8 fragment format).
double unorm8(double v) { return std::round(std::clamp(v, 0.0, 1.0) * 255.0) / 255.0; }

struct Fragment {
  double key;
  std::uint32_t splat;
  double alpha;
};

// The tiles [x0, x1) x [y0, y1) a projection's quad touches (empty when it misses the image).
struct TileRect {
  int x0, y0, x1, y1;
};
TileRect tiles_of(const SplatProjection& p, const SplatCamera& c) {
  const int tiles_x = (c.width + kTile - 1) / kTile, tiles_y = (c.height + kTile - 1) / kTile;
  auto clamp_tile = [](double v, int n) { return static_cast<int>(std::clamp(std::floor(v / kTile), 0.0, double(n))); };
  TileRect r{clamp_tile(p.mean.x - p.radius, tiles_x), clamp_tile(p.mean.y - p.radius, tiles_y),
             clamp_tile(p.mean.x + p.radius, tiles_x - 1) + 1, clamp_tile(p.mean.y + p.radius, tiles_y - 1) + 1};
  if (p.mean.x + p.radius <= 0 || p.mean.y + p.radius <= 0 || p.mean.x - p.radius >= c.width ||
      p.mean.y - p.radius >= c.height)
    r.x1 = r.x0;  // off the image
  return r;
}

// Each tile's splats in index order (a CSR table: first[t] .. first[t + 1] in `splats`).
struct TileBins {
  std::vector<std::size_t> first;
  std::vector<std::uint32_t> splats;
};
TileBins bin_tiles(const std::vector<std::optional<SplatProjection>>& proj, const SplatCamera& c) {
  const int tiles_x = (c.width + kTile - 1) / kTile, tiles_y = (c.height + kTile - 1) / kTile;
  TileBins b;
  b.first.assign(static_cast<size_t>(tiles_x) * tiles_y + 1, 0);
  auto each = [&](auto&& visit) {
    for (std::uint32_t i = 0; i < proj.size(); ++i) {
      if (!proj[i]) continue;
      const TileRect r = tiles_of(*proj[i], c);
      for (int ty = r.y0; ty < r.y1; ++ty)
        for (int tx = r.x0; tx < r.x1; ++tx) visit(static_cast<size_t>(ty) * tiles_x + tx, i);
    }
  };
  each([&](size_t t, std::uint32_t) { ++b.first[t + 1]; });
  for (size_t t = 1; t < b.first.size(); ++t) b.first[t] += b.first[t - 1];
  b.splats.resize(b.first.back());
  std::vector<size_t> fill(b.first.begin(), b.first.end() - 1);
  each([&](size_t t, std::uint32_t i) { b.splats[fill[t]++] = i; });
  return b;
}

// One tile: its pixels' fragments gathered, sorted and composited into `out`.
void composite_tile(int tx, int ty, const std::uint32_t* first, const std::uint32_t* last,
                    const std::vector<std::optional<SplatProjection>>& proj, const SplatCamera& c,
                    const SplatReferenceOptions& o, std::vector<std::vector<Fragment>>& lists, SplatImage& out) {
  const int x0 = tx * kTile, y0 = ty * kTile, x1 = std::min(x0 + kTile, c.width), y1 = std::min(y0 + kTile, c.height);
  for (auto& l : lists) l.clear();
  for (const std::uint32_t* s = first; s != last; ++s) {
    const SplatProjection& p = *proj[*s];
    const int px0 = std::max(x0, static_cast<int>(std::floor(p.mean.x - p.radius))),
              px1 = std::min(x1, static_cast<int>(std::ceil(p.mean.x + p.radius)) + 1),
              py0 = std::max(y0, static_cast<int>(std::floor(p.mean.y - p.radius))),
              py1 = std::min(y1, static_cast<int>(std::ceil(p.mean.y + p.radius)) + 1);
    for (int y = py0; y < py1; ++y)
      for (int x = px0; x < px1; ++x) {
        const glm::dvec2 centre(x + 0.5, y + 0.5);
        const double alpha = splat_alpha(p, centre);
        if (alpha == 0) continue;
        const double key = o.order == SplatOrder::Centre ? p.centre_depth : ray_max_depth(p, centre, c);
        lists[static_cast<size_t>(y - y0) * kTile + (x - x0)].push_back({key, *s, alpha});
      }
  }
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      auto& l = lists[static_cast<size_t>(y - y0) * kTile + (x - x0)];
      std::sort(l.begin(), l.end(), [](const Fragment& a, const Fragment& b) {
        return a.key < b.key || (a.key == b.key && a.splat < b.splat);
      });
      glm::dvec3 colour(0.0), before_c(0.0);
      double t = 1.0, before_t = 0.0, before_a = 0.0;
      bool tie = false;
      double slack = 0;
      for (size_t i = 0; i < l.size(); ++i) {
        const Fragment& f = l[i];
        const double alpha = o.quantise_rgba8 ? unorm8(f.alpha) : f.alpha;
        const glm::dvec3 raw = proj[f.splat]->colour;
        const glm::dvec3 c = o.quantise_rgba8 ? glm::dvec3(unorm8(raw.r), unorm8(raw.g), unorm8(raw.b)) : raw;
        const double next = t * (1.0 - alpha);
        if (o.min_transmittance > 0 && next < o.min_transmittance) break;
        // swapping two neighbours moves the pixel by T a_i a_j (c_i - c_j)
        const glm::dvec3 swap = glm::abs(before_c - c) * (before_t * before_a * alpha);
        if (i > 0 && f.key - l[i - 1].key <= kSplatKeyTie * std::abs(f.key) &&
            std::max({swap.r, swap.g, swap.b}) > kSplatTieEffect) {
          tie = true;
          slack += std::max({swap.r, swap.g, swap.b});
        }
        colour += t * alpha * c;
        before_c = c;
        before_t = t;
        before_a = alpha;
        t = next;
      }
      const size_t at = static_cast<size_t>(y) * c.width + x;
      out.rgba[at] = glm::dvec4(colour + t * o.background, 1.0 - t);
      out.fragments[at] = static_cast<std::uint32_t>(l.size());
      out.tied[at] = tie;
      out.tie_slack[at] = static_cast<float>(slack);
    }
}

}  // namespace

SplatCamera splat_camera(const View& view, int width, int height, double near_plane, double far_plane) {
  const glm::dmat4 m = glm::lookAt(glm::dvec3(view.eye), glm::dvec3(view.target), glm::dvec3(view.up));
  SplatCamera c;
  c.rotation = glm::dmat3(m);
  c.translation = glm::dvec3(m[3]);
  c.width = width;
  c.height = height;
  c.tan_fovy = std::tan(glm::radians(static_cast<double>(view.fov_deg)) / 2);
  c.tan_fovx = c.tan_fovy * width / height;
  c.fy = height / (2 * c.tan_fovy);
  c.fx = width / (2 * c.tan_fovx);
  c.cx = width / 2.0;
  c.cy = height / 2.0;
  c.near_plane = near_plane;
  c.far_plane = far_plane;
  return c;
}

std::optional<SplatProjection> project_splat(const Splat& s, const SplatCamera& c) {
  SplatProjection p;
  p.view_centre = c.rotation * glm::dvec3(s.position) + c.translation;
  const double t = -p.view_centre.z;
  if (!(t > c.near_plane) || t > c.far_plane) return std::nullopt;
  p.centre_depth = t;
  p.mean = glm::dvec2(c.cx + c.fx * p.view_centre.x / t, c.cy + c.fy * p.view_centre.y / t);
  const glm::dquat q(s.rotation.w, s.rotation.x, s.rotation.y, s.rotation.z);
  const glm::dmat3 r = glm::mat3_cast(q);
  const glm::dvec3 sd = glm::max(glm::dvec3(s.scale), glm::dvec3(1e-30));
  const glm::dmat3 rv = c.rotation * r;  // the splat's axes in view space
  const glm::dmat3 cov = rv * glm::dmat3(sd.x * sd.x, 0, 0, 0, sd.y * sd.y, 0, 0, 0, sd.z * sd.z) * glm::transpose(rv);
  p.inv_cov =
      rv * glm::dmat3(1 / (sd.x * sd.x), 0, 0, 0, 1 / (sd.y * sd.y), 0, 0, 0, 1 / (sd.z * sd.z)) * glm::transpose(rv);
  p.inv_cov_centre = p.inv_cov * p.view_centre;
  const double lim_x = 1.3 * c.tan_fovx, lim_y = 1.3 * c.tan_fovy;
  const double x = std::clamp(p.view_centre.x / t, -lim_x, lim_x) * t;
  const double y = std::clamp(p.view_centre.y / t, -lim_y, lim_y) * t;
  // J's rows (glm is column-major: j[col][row]); the third row is zero.
  glm::dmat3 j(0.0);
  j[0][0] = c.fx / t;
  j[2][0] = c.fx * x / (t * t);
  j[1][1] = c.fy / t;
  j[2][1] = c.fy * y / (t * t);
  const glm::dmat3 cov2 = j * cov * glm::transpose(j);
  const double a = cov2[0][0] + 0.3, b = cov2[1][0], d = cov2[1][1] + 0.3;
  const double det = a * d - b * b;
  if (!(det > 0)) return std::nullopt;
  p.conic = glm::dvec3(d / det, -b / det, a / det);
  const double mid = 0.5 * (a + d);
  const double lambda = mid + std::sqrt(std::max(0.0, 0.25 * (a - d) * (a - d) + b * b));
  p.radius = static_cast<int>(std::ceil(3.0 * std::sqrt(lambda)));
  p.opacity = s.opacity;
  p.colour = glm::dvec3(s.colour);
  return p;
}

double splat_alpha(const SplatProjection& p, glm::dvec2 pixel) {
  const glm::dvec2 d = pixel - p.mean;
  if (!(std::abs(d.x) < p.radius && std::abs(d.y) < p.radius)) return 0;
  const double power = -0.5 * (p.conic.x * d.x * d.x + p.conic.z * d.y * d.y) - p.conic.y * d.x * d.y;
  if (power > 0) return 0;
  const double alpha = std::min(0.99, p.opacity * std::exp(power));
  return alpha < kMinAlpha ? 0 : alpha;
}

double ray_max_depth(const SplatProjection& p, glm::dvec2 pixel, const SplatCamera& c) {
  const glm::dvec3 v((pixel.x - c.cx) / c.fx, (pixel.y - c.cy) / c.fy, -1.0);
  return glm::dot(v, p.inv_cov_centre) / glm::dot(v, p.inv_cov * v);
}

SplatImage splat_reference(const SplatList& splats, const SplatCamera& c, const SplatReferenceOptions& o) {
  std::vector<std::optional<SplatProjection>> proj(splats.size());
  for (size_t i = 0; i < splats.size(); ++i) proj[i] = project_splat(splats[i], c);
  const TileBins bins = bin_tiles(proj, c);
  SplatImage out;
  out.width = c.width;
  out.height = c.height;
  out.rgba.assign(static_cast<size_t>(c.width) * c.height, glm::dvec4(o.background, 0.0));
  out.fragments.assign(out.rgba.size(), 0);
  out.tied.assign(out.rgba.size(), 0);
  out.tie_slack.assign(out.rgba.size(), 0.0f);
  // Tiles are independent (each writes its own pixels): workers take them in turn, each with its own
  // lists, and the image is the same whatever the number of workers.
  const int tiles_x = (c.width + kTile - 1) / kTile, tiles_y = (c.height + kTile - 1) / kTile;
  const size_t tiles = static_cast<size_t>(tiles_x) * tiles_y;
  std::atomic<size_t> next{0};
  auto work = [&] {
    std::vector<std::vector<Fragment>> lists(kTile * kTile);
    for (size_t t = next++; t < tiles; t = next++)
      composite_tile(static_cast<int>(t % tiles_x), static_cast<int>(t / tiles_x), bins.splats.data() + bins.first[t],
                     bins.splats.data() + bins.first[t + 1], proj, c, o, lists, out);
  };
  const size_t workers = std::clamp<size_t>(o.threads ? o.threads : std::thread::hardware_concurrency(), 1, tiles);
  std::vector<std::thread> pool;
  for (size_t w = 1; w < workers; ++w) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  return out;
}

}  // namespace oitbench::oit
