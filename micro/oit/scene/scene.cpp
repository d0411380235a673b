#include "oit/scene/scene.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <set>
#include <sstream>

#include "core/data_dirs.hpp"
#include "core/files.hpp"
#include "core/text_position.hpp"
#include "oit/case_support.hpp"
#include "oit/scene/generator_support.hpp"
#include "oit/splats/splat_ply.hpp"
#include "oit/splats/splat_scene.hpp"

namespace oitbench::oit {

namespace {

using nlohmann::json;

// nlohmann keeps no positions for values: find the line of a JSON path by searching for its keys
// in order ("/materials/glass/alpha" -> "materials", then "glass", then "alpha" after it).
size_t locate(const std::string& text, const std::vector<std::string>& keys) {
  size_t pos = 0;
  for (const auto& k : keys) {
    if (k.empty() || std::all_of(k.begin(), k.end(), ::isdigit)) continue;  // array index: no key text
    auto at = text.find("\"" + k + "\"", pos);
    if (at == std::string::npos) break;
    pos = at;
  }
  return pos;
}

// Checked access to one JSON object, with the file, the path and the text for error messages.
class Node {
 public:
  Node(const json& j, const std::string& path, const std::string& text, std::vector<std::string> keys)
      : j_(j), path_(path), text_(text), keys_(std::move(keys)) {}

  [[noreturn]] void fail(const std::string& what) const {
    std::string ptr;
    for (const auto& k : keys_) ptr += "/" + k;
    throw SceneError(path_ + ":" + line_column(text_, locate(text_, keys_)) + ": " + (ptr.empty() ? "/" : ptr) + ": " +
                     what);
  }
  Node child(const std::string& key) const {
    auto k = keys_;
    k.push_back(key);
    return Node(j_.at(key), path_, text_, k);
  }
  Node element(size_t i) const {
    auto k = keys_;
    k.push_back(std::to_string(i));
    return Node(j_.at(i), path_, text_, k);
  }
  const json& raw() const { return j_; }
  bool has(const std::string& key) const { return j_.is_object() && j_.contains(key); }

  // An empty `allowed` accepts any key (a map of names).
  void expect_object(const std::vector<std::string>& allowed) const {
    if (!j_.is_object()) fail("expected an object, got " + std::string(j_.type_name()));
    if (allowed.empty()) return;
    for (const auto& [k, v] : j_.items())
      if (std::find(allowed.begin(), allowed.end(), k) == allowed.end()) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        child(k).fail("unknown key \"" + k + "\"; expected one of: " + list);
      }
  }
  // A required object `key` of named objects ({"NAME": {...}, ...}; `usage` says what is missing),
  // and f(name, node) for each entry, checked as an object of the `allowed` keys. Returns the map.
  template <class F>
  Node for_each_named(const std::string& key, const std::string& usage, const std::vector<std::string>& allowed,
                      F f) const {
    if (!has(key)) fail(usage);
    Node map = child(key);
    map.expect_object({});
    for (const auto& [k, v] : j_.at(key).items()) {
      (void)v;
      Node n = map.child(k);
      n.expect_object(allowed);
      f(k, n);
    }
    return map;
  }
  std::string str() const {
    if (!j_.is_string()) fail("expected a string, got " + std::string(j_.type_name()));
    return j_.get<std::string>();
  }
  double number(double lo, double hi) const {
    if (!j_.is_number()) fail("expected a number, got " + std::string(j_.type_name()));
    double v = j_.get<double>();
    if (v < lo || v > hi) fail("expected a number in [" + fmt(lo) + ", " + fmt(hi) + "], got " + fmt(v));
    return v;
  }
  double integer(double lo, double hi) const {
    double v = number(lo, hi);
    if (v != std::floor(v)) fail("expected a whole number (a count), got " + fmt(v));
    return v;
  }
  bool boolean() const {
    if (!j_.is_boolean()) fail("expected true or false, got " + std::string(j_.type_name()));
    return j_.get<bool>();
  }
  glm::vec3 vec3(double lo = -1e6, double hi = 1e6) const {
    if (!j_.is_array() || j_.size() != 3) fail("expected an array of 3 numbers");
    return {element(0).number(lo, hi), element(1).number(lo, hi), element(2).number(lo, hi)};
  }

 private:
  const json& j_;
  const std::string& path_;
  const std::string& text_;
  std::vector<std::string> keys_;
};

const std::vector<std::string> kGenerators = {"planes", "hairball", "strands", "smoke", "model", "splats", "ply"};
// Generator parameters that are counts (whole numbers), and sizes that must be above 0.
const std::set<std::string> kCountKeys = {"count",      "strands", "segments", "sides",
                                          "per_strand", "seed",    "grid",     "clusters"};
const std::set<std::string> kPositiveKeys = {"half_size",   "segment_length", "tube_radius", "radius",
                                             "head_radius", "size",           "scale_min",   "scale_max"};

SubmitOrder parse_order(const Node& n) {
  auto s = n.str();
  if (s == "as-generated") return SubmitOrder::AsGenerated;
  if (s == "front-to-back") return SubmitOrder::FrontToBack;
  if (s == "back-to-front") return SubmitOrder::BackToFront;
  n.fail("expected \"as-generated\", \"front-to-back\" or \"back-to-front\", got \"" + s + "\"");
}

// ---- generators: each appends primitives (groups of triangles, or one line segment) with one
// centroid per group ----

struct Builder {
  Mesh mesh;
  std::vector<glm::vec3> centroids;               // per group
  std::vector<std::pair<size_t, size_t>> groups;  // [first index, index count) in indices or line_indices
  std::vector<bool> group_opaque;                 // per group: made of an opaque material
  std::vector<bool> group_lines;                  // per group: a line segment (indices in line_indices)
  bool opaque = false;                            // the material of the groups begun next
  void begin() {
    groups.push_back({mesh.indices.size(), 0});
    group_opaque.push_back(opaque);
    group_lines.push_back(false);
  }
  void end(glm::vec3 centroid) {
    groups.back().second = mesh.indices.size() - groups.back().first;
    centroids.push_back(centroid);
  }
  // One line segment: a group of its own, so the view's submission order sorts segments.
  void segment(unsigned a, unsigned b) {
    groups.push_back({mesh.line_indices.size(), 2});
    group_opaque.push_back(opaque);
    group_lines.push_back(true);
    mesh.line_indices.insert(mesh.line_indices.end(), {a, b});
    centroids.push_back((mesh.vertices[a].position + mesh.vertices[b].position) * 0.5f);
  }
  unsigned vertex(glm::vec3 p, glm::vec4 c, glm::vec2 uv = {0, 0}, float soft = 0) {
    mesh.vertices.push_back({p, glm::clamp(c, 0.0f, 1.0f), uv, soft});
    return static_cast<unsigned>(mesh.vertices.size() - 1);
  }
  void quad(unsigned a, unsigned b, unsigned c, unsigned d) {
    mesh.indices.insert(mesh.indices.end(), {a, b, c, a, c, d});
  }
};

double param(const json& p, const char* key, double fallback) {
  return p.contains(key) ? p[key].get<double>() : fallback;
}

// The paper's synthetic scene: `count` planes facing +z, evenly spaced from z = +depth/2 (plane 0)
// to -depth/2 around `offset`, each a different hue (or `colours[i]`, `alphas[i]`), generated
// nearest-to-+z first.
std::vector<AnalyticPlane> planes_of(const json& p, const Material& m) {
  int count = static_cast<int>(param(p, "count", 128));
  double half = param(p, "half_size", 2.0), depth = param(p, "depth", 2.0);
  glm::dvec3 offset(0.0);
  if (p.contains("offset"))
    for (int k = 0; k < 3; ++k) offset[k] = p["offset"][k].get<double>();
  std::vector<AnalyticPlane> out;
  for (int i = 0; i < count; ++i) {
    double z = count == 1 ? 0.0 : depth / 2 - depth * i / (count - 1);
    glm::vec4 c(glm::mix(m.colour, hue(static_cast<double>(i) / count), 0.5f), m.alpha);
    if (p.contains("colours"))
      for (int k = 0; k < 3; ++k) c[k] = p["colours"][i][k].get<float>();
    if (p.contains("alphas") && !m.opaque) c.a = p["alphas"][i].get<float>();
    out.push_back({offset + glm::dvec3(0, 0, z), half, c});
  }
  return out;
}

void gen_planes(Builder& b, const json& p, const Material& m) {
  for (const AnalyticPlane& pl : planes_of(p, m)) {
    b.begin();
    glm::vec3 o(pl.centre);
    float h = static_cast<float>(pl.half_size);
    unsigned v0 = b.vertex(o + glm::vec3(-h, -h, 0), pl.colour), v1 = b.vertex(o + glm::vec3(h, -h, 0), pl.colour),
             v2 = b.vertex(o + glm::vec3(h, h, 0), pl.colour), v3 = b.vertex(o + glm::vec3(-h, h, 0), pl.colour);
    b.quad(v0, v1, v2, v3);
    b.end(o);
  }
}

// One step of a tube: an open `sides`-sided prism of radius `r` from `pos` to `next`, one primitive.
void tube_segment(Builder& b, glm::vec3 pos, glm::vec3 next, int sides, double r, glm::vec4 c) {
  glm::vec3 axis = glm::normalize(next - pos);
  glm::vec3 ref = std::abs(axis.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  glm::vec3 u = glm::normalize(glm::cross(axis, ref)), v = glm::cross(axis, u);
  b.begin();
  unsigned first = static_cast<unsigned>(b.mesh.vertices.size());
  for (int i = 0; i < sides; ++i) {
    double a = 6.283185307179586 * i / sides;
    glm::vec3 off = (u * static_cast<float>(std::cos(a)) + v * static_cast<float>(std::sin(a))) * static_cast<float>(r);
    b.vertex(pos + off, c);
    b.vertex(next + off, c);
  }
  for (int i = 0; i < sides; ++i) {
    unsigned a0 = first + 2 * i, a1 = a0 + 1, b0 = first + 2 * ((i + 1) % sides), b1 = b0 + 1;
    b.quad(a0, b0, b1, a1);
  }
  b.end((pos + next) * 0.5f);
}

// A tangle of thin tubes inside a sphere: `strands` random walks of `segments` steps, each step a
// `sides`-sided open tube. Generated strand by strand, step by step (a modelling package's order).
void gen_hairball(Builder& b, const json& p, const Material& m) {
  int strands = static_cast<int>(param(p, "strands", 500)), segments = static_cast<int>(param(p, "segments", 100));
  int sides = static_cast<int>(param(p, "sides", 3));
  double step = param(p, "segment_length", 0.1), r = param(p, "tube_radius", 0.02), radius = param(p, "radius", 1.0);
  double wiggle = param(p, "wiggle", 0.5);
  Rng rng(static_cast<unsigned long long>(param(p, "seed", 1)));
  for (int s = 0; s < strands; ++s) {
    glm::vec3 pos = rng.unit() * static_cast<float>(radius * std::cbrt(rng.uniform()));
    glm::vec3 dir = rng.unit();
    glm::vec4 c(glm::mix(m.colour, hue(rng.uniform()), 0.3f), m.alpha);
    for (int k = 0; k < segments; ++k) {
      dir = glm::normalize(dir + rng.unit() * static_cast<float>(wiggle));
      glm::vec3 next = pos + dir * static_cast<float>(step);
      if (glm::length(next) > radius) {  // turn back into the sphere
        dir = glm::normalize(glm::reflect(dir, glm::normalize(next)));
        next = pos + dir * static_cast<float>(step);
      }
      tube_segment(b, pos, next, sides, r, c);
      pos = next;
    }
  }
}

// Hair as line strands (Sintorn et al.'s poster renders hair as line segments): `segments` segments
// in strands of `per_strand`, rooted on a head sphere of `head_radius` (no roots below
// y = `lowest_root` x radius: no hair under the chin). Each strand is a random walk of
// `segment_length` steps that starts along the sphere's normal and bends down by `gravity` per step,
// sideways by up to `curl`. A strand's colour is one of four hair tones (shaded a little per strand)
// mixed with the material's colour (`colour_mix`: the tones' share). Generated strand by strand.
// `sides` 0 makes line segments (one primitive each); 3 or more makes the hairball's open tubes of
// `tube_radius` instead (triangles, one primitive per step), the same strands as surfaces.
void gen_strands(Builder& b, const json& p, const Material& m) {
  const size_t segments = static_cast<size_t>(param(p, "segments", 90000));
  const int per_strand = std::max(1, static_cast<int>(param(p, "per_strand", 16)));
  const float head = static_cast<float>(param(p, "head_radius", 0.5)),
              step = static_cast<float>(param(p, "segment_length", 0.06)),
              gravity = static_cast<float>(param(p, "gravity", 0.12)),
              curl = static_cast<float>(param(p, "curl", 0.15)),
              lowest = static_cast<float>(param(p, "lowest_root", -0.3)),
              mix = static_cast<float>(param(p, "colour_mix", 0.75));
  const int sides = static_cast<int>(param(p, "sides", 0));
  const double tube_radius = param(p, "tube_radius", 0.004);
  Rng rng(static_cast<unsigned long long>(param(p, "seed", 1)));
  const glm::vec3 tones[] = {
      {0.45f, 0.30f, 0.18f}, {0.60f, 0.45f, 0.25f}, {0.30f, 0.20f, 0.12f}, {0.75f, 0.62f, 0.40f}};
  b.mesh.vertices.reserve(b.mesh.vertices.size() + segments + segments / per_strand + 1);
  size_t made = 0;
  while (made < segments) {
    glm::vec3 n = rng.unit();
    if (n.y < lowest) continue;
    glm::vec3 pos = n * head, dir = n;
    glm::vec3 tone =
        tones[static_cast<int>(rng.uniform() * 4) % 4] * static_cast<float>(0.85 + 0.15 * rng.range(-1, 1));
    glm::vec4 c(glm::mix(m.colour, tone, mix), m.alpha);
    unsigned prev = sides ? 0 : b.vertex(pos, c);
    for (int s = 0; s < per_strand && made < segments; ++s, ++made) {
      glm::vec3 from = pos;
      pos += step * dir;
      if (sides) {
        tube_segment(b, from, pos, sides, tube_radius, c);
      } else {
        unsigned next = b.vertex(pos, c);
        b.segment(prev, next);
        prev = next;
      }
      glm::vec3 bend(static_cast<float>(rng.range(-curl, curl)), -gravity, static_cast<float>(rng.range(-curl, curl)));
      dir = glm::normalize(dir + bend);
    }
  }
}

// Camera-facing billboards in a rising plume: `count` squares of side `size`, Gaussian about the
// column (`spread` sideways, `height` up), alpha falling off radially (soft material).
void gen_smoke(Builder& b, const json& p, const Material& m, const View& view) {
  int count = static_cast<int>(param(p, "count", 510));
  double size = param(p, "size", 0.5), spread = param(p, "spread", 0.25), height = param(p, "height", 1.6);
  Rng rng(static_cast<unsigned long long>(param(p, "seed", 2)));
  for (int i = 0; i < count; ++i) {
    double t = rng.uniform();
    glm::vec3 centre(rng.normal() * spread * (0.5 + t), (t - 0.5) * height, rng.normal() * spread * (0.5 + t));
    glm::vec3 to_eye = glm::normalize(view.eye - centre);
    glm::vec3 right = glm::normalize(glm::cross(view.up, to_eye)), up = glm::cross(to_eye, right);
    float h = static_cast<float>(size * (0.6 + 0.8 * rng.uniform()) / 2);
    glm::vec4 c(m.colour * static_cast<float>(0.8 + 0.2 * rng.uniform()), m.alpha);
    float soft = m.soft ? 1.0f : 0.0f;
    b.begin();
    unsigned v0 = b.vertex(centre - right * h - up * h, c, {-1, -1}, soft);
    unsigned v1 = b.vertex(centre + right * h - up * h, c, {1, -1}, soft);
    unsigned v2 = b.vertex(centre + right * h + up * h, c, {1, 1}, soft);
    unsigned v3 = b.vertex(centre - right * h + up * h, c, {-1, 1}, soft);
    b.quad(v0, v1, v2, v3);
    b.end(centre);
  }
}

// What a mesh will hold, counted before it is built: build_mesh refuses one past kMaxMeshBytes
// instead of allocating until the process is killed.
struct MeshEstimate {
  double vertices = 0, indices = 0, primitives = 0, splats = 0;
  // The builder's vertices, its indices and their reordered copy, and per primitive its group,
  // centroid and flags; per splat the list, its reordered copy, its distance and its place in the order.
  double bytes() const {
    return vertices * sizeof(Vertex) + indices * 2 * sizeof(unsigned) + primitives * 40 +
           splats * (2 * sizeof(Splat) + sizeof(float) + sizeof(size_t));
  }
};

std::string approx_count(double x) {
  std::ostringstream s;
  s.precision(3);
  s << x;
  return s.str();
}

// Throws SceneError naming the scene file, the object and the parameters behind its size.
void check_mesh_size(const MeshEstimate& total, const SceneDesc& scene, size_t object, const std::string& why,
                     unsigned long long max_bytes) {
  const double index_limit = 4294967295.0;  // indices are 32-bit
  if (total.bytes() <= static_cast<double>(max_bytes) && total.vertices < index_limit) return;
  throw SceneError(scene.path + ": /objects/" + std::to_string(object) + " (" + scene.objects[object].generator +
                   "): " + why + " makes the mesh about " + approx_count(total.primitives) + " primitives (" +
                   approx_count(total.splats) + " splats), " + approx_count(total.vertices) + " vertices, " +
                   approx_count(total.bytes() / (1 << 30)) + " GiB; the most oitbench builds is " +
                   approx_count(static_cast<double>(max_bytes) / (1 << 30)) +
                   " GiB and 2^32 vertices: lower the parameters (or use \"detail\": small)");
}

// A procedural object's size from its parameters alone (a model's needs its file: gen_model).
MeshEstimate estimate_object(const SceneObject& o, const json& p, std::string& why) {
  MeshEstimate e;
  auto num = [&](const char* k, double fallback) { return param(p, k, fallback); };
  if (o.generator == "planes" || o.generator == "smoke") {
    double count = num("count", o.generator == "planes" ? 128 : 510);
    e = {4 * count, 6 * count, count};
    why = "count " + approx_count(count);
  } else if (o.generator == "hairball") {
    double steps = num("strands", 500) * num("segments", 100), sides = num("sides", 3);
    e = {steps * 2 * sides, steps * 6 * sides, steps};
    why = "strands " + approx_count(num("strands", 500)) + " x segments " + approx_count(num("segments", 100)) +
          " x sides " + approx_count(sides);
  } else if (o.generator == "strands") {
    double segments = num("segments", 90000), sides = num("sides", 0);
    e = sides > 0 ? MeshEstimate{segments * 2 * sides, segments * 6 * sides, segments}
                  : MeshEstimate{2 * segments + 1, 2 * segments, segments};
    why = "segments " + approx_count(segments) + (sides > 0 ? " x sides " + approx_count(sides) : "");
  } else if (o.generator == "splats") {
    const double count = splat_generator_params(p).count;
    e = {0, 0, count, count};
    why = "count " + approx_count(count);
  }
  return e;
}

// Three per-axis values from a number (the same on every axis) or an array of three numbers.
glm::vec3 per_axis(const json& p, const char* key, float fallback) {
  if (!p.contains(key)) return glm::vec3(fallback);
  const json& v = p[key];
  if (v.is_array()) return {v[0].get<float>(), v[1].get<float>(), v[2].get<float>()};
  return glm::vec3(v.get<float>());
}

// A model file read with assimp (triangulated, node transforms applied: a mesh placed by several
// nodes appears once per placement), scaled so its bounding box's diagonal is 2, repeated on a
// `grid` lattice (x, y, z counts) `spacing` apart: the engine grid gives a deep CAD scene from a
// small model. Each triangle is a primitive. A triangle's colour mixes the scene material with the
// model material's diffuse colour (`colour_mix`: the model's share); its alpha is the scene
// material's, or `alpha_by_material[model material name]`, or with `model_opacity` the model's own
// opacity where the file gives one below 1 (the house's glass). Materials named in
// `exclude_materials` are left out (before the bounding box is taken). With
// `opaque_unless_translucent`, every model material is opaque except those the file makes
// translucent (model_opacity) or alpha_by_material names: the house's walls and its glass.
// One model mesh's triangles appended to the builder, each vertex placed by `place` and coloured `c`.
template <class Place>
void append_model_mesh(Builder& b, const aiMesh& mesh, Place place, glm::vec4 c) {
  unsigned first = static_cast<unsigned>(b.mesh.vertices.size());
  for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
    const aiVector3D& q = mesh.mVertices[v];
    b.vertex(place(glm::vec3(q.x, q.y, q.z)), c);
  }
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mNumIndices != 3) continue;
    b.begin();
    unsigned a = first + face.mIndices[0], bb = first + face.mIndices[1], cc = first + face.mIndices[2];
    b.mesh.indices.insert(b.mesh.indices.end(), {a, bb, cc});
    b.end((b.mesh.vertices[a].position + b.mesh.vertices[bb].position + b.mesh.vertices[cc].position) / 3.0f);
  }
}

void gen_model(Builder& b, const json& p, const Material& m, const std::string& file, const SceneDesc& scene,
               size_t object, MeshEstimate& total, unsigned long long max_bytes) {
  try {
    check_input_file(file, "model file", kMaxModelFileBytes);
  } catch (const FileError& e) {
    throw SceneError(scene.path + ": /objects/" + std::to_string(object) + "/file: " + e.what());
  }
  Assimp::Importer importer;
  const aiScene* sc = importer.ReadFile(file, aiProcess_Triangulate | aiProcess_PreTransformVertices |
                                                  aiProcess_JoinIdenticalVertices | aiProcess_SortByPType);
  if (!sc || !sc->mRootNode) throw SceneError(file + ": assimp could not read the model: " + importer.GetErrorString());
  auto material_name = [&](unsigned i) {
    aiString name;
    if (sc->mMaterials && i < sc->mNumMaterials) sc->mMaterials[i]->Get(AI_MATKEY_NAME, name);
    return std::string(name.C_Str());
  };
  std::vector<std::string> excluded;
  if (p.contains("exclude_materials"))
    for (const auto& e : p["exclude_materials"]) excluded.push_back(e.get<std::string>());
  auto included = [&](const aiMesh* mesh) {
    return (mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) &&
           std::find(excluded.begin(), excluded.end(), material_name(mesh->mMaterialIndex)) == excluded.end();
  };
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (unsigned i = 0; i < sc->mNumMeshes; ++i) {
    if (!included(sc->mMeshes[i])) continue;
    for (unsigned v = 0; v < sc->mMeshes[i]->mNumVertices; ++v) {
      const aiVector3D& q = sc->mMeshes[i]->mVertices[v];
      lo = glm::min(lo, glm::vec3(q.x, q.y, q.z));
      hi = glm::max(hi, glm::vec3(q.x, q.y, q.z));
    }
  }
  if (lo.x > hi.x) throw SceneError(file + ": the model has no triangles (after exclude_materials)");
  glm::vec3 centre = (lo + hi) * 0.5f;
  float scale = 2.0f / std::max(glm::length(hi - lo), 1e-6f);
  glm::ivec3 grid = glm::max(glm::ivec3(per_axis(p, "grid", 1.0f)), glm::ivec3(1));
  {  // the instances' size, before any is made
    MeshEstimate one;
    for (unsigned i = 0; i < sc->mNumMeshes; ++i)
      if (included(sc->mMeshes[i])) {
        one.vertices += sc->mMeshes[i]->mNumVertices;
        one.indices += 3.0 * sc->mMeshes[i]->mNumFaces;
        one.primitives += sc->mMeshes[i]->mNumFaces;
      }
    const double copies = static_cast<double>(grid.x) * grid.y * grid.z;
    total.vertices += one.vertices * copies;
    total.indices += one.indices * copies;
    total.primitives += one.primitives * copies;
    check_mesh_size(total, scene, object,
                    file + " (" + approx_count(one.primitives) + " triangles) x grid " + std::to_string(grid.x) +
                        " x " + std::to_string(grid.y) + " x " + std::to_string(grid.z),
                    max_bytes);
  }
  glm::vec3 spacing = per_axis(p, "spacing", 1.0f);
  float mix = static_cast<float>(param(p, "colour_mix", 0.5));
  const bool opaque_unless = p.value("opaque_unless_translucent", false);
  bool model_opacity = p.value("model_opacity", false);
  const json alpha_by_material = p.value("alpha_by_material", json::object());
  glm::vec3 half = 0.5f * spacing * glm::vec3(grid - 1);
  for (int gz = 0; gz < grid.z; ++gz)
    for (int gy = 0; gy < grid.y; ++gy)
      for (int gx = 0; gx < grid.x; ++gx) {
        glm::vec3 offset = glm::vec3(gx, gy, gz) * spacing - half;
        for (unsigned i = 0; i < sc->mNumMeshes; ++i) {
          const aiMesh* mesh = sc->mMeshes[i];
          if (!included(mesh)) continue;
          glm::vec3 diffuse(1.0f);
          float alpha = m.alpha;
          bool opaque = m.opaque || opaque_unless;
          if (sc->mMaterials && mesh->mMaterialIndex < sc->mNumMaterials) {
            const aiMaterial* mat = sc->mMaterials[mesh->mMaterialIndex];
            aiColor4D d;
            if (aiGetMaterialColor(mat, AI_MATKEY_COLOR_DIFFUSE, &d) == AI_SUCCESS) diffuse = glm::vec3(d.r, d.g, d.b);
            float opacity = 1.0f;
            if (model_opacity && mat->Get(AI_MATKEY_OPACITY, opacity) == AI_SUCCESS && opacity < 1.0f) {
              alpha = opacity;
              opaque = m.opaque;
            }
            auto named = alpha_by_material.find(material_name(mesh->mMaterialIndex));
            if (named != alpha_by_material.end()) {
              alpha = named->get<float>();
              opaque = m.opaque;
            }
          }
          b.opaque = opaque;
          glm::vec4 c(glm::mix(m.colour, diffuse, mix), opaque ? 1.0f : alpha);
          append_model_mesh(
              b, *mesh, [&](glm::vec3 q) { return (q - centre) * scale + offset; }, c);
        }
      }
}

std::string resolve_model(const SceneDesc& s, const std::string& file) {
  // The scene's folder; models/ beside it (an install or a bundle carries the models it needs
  // there, share/oitbench/models/); then the scene's own roots (Debian's assimp-testmodels).
  const std::filesystem::path scene_dir = std::filesystem::path(s.path).parent_path();
  std::vector<std::filesystem::path> roots = {scene_dir, scene_dir.parent_path() / "models"};
  if (const char* env = std::getenv("OITBENCH_MODELS")) roots.insert(roots.begin(), env);
  for (const auto& r : s.model_roots) roots.push_back(r);
  std::string tried;
  for (const auto& r : roots) {
    auto p = r / file;
    if (std::filesystem::exists(p)) return p.string();
    tried += (tried.empty() ? "" : ", ") + r.string();
  }
  throw SceneError(s.path + ": model file \"" + file + "\" not found in " + tried +
                   " (set OITBENCH_MODELS, or install Debian's assimp-testmodels)");
}

[[noreturn]] void splat_file_error(const SceneDesc& scene, size_t object, const SplatFileError& e) {
  throw SceneError(scene.path + ": /objects/" + std::to_string(object) + "/file: " + e.what());
}

// A "ply" object's size from its file's header (the first `count` splats when its params say so),
// before anything is read for them.
MeshEstimate estimate_ply(const SceneDesc& scene, size_t object, const json& p, std::string& why) {
  const std::string file = resolve_model(scene, scene.objects[object].file);
  SplatPlyHeader h;
  try {
    h = read_splat_ply_header(file);
  } catch (const SplatFileError& e) {
    splat_file_error(scene, object, e);
  }
  const double n = std::min(static_cast<double>(h.count), param(p, "count", 1e300));
  why = file + " (" + approx_count(static_cast<double>(h.count)) + " splats)" +
        (p.contains("count") ? ", count " + approx_count(param(p, "count", 0)) : "");
  return {0, 0, n, n};
}

// A "ply" object's splats for the view (their spherical harmonics seen from its eye), moved by `offset`.
SplatList gen_ply(const SceneDesc& scene, size_t object, const json& p, const View& view) {
  const std::string file = resolve_model(scene, scene.objects[object].file);
  glm::vec3 offset(0.0f);
  if (p.contains("offset"))
    for (int k = 0; k < 3; ++k) offset[k] = p["offset"][k].get<float>();
  const std::uint64_t count = p.contains("count") ? p["count"].get<std::uint64_t>() : UINT64_MAX;
  try {
    return read_splat_ply(file, view.eye, count, offset);
  } catch (const SplatFileError& e) {
    splat_file_error(scene, object, e);
  }
}

void append_splats(SplatList& to, SplatList&& from) {
  if (to.empty())
    to = std::move(from);
  else
    to.insert(to.end(), from.begin(), from.end());
}

// The parameter sets an object is built with: its "params", and "small" applied over them when given.
// f(merged, params): params is true for "params" alone, false for "small" over them.
template <class F>
void for_each_parameter_set(const SceneObject& obj, F f) {
  for (const json* ps : {&obj.params, &obj.small}) {
    if (!ps->is_object()) continue;
    json merged = obj.params;
    for (const auto& [k, v] : ps->items()) merged[k] = v;
    f(merged, ps == &obj.params);
  }
}

// "splats": its parameters taken together (params with small applied, and params alone).
void check_splat_params(Node& o, const SceneObject& obj) {
  if (obj.generator != "splats") return;
  for_each_parameter_set(obj, [&](const json& merged, bool params) {
    auto problem = splat_params_problem(merged);
    if (!problem) return;
    Node where = o.child(params ? "params" : "small");
    if (where.has(problem->first)) where.child(problem->first).fail(problem->second);
    where.fail(problem->second + " (with the defaults of the keys not given)");
  });
}

// Every model file of the scene found and a regular file of bounded size: a folder or /dev/null is bad
// input (exit 2) before any case runs, not an error row.
void check_model_files_of(const SceneDesc& scene) {
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    if (scene.objects[i].generator == "ply") {
      try {
        check_splat_ply(resolve_model(scene, scene.objects[i].file));
      } catch (const SplatFileError& e) {
        splat_file_error(scene, i, e);
      }
    }
    if (scene.objects[i].generator != "model") continue;
    try {
      check_input_file(resolve_model(scene, scene.objects[i].file), "model file", kMaxModelFileBytes);
    } catch (const FileError& e) {
      throw SceneError(scene.path + ": /objects/" + std::to_string(i) + "/file: " + e.what());
    }
  }
}

// "light" and "effects", checked against what the scene holds: each effect needs something to act on.
void parse_light_and_effects(const Node& root, SceneDesc& s) {
  if (root.has("light")) {
    auto n = root.child("light");
    n.expect_object({"eye", "target", "up", "fov", "ambient"});
    Light l;
    if (!n.has("eye")) n.fail("expected \"eye\": [x, y, z], where the light stands");
    l.eye = n.child("eye").vec3();
    if (n.has("target")) l.target = n.child("target").vec3();
    if (n.has("up")) l.up = n.child("up").vec3();
    if (n.has("fov")) l.fov_deg = static_cast<float>(n.child("fov").number(1, 170));
    if (n.has("ambient")) l.ambient = static_cast<float>(n.child("ambient").number(0, 1));
    if (glm::length(l.eye - l.target) < 1e-6f) n.fail("eye and target coincide");
    if (glm::length(glm::cross(glm::normalize(l.target - l.eye), l.up)) < 1e-4f)
      n.fail("\"up\" is parallel to the light's direction; give an up vector across it");
    s.light = l;
  }
  if (!root.has("effects")) {
    s.effects = {"transparency"};
    return;
  }
  auto e = root.child("effects");
  const auto& valid = effect_names();
  std::string list;
  for (const auto& v : valid) list += (list.empty() ? "" : ", ") + v;
  if (!e.raw().is_array() || e.raw().empty())
    e.fail("expected a non-empty array of effect names (" + list + "), e.g. [\"transparency\"]");
  bool any_opaque = false, any_transparent = false;
  for (const auto& o : s.objects) {
    const auto& m = s.material(o.material);
    if (o.generator == "strands" || o.generator == "splats" || o.generator == "ply") {  // always captured
      any_transparent = true;
      continue;
    }
    (m.opaque ? any_opaque : any_transparent) = true;
    // a model can hold opaque and transparent materials of its own (params "opaque_unless_translucent")
    if (o.generator == "model" && o.params.value("opaque_unless_translucent", false))
      any_opaque = any_transparent = true;
  }
  std::vector<std::string> declared;
  for (size_t i = 0; i < e.raw().size(); ++i) {
    auto n = e.element(i);
    auto name = n.str();
    if (std::find(valid.begin(), valid.end(), name) == valid.end())
      n.fail("unknown effect \"" + name + "\"; valid effects: " + list);
    if (std::find(declared.begin(), declared.end(), name) != declared.end())
      n.fail("effect \"" + name + "\" is declared twice");
    if (name == "opaque" && !any_opaque)
      n.fail("effect \"opaque\" has nothing to act on: no object uses an opaque material (\"opaque\": true)");
    if (name == "transparency" && !any_transparent)
      n.fail("effect \"transparency\" has nothing to act on: every object's material is opaque");
    if (name == "self-shadowing" && !s.light)
      n.fail("effect \"self-shadowing\" needs a light: add \"light\": {\"eye\": [x, y, z], \"target\": [x, y, z]}");
    declared.push_back(name);
  }
  for (const auto& v : valid)  // canonical order
    if (std::find(declared.begin(), declared.end(), v) != declared.end()) s.effects.push_back(v);
}

// The JSON of a scene file; a syntax error or an out-of-range number names FILE:LINE:COLUMN.
json parse_json(const std::string& path, const std::string& text) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    // e.byte is the 1-based offset of the character that broke the parse.
    std::string what = e.what();
    if (auto at = what.find("syntax error"); at != std::string::npos) what = what.substr(at);
    throw SceneError(path + ":" + line_column(text, e.byte > 0 ? e.byte - 1 : 0) + ": malformed JSON: " + what);
  } catch (const json::exception& e) {  // a number past a double's range (1e400)
    throw SceneError(path + ":" + line_column(text, json_error_offset(text, e.what())) + ": " + e.what());
  }
  return j;
}

// One parameter of an object's "params" or "small", checked by its kind (counts, sizes, lists).
void check_object_param(Node& pn, const std::string& pk, const json& pv, const SceneObject& obj) {
  auto v = pn.child(pk);
  if (pk == "model_opacity" || pk == "opaque_unless_translucent") {
    v.boolean();
  } else if (pk == "alpha_by_material") {
    v.expect_object({});
    for (const auto& [mk, mv] : pv.items()) v.child(mk).number(0, 1);
  } else if (pk == "exclude_materials") {
    if (!pv.is_array()) v.fail("expected an array of model material names");
    for (size_t e = 0; e < pv.size(); ++e) v.element(e).str();
  } else if (pk == "offset") {
    v.vec3();
  } else if (pk == "colours" || pk == "alphas") {
    if (!pv.is_array())
      v.fail(pk == "colours" ? "expected an array of [r, g, b], one per plane"
                             : "expected an array of alphas, one per plane");
    for (size_t e = 0; e < pv.size(); ++e)
      pk == "colours" ? (void)v.element(e).vec3(0, 1) : (void)v.element(e).number(0, 1);
  } else if ((pk == "grid" || pk == "spacing") && pv.is_array()) {
    v.vec3(pk == "grid" ? 1 : 0, 1e4);
    if (pk == "grid")
      for (size_t e = 0; e < 3; ++e) v.element(e).integer(1, 1e4);
  } else if (pk == "opacity_min" || pk == "opacity_max") {
    v.number(0, 1);
  } else if (pk == "anisotropy") {
    v.number(1, 1e4);
  } else if (pk == "opacity_shape") {
    if (v.number(0, 1e3) == 0) v.fail("expected an exponent above 0");
  } else if (pk == "lowest_root") {
    v.number(-1, 0.9);                // roots are drawn until one lies above it: near 1 none ever does
  } else if (kCountKeys.count(pk)) {  // counts: whole numbers, never truncated
    double x = v.integer(pk == "grid" ? 1 : 0, 1e7);
    if (pk == "sides" && obj.generator == "strands" && x > 0 && x < 3)
      v.fail("expected 0 (line segments) or 3 and more (tubes), got " + std::to_string(static_cast<int>(x)));
  } else {
    double x = v.number(0, pk == "colour_mix" ? 1 : 1e7);
    // A size of 0 makes primitives without area: every case would capture nothing and pass.
    if (x == 0 && kPositiveKeys.count(pk))
      v.fail("expected a number above 0 (0 makes primitives without area, so nothing is drawn)");
  }
}

// "planes": colours and alphas lists hold one entry per plane (count), in params and in small.
void check_plane_lists(Node& o, const SceneObject& obj) {
  if (obj.generator != "planes") return;
  for_each_parameter_set(obj, [&](const json& merged, bool params) {
    size_t count = merged.contains("count") ? merged["count"].get<size_t>() : 128;
    for (const char* list : {"colours", "alphas"})
      if (merged.contains(list) && merged[list].size() != count)
        o.child(params || !obj.small.contains(list) ? "params" : "small")
            .child(list)
            .fail("expected " + std::to_string(count) + " entries (one per plane: count), got " +
                  std::to_string(merged[list].size()));
  });
}

// One entry of "objects": its generator, material, params and small.
SceneObject parse_object(Node o, const SceneDesc& s) {
  o.expect_object({"generator", "material", "params", "small", "file"});
  SceneObject obj;
  if (!o.has("generator"))
    o.fail("expected \"generator\": one of planes, hairball, strands, smoke, model, splats, ply");
  obj.generator = o.child("generator").str();
  if (std::find(kGenerators.begin(), kGenerators.end(), obj.generator) == kGenerators.end())
    o.child("generator")
        .fail("unknown generator \"" + obj.generator +
              "\"; expected planes, hairball, strands, smoke, model, splats or ply");
  if (obj.generator == "model" || obj.generator == "ply") {
    if (!o.has("file"))
      o.fail(obj.generator == "model" ? "expected \"file\": the model file (searched in model_roots)"
                                      : "expected \"file\": the 3DGS PLY file (searched like model files)");
    obj.file = o.child("file").str();
  }
  if (!o.has("material")) o.fail("expected \"material\": the name of one of the scene's materials");
  obj.material = o.child("material").str();
  bool known =
      std::any_of(s.materials.begin(), s.materials.end(), [&](const Material& m) { return m.name == obj.material; });
  if (!known) o.child("material").fail("no material named \"" + obj.material + "\" in \"materials\"");
  for (const char* key : {"params", "small"}) {
    if (!o.has(key)) continue;
    auto pn = o.child(key);
    pn.expect_object({"count",
                      "half_size",
                      "depth",
                      "strands",
                      "segments",
                      "sides",
                      "segment_length",
                      "tube_radius",
                      "radius",
                      "wiggle",
                      "seed",
                      "per_strand",
                      "head_radius",
                      "gravity",
                      "curl",
                      "lowest_root",
                      "size",
                      "spread",
                      "height",
                      "grid",
                      "spacing",
                      "colour_mix",
                      "model_opacity",
                      "opaque_unless_translucent",
                      "alpha_by_material",
                      "exclude_materials",
                      "offset",
                      "colours",
                      "alphas",
                      "clusters",
                      "scale_min",
                      "scale_max",
                      "anisotropy",
                      "opacity_min",
                      "opacity_max",
                      "opacity_shape"});
    for (const auto& [pk, pv] : pn.raw().items()) check_object_param(pn, pk, pv, obj);
    (std::string(key) == "params" ? obj.params : obj.small) = pn.raw();
  }
  if (obj.params.is_null()) obj.params = json::object();
  check_plane_lists(o, obj);
  check_splat_params(o, obj);
  return obj;
}

void parse_materials(const Node& root, SceneDesc& s) {
  auto material = [&](const std::string& k, const Node& n) {
    Material m;
    m.name = k;
    if (n.has("colour")) m.colour = n.child("colour").vec3(0, 1);
    if (n.has("alpha")) m.alpha = static_cast<float>(n.child("alpha").number(0, 1));
    if (n.has("opaque")) m.opaque = n.child("opaque").boolean();
    if (n.has("soft")) m.soft = n.child("soft").boolean();
    if (m.opaque) m.alpha = 1.0f;
    s.materials.push_back(m);
  };
  root.for_each_named("materials", "expected \"materials\": {\"NAME\": {\"colour\": [r, g, b], \"alpha\": a}}",
                      {"colour", "alpha", "opaque", "soft"}, material);
}

void parse_views(const Node& root, SceneDesc& s) {
  auto view_of = [&](const std::string& k, const Node& n) {
    View view;
    view.name = k;
    if (!n.has("eye")) n.fail("expected \"eye\": [x, y, z]");
    view.eye = n.child("eye").vec3();
    if (n.has("target")) view.target = n.child("target").vec3();
    if (n.has("up")) view.up = n.child("up").vec3();
    if (n.has("fov")) view.fov_deg = static_cast<float>(n.child("fov").number(1, 170));
    if (n.has("order")) view.order = parse_order(n.child("order"));
    if (glm::length(view.eye - view.target) < 1e-6f) n.fail("eye and target coincide");
    if (glm::length(glm::cross(glm::normalize(view.target - view.eye), view.up)) < 1e-4f)
      n.fail("\"up\" is parallel to the view direction (or zero); give an up vector across it");
    s.views.push_back(view);
  };
  Node views = root.for_each_named("views", "expected \"views\": {\"NAME\": {\"eye\": [x, y, z], ...}}",
                                   {"eye", "target", "up", "fov", "order"}, view_of);
  if (s.views.empty()) views.fail("expected at least one view");
}

}  // namespace

const std::vector<std::string>& effect_names() {
  static const std::vector<std::string> names = {"opaque", "transparency", "self-shadowing"};
  return names;
}

bool SceneDesc::has_effect(const std::string& e) const {
  return std::find(effects.begin(), effects.end(), e) != effects.end();
}

const View& SceneDesc::view(const std::string& n) const {
  for (const auto& v : views)
    if (v.name == n) return v;
  std::string list;
  for (const auto& v : views) list += (list.empty() ? "" : ", ") + v.name;
  throw SceneError(path + ": scene \"" + name + "\" has no view \"" + n + "\"; views: " + list);
}

const Material& SceneDesc::material(const std::string& n) const {
  for (const auto& m : materials)
    if (m.name == n) return m;
  throw SceneError(path + ": scene \"" + name + "\" has no material \"" + n + "\"");
}

SceneDesc parse_scene(const std::string& path, const std::string& text) {
  json j = parse_json(path, text);
  Node root(j, path, text, {});
  root.expect_object(
      {"name", "description", "background", "effects", "light", "materials", "objects", "views", "model_roots"});
  SceneDesc s;
  s.path = path;
  s.name = root.has("name") ? root.child("name").str() : std::filesystem::path(path).stem().string();
  if (root.has("description")) s.description = root.child("description").str();
  if (root.has("model_roots")) {
    auto r = root.child("model_roots");
    if (!r.raw().is_array()) r.fail("expected an array of folders");
    for (size_t i = 0; i < r.raw().size(); ++i) s.model_roots.push_back(r.element(i).str());
  }
  if (root.has("background")) s.background = root.child("background").vec3(0, 1);
  parse_materials(root, s);
  if (!root.has("objects")) root.fail("expected \"objects\": [{\"generator\": ..., \"material\": ...}]");
  auto objs = root.child("objects");
  if (!objs.raw().is_array() || objs.raw().empty()) objs.fail("expected a non-empty array of objects");
  for (size_t i = 0; i < objs.raw().size(); ++i) {
    s.objects.push_back(parse_object(objs.element(i), s));
  }
  parse_light_and_effects(root, s);
  parse_views(root, s);
  return s;
}

std::string default_scene_dir() { return data_dir("scenes"); }

SceneDesc load_scene(const std::string& name_or_path) {
  std::filesystem::path path = name_or_path;
  bool is_path = name_or_path.find('/') != std::string::npos || name_or_path.ends_with(".json");
  if (!is_path) path = std::filesystem::path(default_scene_dir()) / (name_or_path + ".json");
  std::error_code exists_ec;
  if (!std::filesystem::exists(path, exists_ec)) {
    std::string names;
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(default_scene_dir(), ec))
      if (e.path().extension() == ".json") names += (names.empty() ? "" : ", ") + e.path().stem().string();
    throw SceneError("scene '" + name_or_path + "': cannot read " + path.string() + "; scenes in " +
                     default_scene_dir() + ": " + (names.empty() ? "(none)" : names));
  }
  try {
    return parse_scene(path.string(), read_text_file(path.string(), "scene file"));
  } catch (const FileError& e) {
    throw SceneError(e.what());
  }
}

void check_model_files(const SceneDesc& scene) { check_model_files_of(scene); }

namespace {

// Each object's parameters at `detail` (its "small" overrides applied).
std::vector<json> object_params(const SceneDesc& scene, Detail detail) {
  std::vector<json> params;
  for (const auto& o : scene.objects) {
    json p = o.params;
    if (detail == Detail::Small && o.small.is_object())
      for (const auto& [k, v] : o.small.items()) p[k] = v;
    params.push_back(std::move(p));
  }
  return params;
}

}  // namespace

double scene_splat_count(const SceneDesc& scene, Detail detail) {
  const std::vector<json> params = object_params(scene, detail);
  double splats = 0;
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    std::string why;
    const std::string& g = scene.objects[i].generator;
    if (g == "ply")
      splats += estimate_ply(scene, i, params[i], why).splats;
    else if (g == "splats")
      splats += estimate_object(scene.objects[i], params[i], why).splats;
  }
  return splats;
}

Mesh build_mesh(const SceneDesc& scene, const View& view, Detail detail, bool split_opaque,
                unsigned long long max_bytes) {
  const std::vector<json> params = object_params(scene, detail);
  // Bound the work before any of it: the procedural objects' sizes from their parameters (a model's
  // once its file is read, before its instances are made).
  MeshEstimate total;
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    std::string why;
    MeshEstimate e = scene.objects[i].generator == "ply" ? estimate_ply(scene, i, params[i], why)
                                                         : estimate_object(scene.objects[i], params[i], why);
    total = {total.vertices + e.vertices, total.indices + e.indices, total.primitives + e.primitives,
             total.splats + e.splats};
    check_mesh_size(total, scene, i, why, max_bytes);
  }
  Builder b;
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const auto& o = scene.objects[i];
    const json& p = params[i];
    const Material& m = scene.material(o.material);
    b.opaque = m.opaque;
    if (o.generator == "planes")
      gen_planes(b, p, m);
    else if (o.generator == "hairball")
      gen_hairball(b, p, m);
    else if (o.generator == "strands")
      gen_strands(b, p, m);
    else if (o.generator == "model")
      gen_model(b, p, m, resolve_model(scene, o.file), scene, i, total, max_bytes);
    else if (o.generator == "splats")
      append_splats(b.mesh.splats, generate_splats(splat_generator_params(p), m));
    else if (o.generator == "ply")
      append_splats(b.mesh.splats, gen_ply(scene, i, p, view));
    else
      gen_smoke(b, p, m, view);
  }
  order_splats(b.mesh.splats, view);
  // Reorder whole primitives by their centroid's distance to the eye (stable: ties keep generation order).
  std::vector<size_t> order(b.groups.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  if (view.order != SubmitOrder::AsGenerated) {
    std::vector<float> dist(b.groups.size());
    for (size_t i = 0; i < order.size(); ++i) dist[i] = glm::length(b.centroids[i] - view.eye);
    bool front_to_back = view.order == SubmitOrder::FrontToBack;
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t c) { return front_to_back ? dist[a] < dist[c] : dist[a] > dist[c]; });
  }
  std::vector<unsigned> indices, opaque, lines;
  indices.reserve(b.mesh.indices.size());
  lines.reserve(b.mesh.line_indices.size());
  for (size_t g : order) {
    auto [first, count] = b.groups[g];
    if (b.group_lines[g]) {
      lines.insert(lines.end(), b.mesh.line_indices.begin() + first, b.mesh.line_indices.begin() + first + count);
      continue;
    }
    auto& out = split_opaque && b.group_opaque[g] ? opaque : indices;
    out.insert(out.end(), b.mesh.indices.begin() + first, b.mesh.indices.begin() + first + count);
  }
  b.mesh.indices = std::move(indices);
  b.mesh.opaque_indices = std::move(opaque);
  b.mesh.line_indices = std::move(lines);
  return std::move(b.mesh);
}

std::optional<std::vector<AnalyticPlane>> analytic_planes(const SceneDesc& scene, Detail detail) {
  std::vector<AnalyticPlane> out;
  for (const auto& o : scene.objects) {
    if (o.generator != "planes") return std::nullopt;
    json p = o.params;
    if (detail == Detail::Small && o.small.is_object())
      for (const auto& [k, v] : o.small.items()) p[k] = v;
    for (const auto& pl : planes_of(p, scene.material(o.material))) out.push_back(pl);
  }
  return out;
}

glm::mat4 view_projection(const View& view, const Mesh& mesh, float aspect) {
  glm::vec2 nf = near_far(view, mesh);
  return glm::perspective(glm::radians(view.fov_deg), aspect, nf.x, nf.y) * glm::lookAt(view.eye, view.target, view.up);
}

glm::vec2 near_far(const View& view, const Mesh& mesh) {
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const auto& v : mesh.vertices) {
    lo = glm::min(lo, v.position);
    hi = glm::max(hi, v.position);
  }
  for (const auto& s : mesh.splats) {  // a splat reaches 3 standard deviations (what the rasteriser draws)
    const float r = 3.0f * std::max({s.scale.x, s.scale.y, s.scale.z});
    lo = glm::min(lo, s.position - r);
    hi = glm::max(hi, s.position + r);
  }
  glm::vec3 centre = (lo + hi) * 0.5f;
  float radius = glm::length(hi - lo) * 0.5f;
  float dist = glm::length(centre - view.eye);
  float near_plane = std::max(0.01f, dist - radius - 0.01f), far_plane = dist + radius + 0.01f;
  return {near_plane, far_plane};
}

}  // namespace oitbench::oit
