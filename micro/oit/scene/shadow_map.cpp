#include "oit/scene/shadow_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <numeric>
#include <sstream>

#include "gl/render_target.hpp"
#include "oit/capture/fragment_lists.hpp"
#include "oit/case_support.hpp"
#include "oit/scene/gpu_mesh.hpp"
#include "oit/scene/radix_sort.hpp"
#include "shaders/lines/bindings.h"
#include "shaders/shadow/bindings.h"

namespace oitbench::oit {

namespace {

static_assert(sizeof(Vertex) % sizeof(float) == 0 && offsetof(Vertex, position) == 0,
              "slice_keys.comp reads oit::Vertex as floats, position first");
constexpr int kVertexFloats = static_cast<int>(sizeof(Vertex) / sizeof(float));

gl::Buffer make_storage(GLsizeiptr bytes, const void* data = nullptr) {
  gl::Buffer b = gl::make_buffer();
  glNamedBufferStorage(b.get(), std::max<GLsizeiptr>(bytes, 4), data, GL_DYNAMIC_STORAGE_BIT);
  return b;
}

}  // namespace

struct OpacityShadowMap::LightFragments {
  HostLists host;
};

// One kind of primitive, `vertices` indices each, drawn as `mode`: its keys, its sort, its sorted
// elements and one indirect draw per slice. The light capture numbers the primitives of all sets
// in one sequence, a set's starting at `base`. A line list (Mesh line primitives) is one more set
// of GL_LINES with 2 vertices; every pass below is written for any set.
struct OpacityShadowMap::PrimitiveSet {
  GLenum mode = GL_TRIANGLES;
  int vertices = 3;
  size_t count = 0, base = 0;
  gl::Buffer indices, elements, bounds, commands;
  gl::Program keys_prog, emit, bounds_prog, commands_prog;
  std::unique_ptr<RadixSort> sort;  // the primitives' (slice key, index) pairs

  size_t bytes(int slices) const {
    const size_t n = count * sizeof(unsigned);
    return sort->bytes() + 2 * vertices * n + 7 * slices * sizeof(unsigned);
  }
};

OpacityShadowMap::OpacityShadowMap(const CaseContext& ctx, const Mesh& mesh, const Light& light, int slices,
                                   int resolution)
    : ctx_(ctx),
      slices_(slices),
      resolution_(resolution),
      slice_off_(ctx.fault() == kShadowSliceOffFault),
      ambient_(light.ambient) {
  if (slices_ < 2) throw std::invalid_argument("self-shadowing: at least 2 slices");
  while ((1 << bits_) < slices_) ++bits_;
  // The light's frustum: its axis through `target`, near and far planes around the mesh's bounding sphere.
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const auto& v : mesh.vertices) {
    lo = glm::min(lo, v.position);
    hi = glm::max(hi, v.position);
  }
  const glm::vec3 centre = (lo + hi) * 0.5f;
  const float radius = glm::length(hi - lo) * 0.5f + 0.01f;
  const float axial = glm::dot(centre - light.eye, glm::normalize(light.target - light.eye));
  near_ = std::max(0.01f, axial - radius);
  far_ = std::max(near_ + 0.01f, axial + radius);
  light_view_proj_ =
      glm::perspective(glm::radians(light.fov_deg), 1.0f, near_, far_) * glm::lookAt(light.eye, light.target, light.up);

  vertices_ = make_storage(static_cast<GLsizeiptr>(mesh.vertices.size() * sizeof(Vertex)), mesh.vertices.data());
  // Every primitive casts a shadow: the transparent triangles, the opaque ones, then the line segments.
  std::vector<unsigned> triangles(mesh.indices);
  triangles.insert(triangles.end(), mesh.opaque_indices.begin(), mesh.opaque_indices.end());
  std::vector<std::pair<GLenum, const std::vector<unsigned>*>> lists = {{GL_TRIANGLES, &triangles},
                                                                        {GL_LINES, &mesh.line_indices}};
  size_t base = 0;
  for (const auto& [mode, list] : lists) {
    PrimitiveSet set;
    set.mode = mode;
    set.vertices = mode == GL_LINES ? 2 : 3;
    set.count = list->size() / set.vertices;
    set.base = base;
    base += set.count;
    if (!set.count) continue;
    set.indices = make_storage(static_cast<GLsizeiptr>(list->size() * sizeof(unsigned)), list->data());
    const GLsizeiptr n = static_cast<GLsizeiptr>(set.count * sizeof(unsigned));
    set.sort = std::make_unique<RadixSort>(ctx, set.count, bits_);
    set.elements = make_storage(set.vertices * n);
    set.bounds = make_storage(static_cast<GLsizeiptr>(2 * slices_ * sizeof(unsigned)));
    set.commands = make_storage(static_cast<GLsizeiptr>(5 * slices_ * sizeof(unsigned)));
    const Defines primitive = {{"PRIMITIVE_VERTICES", std::to_string(set.vertices)},
                               {"VERTEX_FLOATS", std::to_string(kVertexFloats)},
                               {"SLICES", std::to_string(slices_)}};
    set.keys_prog = ctx.build({{GL_COMPUTE_SHADER, "lines/slice_keys.comp"}}, primitive);
    const GLuint keys = set.keys_prog.get();
    glProgramUniformMatrix4fv(keys, glGetUniformLocation(keys, "viewProj"), 1, GL_FALSE, &light_view_proj_[0][0]);
    glProgramUniform1f(keys, glGetUniformLocation(keys, "nearDistance"), near_);
    glProgramUniform1f(keys, glGetUniformLocation(keys, "farDistance"), far_);
    set.emit = ctx.build({{GL_COMPUTE_SHADER, "lines/emit_indices.comp"}}, primitive);
    Defines bounds = primitive, commands = primitive;
    bounds.emplace_back("PHASE_BOUNDS", "");
    commands.emplace_back("PHASE_COMMANDS", "");
    set.bounds_prog = ctx.build({{GL_COMPUTE_SHADER, "shadow/slice_ranges.comp"}}, bounds);
    set.commands_prog = ctx.build({{GL_COMPUTE_SHADER, "shadow/slice_ranges.comp"}}, commands);
    sets_.push_back(std::move(set));
  }

  vao_ = gl::make_vertex_array();  // for shaders/scene/scene.vert
  bind_vertex_layout(vao_.get(), vertices_.get());

  map_ = gl::make_texture(GL_TEXTURE_3D);
  glTextureStorage3D(map_.get(), 1, GL_R32F, resolution_, resolution_, slices_ + 1);
  glTextureParameteri(map_.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(map_.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    glTextureParameteri(map_.get(), wrap, GL_CLAMP_TO_EDGE);
  fbo_ = gl::make_framebuffer();
  accumulate_ = ctx.build({{GL_VERTEX_SHADER, "scene/scene.vert"}, {GL_FRAGMENT_SHADER, "shadow/accumulate.frag"}}, {});
  glProgramUniformMatrix4fv(accumulate_.get(), glGetUniformLocation(accumulate_.get(), "viewProj"), 1, GL_FALSE,
                            &light_view_proj_[0][0]);
  prefix_ = ctx.build({{GL_COMPUTE_SHADER, "shadow/prefix_layers.comp"}}, {});
}

OpacityShadowMap::~OpacityShadowMap() = default;

size_t OpacityShadowMap::bytes() const {
  size_t b = static_cast<size_t>(resolution_) * resolution_ * (slices_ + 1) * sizeof(float);
  for (const auto& set : sets_) b += set.bytes(slices_);
  return b;
}

void OpacityShadowMap::build(PassTimer& timer) {
  {
    auto t = timer.pass(kShadowSortPass);
    for (auto& set : sets_) sort_primitives(set);
  }
  auto t = timer.pass(kShadowMapPass);
  draw_map();
}

void OpacityShadowMap::build() {
  PassTimer untimed(false, false);
  build(untimed);
}

void OpacityShadowMap::sort_primitives(PrimitiveSet& set) {
  const GLuint count = static_cast<GLuint>(set.count), groups = (count + 255) / 256;
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SLICE_KEYS_VERTICES_BINDING, vertices_.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SLICE_KEYS_KEYS_BINDING, set.sort->keys_in().get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SLICE_KEYS_INDICES_BINDING, set.sort->indices_in().get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SLICE_KEYS_PRIMITIVES_BINDING, set.indices.get());
  glUseProgram(set.keys_prog.get());
  glUniform1ui(glGetUniformLocation(set.keys_prog.get(), "segments"), count);
  glDispatchCompute(groups, 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  set.sort->sort();  // the primitive radix sort the lines experiment and the splats' global sort run
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EMIT_SORTED_BINDING, set.sort->sorted_indices().get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EMIT_ELEMENTS_BINDING, set.elements.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EMIT_PRIMITIVES_BINDING, set.indices.get());
  glUseProgram(set.emit.get());
  glUniform1ui(glGetUniformLocation(set.emit.get(), "segments"), count);
  glDispatchCompute(groups, 1, 1);
  // Each slice's range of the sorted elements as an indirect draw.
  const GLuint zero = 0;
  glClearNamedBufferData(set.bounds.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SLICE_RANGES_SORTED_KEYS_BINDING, set.sort->sorted_keys().get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SLICE_RANGES_BOUNDS_BINDING, set.bounds.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SLICE_RANGES_COMMANDS_BINDING, set.commands.get());
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  glUseProgram(set.bounds_prog.get());
  glUniform1ui(glGetUniformLocation(set.bounds_prog.get(), "count"), count);
  glDispatchCompute(groups, 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  glUseProgram(set.commands_prog.get());
  glDispatchCompute((static_cast<GLuint>(slices_) + 63) / 64, 1, 1);
  glMemoryBarrier(GL_ELEMENT_ARRAY_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
}

void OpacityShadowMap::draw_map() {
  const float zero = 0.0f;
  glClearTexImage(map_.get(), 0, GL_RED, GL_FLOAT, &zero);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
  glViewport(0, 0, resolution_, resolution_);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_ONE, GL_ONE);
  glUseProgram(accumulate_.get());
  glBindVertexArray(vao_.get());
  for (int slice = 0; slice < slices_; ++slice) {
    // Slice k lands in layer k + 1: layer 0 is what lies in front of the first slice, nothing.
    const int layer = std::min(slice + (slice_off_ ? 2 : 1), slices_);
    glNamedFramebufferTextureLayer(fbo_.get(), GL_COLOR_ATTACHMENT0, map_.get(), 0, layer);
    for (const auto& set : sets_) {
      glVertexArrayElementBuffer(vao_.get(), set.elements.get());
      glBindBuffer(GL_DRAW_INDIRECT_BUFFER, set.commands.get());
      glDrawElementsIndirect(set.mode, GL_UNSIGNED_INT,
                             reinterpret_cast<const void*>(static_cast<uintptr_t>(slice) * 5 * sizeof(unsigned)));
    }
  }
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
  glDisable(GL_BLEND);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
  glBindImageTexture(SHADOW_PREFIX_IMAGE_UNIT, map_.get(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32F);
  glUseProgram(prefix_.get());
  glDispatchCompute((static_cast<GLuint>(resolution_) + 7) / 8, (static_cast<GLuint>(resolution_) + 7) / 8, 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

void OpacityShadowMap::bind(GLuint program) const {
  glBindTextureUnit(SHADOW_MAP_UNIT, map_.get());
  glProgramUniformMatrix4fv(program, glGetUniformLocation(program, "shadowViewProj"), 1, GL_FALSE,
                            &light_view_proj_[0][0]);
  glProgramUniform2f(program, glGetUniformLocation(program, "shadowRange"), near_, far_);
  glProgramUniform1f(program, glGetUniformLocation(program, "shadowAmbient"), ambient_);
}

// Every fragment the map pass rasterises, seen from the light once (the map's geometry never moves).
OpacityShadowMap::LightFragments& OpacityShadowMap::light_fragments() {
  if (light_) return *light_;
  light_ = std::make_unique<LightFragments>();
  RenderTarget target(resolution_, resolution_, GL_RGBA8);
  FragmentLists lists(resolution_, resolution_, static_cast<size_t>(resolution_) * resolution_ * 8, false);
  auto build = [&] {
    auto built = build_capture_programs(
        lists, ctx_, {{GL_VERTEX_SHADER, "scene/scene.vert"}, {GL_FRAGMENT_SHADER, "shadow/light_capture.frag"}});
    for (const auto& p : built)
      glProgramUniformMatrix4fv(p.get(), glGetUniformLocation(p.get(), "viewProj"), 1, GL_FALSE,
                                &light_view_proj_[0][0]);
    return built;
  };
  auto programs = build();
  target.bind();
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  capture_complete(lists, programs, build, [&] {
    glBindVertexArray(vao_.get());
    for (const auto& set : sets_) {  // every primitive, numbered as the keys are
      for (const auto& p : programs)
        glProgramUniform1ui(p.get(), glGetUniformLocation(p.get(), "primitiveBase"), static_cast<GLuint>(set.base));
      glVertexArrayElementBuffer(vao_.get(), set.indices.get());
      glDrawElements(set.mode, static_cast<GLsizei>(set.count * set.vertices), GL_UNSIGNED_INT, nullptr);
    }
  });
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  light_->host = lists.read_back();
  return *light_;
}

namespace {

double alpha_of(unsigned colour) { return static_cast<double>(colour >> 24) / 255.0; }

// The exact reference, a deep shadow map, against the opacity map `cpu` (optical depth per layer):
// (sum of squared, largest absolute) transmittance errors over every light fragment.
std::pair<double, double> deep_shadow_error(const HostLists& host, const std::vector<double>& cpu, size_t texels,
                                            int slices_, double near_, double far_) {
  double sum_sq = 0, max_abs = 0;
  std::vector<std::pair<float, double>> column;  // (window depth, alpha)
  const double nf2 = 2.0 * near_ * far_, fpn = far_ + near_, fmn = far_ - near_;
  for (size_t p = 0; p < texels; ++p) {
    column.clear();
    for (unsigned node = host.heads[p]; node != kListEnd; node = host.next[node])
      column.emplace_back(glm::uintBitsToFloat(host.nodes[node].y), alpha_of(host.nodes[node].x));
    std::sort(column.begin(), column.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    double in_front = 1.0;
    for (size_t i = 0; i < column.size();) {
      size_t j = i;
      double group = 1.0;
      for (; j < column.size() && column[j].first == column[i].first; ++j) {
        const double w = nf2 / (fpn - (2.0 * column[j].first - 1.0) * fmn);  // light-view distance
        const double s = std::clamp((w - near_) / fmn, 0.0, 1.0) * slices_;
        const int k = std::min(static_cast<int>(s), slices_ - 1);
        const double t = s - k;
        const double tau = (1.0 - t) * cpu[k * texels + p] + t * cpu[(k + 1) * texels + p];
        const double e = std::exp(-tau) - in_front;
        sum_sq += e * e;
        max_abs = std::max(max_abs, std::abs(e));
        group *= 1.0 - column[j].second;
      }
      in_front *= group;
      i = j;
    }
  }
  return {sum_sq, max_abs};
}

}  // namespace

ShadowCheck OpacityShadowMap::validate() {
  ShadowCheck check;
  auto& m = check.metrics;
  m["shadow_map_bytes"] = std::to_string(bytes());
  const int layers = slices_ + 1;
  const size_t texels = static_cast<size_t>(resolution_) * resolution_;

  // The sort: each set's GPU keys, sorted stably on the CPU, must give exactly the GPU's order.
  // `keys` holds every primitive's key in the light capture's numbering (a set's from its base).
  std::vector<unsigned> keys;
  for (const auto& set : sets_) {
    const size_t n = set.count;
    std::vector<unsigned> own(n), order(n), gpu(n);
    glGetNamedBufferSubData(set.sort->keys_in().get(), 0, static_cast<GLsizeiptr>(n * sizeof(unsigned)), own.data());
    glGetNamedBufferSubData(set.sort->sorted_indices().get(), 0, static_cast<GLsizeiptr>(n * sizeof(unsigned)),
                            gpu.data());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](unsigned a, unsigned b) { return own[a] < own[b]; });
    auto wrong = std::mismatch(order.begin(), order.end(), gpu.begin());
    if (wrong.first != order.end())
      check.problems.push_back("shadow-sort: the radix sort differs from a stable CPU sort at position " +
                               std::to_string(wrong.first - order.begin()) + " (primitive " +
                               std::to_string(*wrong.second) + ", expected " + std::to_string(*wrong.first) + ")");
    keys.resize(set.base);
    keys.insert(keys.end(), own.begin(), own.end());
  }
  const size_t n = keys.size();
  if (n >= (1u << 24))
    check.problems.push_back("shadow light capture: " + std::to_string(n) +
                             " primitives; the capture numbers at most 2^24 (24 bits in a fragment's colour)");

  // The CPU map from the same slices: each light fragment's optical depth into its primitive's layer.
  const auto& host = light_fragments().host;
  if (!host.error.empty()) check.problems.push_back("shadow light capture: " + host.error);
  std::vector<double> cpu(static_cast<size_t>(layers) * texels, 0.0);
  size_t fragments = 0, bad_ids = 0;
  for (size_t p = 0; p < texels; ++p)
    for (unsigned node = host.heads[p]; node != kListEnd; node = host.next[node]) {
      const unsigned id = host.nodes[node].x & 0xFFFFFFu;
      ++fragments;
      if (id >= n || keys[id] >= static_cast<unsigned>(slices_)) {
        ++bad_ids;
        continue;
      }
      const int slice = slices_ - 1 - static_cast<int>(keys[id]);
      cpu[static_cast<size_t>(slice + 1) * texels + p] +=
          -std::log(1.0 - std::min(alpha_of(host.nodes[node].x), SHADOW_MAX_ALPHA));
    }
  if (bad_ids) check.problems.push_back(std::to_string(bad_ids) + " light fragment(s) name no primitive with a key");
  for (int k = 1; k < layers; ++k)
    for (size_t p = 0; p < texels; ++p) cpu[k * texels + p] += cpu[(k - 1) * texels + p];
  m["shadow_light_fragments"] = std::to_string(fragments);

  std::vector<float> map(static_cast<size_t>(layers) * texels);
  glGetTextureImage(map_.get(), 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(map.size() * sizeof(float)), map.data());
  double max_diff = 0;
  size_t bad = 0;
  std::string first_bad;
  for (size_t i = 0; i < map.size(); ++i) {
    const double d = std::abs(static_cast<double>(map[i]) - cpu[i]);
    max_diff = std::max(max_diff, std::isfinite(d) ? d : 1e30);
    if (!(d <= kShadowMapTolerance * (1.0 + cpu[i]))) {
      if (!bad++)
        first_bad = "texel (" + std::to_string(i % texels % resolution_) + ", " +
                    std::to_string(i % texels / resolution_) + ") layer " + std::to_string(i / texels) + ": GPU " +
                    fmt(map[i]) + ", CPU " + fmt(cpu[i]);
    }
  }
  m["shadow_map_max_diff"] = fmt(max_diff);
  if (bad)
    check.problems.push_back("shadow-map: " + std::to_string(bad) +
                             " texel(s) of the opacity map differ from the CPU map of the same slices by more than " +
                             fmt(kShadowMapTolerance) + " x (1 + optical depth); first: " + first_bad);

  // The exact reference, a deep shadow map: per light pixel the fragments sorted by depth, each
  // lit by the product of (1 - alpha) of those strictly in front of it. The opacity map's
  // transmittance at the same fragments (its layers interpolated at their slice position) is compared.
  auto [sum_sq, max_abs] = deep_shadow_error(host, cpu, texels, slices_, near_, far_);
  m["shadow_rmse"] = fmt(fragments ? std::sqrt(sum_sq / static_cast<double>(fragments)) : 0.0);
  m["shadow_max_abs_error"] = fmt(max_abs);
  return check;
}

std::unique_ptr<OpacityShadowMap> make_self_shadowing(const CaseContext& ctx, const SceneDesc& scene, const Mesh& mesh,
                                                      const ParamSet& p) {
  if (!scene.has_effect("self-shadowing") || !scene.light) return nullptr;
  return std::make_unique<OpacityShadowMap>(ctx, mesh, *scene.light, static_cast<int>(p.get_int("shadow_slices")),
                                            static_cast<int>(p.get_int("shadow_resolution")));
}

}  // namespace oitbench::oit
