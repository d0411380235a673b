#pragma once
// Scenes as data: a JSON file in scenes/ names the materials, the objects (each made by a procedural
// generator), the effects the scene needs and the camera views. The format is documented in
// scenes/README.md; build_mesh() turns one view of a scene into triangles and line segments in
// submission order.
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "oit/splats/splat.hpp"

namespace oitbench::oit {

// A malformed or inconsistent scene file; the message starts with "file:line:column:".
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Material {
  std::string name;
  glm::vec3 colour{1.0f};
  float alpha = 0.5f;
  bool opaque = false;  // opaque surfaces hide what lies behind them (alpha forced to 1)
  bool soft = false;    // alpha falls off radially over the primitive's uv (smoke billboards)
};

// Which order the primitives are submitted in, relative to the view's eye. Per-pixel linked lists
// prepend, so front-to-back submission stores each pixel's fragments far-to-near: already sorted
// for the resolves (the best case), and back-to-front the reverse (the worst case).
enum class SubmitOrder { AsGenerated, FrontToBack, BackToFront };

struct View {
  std::string name;
  glm::vec3 eye{0, 0, 3}, target{0, 0, 0}, up{0, 1, 0};
  float fov_deg = 45.0f;
  SubmitOrder order = SubmitOrder::AsGenerated;
};

// A light for the self-shadowing effect: a spot light looking from `eye` at `target` whose
// frustum (`fov`) holds what it lights; `ambient` is the light a fully shadowed fragment keeps.
struct Light {
  glm::vec3 eye{0, 3, 0}, target{0, 0, 0}, up{0, 0, 1};
  float fov_deg = 45.0f;
  float ambient = 0.25f;
};

// The effects a scene can declare ("effects": [...]); each contributes passes (docs/effects.md).
//   transparency   capture and resolve of the transparent primitives (exact and approximate OIT)
//   opaque         the opaque primitives drawn first into colour and depth; transparent fragments
//                  captured against that depth and composited over that colour
//   self-shadowing an opacity shadow map from the scene's light, read by every shaded fragment
const std::vector<std::string>& effect_names();

struct SceneObject {
  std::string generator;  // planes | hairball | strands | smoke | model | splats | ply
  std::string file;       // model, ply: the model or splat file, resolved against the scene's model_roots
  nlohmann::json params;  // the generator's parameters, "small" overrides already applied when asked
  nlohmann::json small;   // overrides for the small (quick/test) size
  std::string material;
};

struct SceneDesc {
  std::string name, description, path;
  glm::vec3 background{1.0f};
  std::vector<std::string> effects;      // declared effects, in effect_names() order
  std::optional<Light> light;            // required by self-shadowing
  std::vector<std::string> model_roots;  // folders searched for model files (after the scene's own folder)
  std::vector<Material> materials;
  std::vector<SceneObject> objects;
  std::vector<View> views;

  bool has_effect(const std::string& e) const;
  const View& view(const std::string& name) const;          // throws SceneError listing the views
  const Material& material(const std::string& name) const;  // throws SceneError
};

enum class Detail { Full, Small };

// Parses a scene; every error names `path`, the line and column and what was expected.
SceneDesc parse_scene(const std::string& path, const std::string& text);
// A name ("planes") is looked up in the scene directory; anything with '/' or ".json" is a path.
SceneDesc load_scene(const std::string& name_or_path);
std::string default_scene_dir();  // $OITBENCH_SCENES, else scenes/ beside the binary or the source tree

struct Vertex {
  glm::vec3 position;
  glm::vec4 colour;  // straight alpha, float: the capture quantises it to the fragment format (frag_colour)
  glm::vec2 uv;      // used by soft materials
  float soft;        // 1 for soft materials
};

struct Mesh {
  std::vector<Vertex> vertices;
  std::vector<unsigned> indices;         // transparent triangles, in submission order
  std::vector<unsigned> opaque_indices;  // opaque triangles (only when built with split_opaque)
  // Line segments (hair strands), two vertex indices each, in submission order; drawn as GL_LINES
  // after the triangles. Always captured: a strand of an opaque material has alpha 1 but stays here.
  std::vector<unsigned> line_indices;
  // Gaussian splats (generators "splats" and "ply"), in submission order, their colours evaluated for
  // the view the mesh was built for; always transparent, drawn by the splat rasteriser (shaders/splats/).
  SplatList splats;
  size_t triangles() const { return (indices.size() + opaque_indices.size()) / 3; }
  size_t segments() const { return line_indices.size() / 2; }
  // Primitives: triangles plus line segments plus splats (what the `polygons` metric counts).
  size_t polygons() const { return triangles() + segments() + splats.size(); }
};

// Generates every object for `view` (billboards face its eye) and orders the primitives (a triangle
// group, or one line segment) as the view asks.
// split_opaque: primitives of opaque materials go to opaque_indices (the opaque effect draws them);
// otherwise they stay in `indices` with alpha 1, captured like any other fragment.
// Throws SceneError naming the file, the object and its parameters when the mesh would take more than
// `max_bytes` (estimated from the parameters, and for a model from its file, before anything is made).
// Throws SceneError naming the scene file and the object when a model file is missing or is not a regular
// file of bounded size (a folder, /dev/null): checked before any case runs.
void check_model_files(const SceneDesc& scene);

inline constexpr unsigned long long kMaxMeshBytes = 4ull << 30;
// The splats build_mesh would make of `scene` at `detail` (its "splats" objects' counts, its "ply" objects'
// header counts), counted before anything is built; 0 for a scene without splats. A bad PLY file is a SceneError.
double scene_splat_count(const SceneDesc& scene, Detail detail);
Mesh build_mesh(const SceneDesc& scene, const View& view, Detail detail, bool split_opaque = false,
                unsigned long long max_bytes = kMaxMeshBytes);

// The planes generator's planes of a scene, exactly as described (centre, half size, colour, alpha):
// what the geometric reference (geometric_reference.hpp) intersects pixel rays with. Empty when the
// scene has an object of another generator, whose answer is not analytic.
struct AnalyticPlane {
  glm::dvec3 centre;  // the square faces +z
  double half_size;
  glm::vec4 colour;  // as the vertices carry it
};
std::optional<std::vector<AnalyticPlane>> analytic_planes(const SceneDesc& scene, Detail detail);

// The camera's view-projection for an aspect ratio; near and far planes (near_far) enclose the mesh.
glm::mat4 view_projection(const View& view, const Mesh& mesh, float aspect);
glm::vec2 near_far(const View& view, const Mesh& mesh);

}  // namespace oitbench::oit
