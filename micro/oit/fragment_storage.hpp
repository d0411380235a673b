#pragma once
// Where the exact techniques keep every captured fragment (Knowles, Leach, Zambetta 2014, section
// 2.2): per-pixel linked lists, PPLL (fragment_lists.hpp), or packed per-pixel arrays, PPPA
// (packed_arrays.hpp: count pass, prefix sum, fill). Shaders read either through the one API of
// shaders/oit/storage/fragments.glsl, selected by the storage's defines(); the resolves, the sorts
// and the CPU side are written once.
#include <cstddef>
#include <functional>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

#include "core/registry.hpp"
#include "gl/gl_objects.hpp"
#include "gl/shader.hpp"

namespace oitbench::oit {

inline constexpr unsigned kListEnd = 0xFFFFFFFFu;

// Image units and bindings of shaders/oit/storage/*.glsl. Unit 1 (the fragments) is shared.
inline constexpr GLuint kHeadsUnit = 0, kNodesUnit = 1, kNextUnit = 2, kCountsUnit = 3, kCounterBinding = 0,
                        kOffsetsBinding = 2;

// The fragments as read back to the CPU (the input of the CPU reference and of CPU-NATIVE), as
// lists whatever the layout: a packed array reads back as lists whose next node is the next slot.
struct HostLists {
  int width = 0, height = 0;
  std::vector<unsigned> heads;    // width*height, row-major from the bottom row
  std::vector<glm::uvec2> nodes;  // (packUnorm4x8 colour, floatBitsToUint depth)
  std::vector<unsigned> next;
  std::vector<unsigned> counts;  // per-pixel counts when captured with counts, else empty
  std::string error;             // what the layout's own read-back check found wrong, else empty
};

enum class CaptureStorage { PPLL, PPPA };
const std::vector<std::string>& capture_storage_names();        // "PPLL", "PPPA"
CaptureStorage parse_capture_storage(const std::string& name);  // throws std::invalid_argument

class FragmentStorage {
 public:
  virtual ~FragmentStorage() = default;
  virtual CaptureStorage kind() const = 0;
  // For every shader that includes storage/fragments.glsl: selects this layout.
  virtual Defines defines() const = 0;
  // One entry per pass of the geometry a capture takes: what that pass's program adds to defines().
  virtual std::vector<Defines> capture_passes() const = 0;
  // Captures a frame: for each pass, programs[i] (built from capture_passes()[i], see
  // build_capture_programs) is current while `draw` submits the geometry. Returns how often the
  // frame was rendered again because the pool was too small (fragments are never dropped).
  virtual int capture(const std::vector<GLuint>& programs, const std::function<void()>& draw) = 0;
  virtual void bind() const = 0;         // images and buffers for a pass that reads the fragments
  virtual size_t fragments() const = 0;  // captured in the last frame
  virtual size_t pool() const = 0;       // fragments the storage holds room for
  virtual size_t bytes() const = 0;      // GPU memory it holds
  virtual bool with_counts() const = 0;  // per-pixel counts exist (fragCounts, image unit 3)
  virtual HostLists read_back() const = 0;
};

// A buffer of `texels` seen as an image buffer of `format` (`texel_bytes` each): the fragments of
// both layouts, PPLL's next pointers. Throws Unsupported past GL_MAX_TEXTURE_BUFFER_SIZE, naming `what`.
struct TexelBuffer {
  gl::Buffer buffer;
  gl::Texture view;
};
TexelBuffer make_texel_buffer(size_t texels, GLenum format, size_t texel_bytes, const std::string& what);

// `with_counts`: PPLL also counts each pixel's fragments (BMA); PPPA always does.
std::unique_ptr<FragmentStorage> make_fragment_storage(CaptureStorage kind, const CaseContext& ctx, size_t initial_pool,
                                                       bool with_counts);

// The capture programs of `storage` from `stages` (a fragment shader that calls store_fragment()),
// with `extra` defines (an effect's, e.g. OpacityShadowMap::defines()).
std::vector<gl::Program> build_capture_programs(const FragmentStorage& storage, const CaseContext& ctx,
                                                const std::vector<ShaderStage>& stages, const Defines& extra = {});
std::vector<GLuint> ids(const std::vector<gl::Program>& programs);

}  // namespace oitbench::oit
