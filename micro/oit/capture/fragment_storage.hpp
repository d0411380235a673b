#pragma once
// Where the exact techniques keep every captured fragment (Knowles, Leach, Zambetta 2014, section
// 2.2): per-pixel linked lists, PPLL (fragment_lists.hpp), or packed per-pixel arrays, PPPA
// (packed_arrays.hpp: count pass, prefix sum, fill). Shaders read either through the one API of
// shaders/capture/fragment_storage.glsl, selected by the storage's defines(); the resolves, the sorts
// and the CPU side are written once.
#include <array>
#include <cstddef>
#include <functional>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/memory_budget.hpp"
#include "core/registry.hpp"
#include "gl/gl_objects.hpp"
#include "gl/shader.hpp"
#include "shaders/capture/bindings.h"

namespace oitbench::oit {

inline constexpr unsigned kListEnd = 0xFFFFFFFFu;

// Image units and bindings of shaders/capture/*.glsl. Unit 1 (the fragments) is shared; unit 5
// holds the depths of the wide colour formats (docs/precision.md).
inline constexpr GLuint kHeadsUnit = CAPTURE_HEADS_UNIT, kNodesUnit = CAPTURE_NODES_UNIT, kNextUnit = CAPTURE_NEXT_UNIT,
                        kCountsUnit = CAPTURE_COUNTS_UNIT, kNodeDepthUnit = CAPTURE_NODE_DEPTH_UNIT,
                        kCounterBinding = CAPTURE_COUNTER_BINDING, kOffsetsBinding = CAPTURE_OFFSETS_BINDING;

// What one captured fragment keeps (the frag_colour and frag_depth parameters; shaders/capture/
// fragments.glsl is written once against them):
//   colour rgba8    packUnorm4x8 (the papers' packing; 8-byte nodes with the depth)
//          rgba16f  two packHalf2x16 words, depth apart (12 bytes)
//          rgba32f  four float words, depth apart (20 bytes)
//   depth  window   gl_FragCoord.z
//          view     the view-space distance along the view axis (clip w), a float32: relative
//                   precision 2^-24 at every distance, where window depth's collapses away from near
// Either depth is >= 0, so its float bits compare as uints (the sorts' key).
enum class FragColour { RGBA8, RGBA16F, RGBA32F };
enum class FragDepth { Window, View };
struct FragFormat {
  FragColour colour = FragColour::RGBA8;
  FragDepth depth = FragDepth::Window;
};
const std::vector<std::string>& frag_colour_names();  // "rgba8", "rgba16f", "rgba32f"
const std::vector<std::string>& frag_depth_names();   // "window", "view"
// Throws std::invalid_argument naming the valid values.
FragFormat parse_frag_format(const std::string& colour, const std::string& depth);
Defines frag_format_defines(FragFormat f);  // FRAG_COLOUR_<X>, FRAG_DEPTH_<X>
size_t frag_node_bytes(FragColour c);       // 8, 12, 20: one fragment's colour and depth

// The fragments as read back to the CPU (the input of the CPU reference and of CPU-NATIVE), as
// lists whatever the layout: a packed array reads back as lists whose next node is the next slot.
struct HostLists {
  int width = 0, height = 0;
  std::vector<unsigned> heads;    // width*height, row-major from the bottom row
  std::vector<glm::uvec2> nodes;  // (packUnorm4x8 colour, floatBitsToUint depth); wide colours: x unused
  FragColour colour = FragColour::RGBA8;
  std::vector<glm::uvec4> wide;  // rgba16f: (half rg, half ba, 0, 0); rgba32f: float bits; else empty
  std::vector<unsigned> next;
  std::vector<unsigned> counts;  // per-pixel counts when captured with counts, else empty
  std::string error;             // what the layout's own read-back check found wrong, else empty
};

// An array of `texels` seen as image buffers of `format` (`texel_bytes` each): the fragments of both
// layouts, PPLL's next pointers. One texel buffer holds at most GL_MAX_TEXTURE_BUFFER_SIZE texels
// (128 Mi on llvmpipe: 197 M fragments do not fit), so the array is split into chunks of the largest
// power of two that fits, each its own buffer and image unit: chunk 0 on the layout's unit, chunk c
// on chunk_unit(slot, c). Shaders select the chunk by the index's high bits (FRAG_CHUNKS,
// FRAG_CHUNK_SHIFT, injected only past one chunk, so the common case compiles exactly as before).
// `min_chunks` keeps at least that many (a pool that shrinks keeps the programs it was built for).
// Throws Unsupported past kMaxChunks chunks, naming `what`.
inline constexpr size_t kMaxChunks = 4;
enum class ChunkSlot : GLuint { Colours = 0, Next = 1, Depths = 2 };
GLuint chunk_unit(GLuint first_unit, ChunkSlot slot, size_t chunk);  // units 8.. hold chunks 1..
size_t max_chunk_texels();                                           // the largest power of two that fits
class ChunkedTexels {
 public:
  ChunkedTexels() = default;
  ChunkedTexels(size_t texels, GLenum format, size_t texel_bytes, const std::string& what, size_t min_chunks = 1);
  size_t chunks() const { return buffers_.size(); }
  unsigned shift() const { return shift_; }
  void bind(GLuint first_unit, ChunkSlot slot) const;
  void read(size_t n, void* out) const;  // the first n texels, across chunks
 private:
  GLenum format_ = GL_R32UI;
  size_t texel_bytes_ = 4;
  unsigned shift_ = 0;
  std::vector<gl::Buffer> buffers_;
  std::vector<gl::Texture> views_;
};

// A node's colour as stored (decoded exactly), and the words equal depths are ordered by: alpha,
// blue, green, red of the stored colour, compared as uints (larger goes farther), as the shaders do.
glm::dvec4 node_colour(const HostLists& h, size_t node);
std::array<unsigned, 4> node_tie_key(const HostLists& h, size_t node);

// Every node's colour and depth words in one or two chunked texel arrays (image units 1 and 5, and
// their chunks'), per format.
class NodePool {
 public:
  NodePool() = default;
  NodePool(size_t pool, FragColour colour, const std::string& what, size_t min_chunks = 1);
  void bind() const;
  void read(size_t n, HostLists& h) const;  // the first n nodes into h.nodes (and h.wide)
  size_t chunks() const { return colours_.chunks(); }
  unsigned shift() const { return colours_.shift(); }

 private:
  FragColour colour_ = FragColour::RGBA8;
  ChunkedTexels colours_, depths_;
};
// FRAG_CHUNKS and FRAG_CHUNK_SHIFT for a pool of `chunks` chunks (nothing for one).
Defines chunk_defines(size_t chunks, unsigned shift);
// How many chunks a pool of `texels` needs.
size_t chunks_for(size_t texels);

enum class CaptureStorage { PPLL, PPPA };
const std::vector<std::string>& capture_storage_names();        // "PPLL", "PPPA"
CaptureStorage parse_capture_storage(const std::string& name);  // throws std::invalid_argument

class FragmentStorage {
 public:
  virtual ~FragmentStorage() = default;
  // Called with a pool size before it is allocated; throws Unsupported when that pool would not fit
  // the case's memory (make_fragment_storage sets it from CaseContext::memory()).
  void set_pool_guard(std::function<void(size_t pool)> guard) { guard_ = std::move(guard); }
  virtual CaptureStorage kind() const = 0;
  // For every shader that includes fragment_storage.glsl: selects this layout.
  virtual Defines defines() const = 0;
  // One entry per pass of the geometry a capture takes: what that pass's program adds to defines().
  virtual std::vector<Defines> capture_passes() const = 0;
  // Captures a frame: for each pass, programs[i] (built from capture_passes()[i], see
  // build_capture_programs) is current while `draw` submits the geometry. Returns how often the
  // frame was rendered again because the pool was too small (fragments are never dropped).
  virtual int capture(const std::vector<GLuint>& programs, const std::function<void()>& draw) = 0;
  virtual void bind() const = 0;         // images and buffers for a pass that reads the fragments
  virtual size_t bytes() const = 0;      // GPU memory it holds
  virtual bool with_counts() const = 0;  // per-pixel counts exist (fragCounts, image unit 3)
  virtual HostLists read_back() const = 0;
  size_t fragments() const { return fragments_; }     // captured in the last frame
  size_t pool() const { return pool_; }               // fragments the storage holds room for
  size_t buffers() const { return nodes_.chunks(); }  // texel buffers each node array is split into

 protected:
  // What both layouts keep: the image's size, the fragment format, the node pool (NodePool) and the
  // fragments of the last frame.
  FragmentStorage(int width, int height, FragFormat format) : width_(width), height_(height), format_(format) {}
  void check_pool(size_t pool) const {
    if (guard_) guard_(pool);
  }
  // The format's defines and the node chunks' (every layout's defines() begins with them).
  Defines node_defines() const;
  // Refuses `pool` through the guard (Unsupported) before anything that large is allocated, then
  // allocates the nodes of `pool` fragments, never in fewer chunks than the programs were built for
  // (defines()), more only past the last one. Returns the chunks.
  size_t allocate_nodes(size_t pool, const std::string& what);

  int width_, height_;
  FragFormat format_;
  size_t pool_ = 0, fragments_ = 0;
  NodePool nodes_;

 private:
  std::function<void(size_t)> guard_;
};

// What a pool of `pool` fragments costs (core/memory_budget.hpp): on the GPU the storage (nodes,
// PPLL's next pointers, the per-pixel heads, counts and offsets); on the CPU the read-back (HostLists
// and the read's temporaries) `host_copies` times, plus the per-pixel buffers of the CPU and geometric
// references and the image comparison (kValidationBytesPerPixel). The CPU reference itself streams:
// it composites one pixel's fragments at a time.
inline constexpr size_t kValidationBytesPerPixel = 160;
MemoryNeed fragment_memory(CaptureStorage kind, FragFormat format, bool with_counts, unsigned long long pool,
                           size_t pixels, int host_copies = 1);

// What a case tells make_fragment_storage about the fragments to come: `expected`, the fragments its
// scene makes (estimate_fragments in oit/scene/coverage_estimate.hpp; 0: unknown), checked against the
// memory limits before anything is allocated; `host_copies`, the read-backs its validation holds at once
// (the opaque effect's unoccluded capture: 3).
struct FragmentBudget {
  unsigned long long expected = 0;
  int host_copies = 1;
  MemoryNeed held = {};  // what the case holds beside the fragments (a splat scene's splats), in every check
};

// The check make_fragment_storage makes first: the expected fragments (and the 1/8 a pool grows by)
// against the case's memory, and against the 32-bit fragment index. For a case that draws before it
// allocates (a count pass that sizes its pool): nothing is drawn for a case that cannot be held.
void require_fragment_budget(CaptureStorage kind, const CaseContext& ctx, bool with_counts, FragFormat format,
                             const FragmentBudget& budget);

// `with_counts`: PPLL also counts each pixel's fragments (BMA); PPPA always does.
// Throws Unsupported, naming the estimate and the limit, when the expected fragments (or the initial
// pool) would not fit the case's memory; later growth of the pool is checked the same way.
std::unique_ptr<FragmentStorage> make_fragment_storage(CaptureStorage kind, const CaseContext& ctx, size_t initial_pool,
                                                       bool with_counts, FragFormat format = {},
                                                       FragmentBudget budget = {});

// The capture programs of `storage` from `stages` (a fragment shader that calls store_fragment()),
// with `extra` defines (an effect's, e.g. OpacityShadowMap::defines()).
std::vector<gl::Program> build_capture_programs(const FragmentStorage& storage, const CaseContext& ctx,
                                                const std::vector<ShaderStage>& stages, const Defines& extra = {});
std::vector<GLuint> ids(const std::vector<gl::Program>& programs);

// Captures a frame with `programs` and, where the pool grew into more texel-buffer chunks than they
// were built for (the fragments past their chunks were not stored), rebuilds them with `build` (which
// also sets their uniforms) and captures again, until the layout holds. Returns the re-renders.
int capture_complete(FragmentStorage& storage, std::vector<gl::Program>& programs,
                     const std::function<std::vector<gl::Program>()>& build, const std::function<void()>& draw);

}  // namespace oitbench::oit
