// layout: per-pixel storage layouts (Brüll 2018, section 4.1, Eq. 4.1/4.2, Table 4.1).
// One read-modify-write workload (shaders/layout/layout.frag: every fragment loads its pixel's n
// nodes, adds to each, stores them back) over `layers` overlapping screen-filling quads per draw,
// `draws` draws, with the storage picked by one injected define (shaders/storage/).
#include <cstdint>
#include <memory>
#include <string>

#include "core/registry.hpp"
#include "oit/storage/storage_layout.hpp"

namespace oitbench {

namespace {

// The same function as node_value() in shaders/layout/layout.frag.
std::uint32_t layout_node_value(int x, int y, int i) {
  return ((static_cast<std::uint32_t>(x) * 73856093u) ^ (static_cast<std::uint32_t>(y) * 19349663u) ^
          (static_cast<std::uint32_t>(i) * 83492791u)) |
         1u;
}

class LayoutCase final : public CaseInstance {
 public:
  LayoutCase(const ParamSet& p, CaseContext& ctx)
      : layout_(StorageLayout::parse(p.get("layout"))),
        nodes_(static_cast<int>(p.get_int("nodes"))),
        layers_(static_cast<int>(p.get_int("layers"))),
        draws_(static_cast<int>(p.get_int("draws"))),
        width_(ctx.width()),
        height_(ctx.height()),
        storage_(layout_, width_, height_, nodes_),
        fbo_(storage_only_framebuffer(width_, height_)),
        vao_(gl::make_vertex_array()) {
    Defines defines = layout_.defines(width_, height_, nodes_);
    if (p.get("order") == "scattered") defines.push_back({"ORDER_SCATTERED", ""});
    program_ =
        ctx.build({{GL_VERTEX_SHADER, "common/layers.vert"}, {GL_FRAGMENT_SHADER, "layout/layout.frag"}}, defines);
    glProgramUniform1i(program_.get(), glGetUniformLocation(program_.get(), "zero"), 0);
  }

  void run(PassTimer& timer) override {
    {
      auto t = timer.pass("clear");
      storage_.clear();
    }
    auto t = timer.pass("update");
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
    glViewport(0, 0, width_, height_);
    glUseProgram(program_.get());
    glBindVertexArray(vao_.get());
    storage_.bind();
    for (int d = 0; d < draws_; ++d) {
      glDrawArrays(GL_TRIANGLES, 0, 6 * layers_);
      // Draws are ordered by the barrier; fragments within one draw are not ordered at all.
      StorageResources::barrier();
    }
  }

  // Exact when layers == 1 (one fragment per pixel per draw, barriers between draws): every node
  // must be (draws * value, draws). With layers > 1 fragments of one pixel may run concurrently
  // (GL orders neither them nor their read-modify-writes without a lock or interlock), so a
  // count below layers * draws is a lost update: counted, not a failure. Whatever was lost, a
  // node written whole is self-consistent (sum == count * value, count <= layers * draws); an
  // inconsistent node (wrong address, torn or corrupted write) always fails.
  Validation validate() override {
    auto got = storage_.read_back();
    const std::uint32_t expected = static_cast<std::uint32_t>(layers_) * static_cast<std::uint32_t>(draws_);
    long long lost = 0, lost_pixels = 0, inconsistent = 0;
    std::string first_bad, first_lost;
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < width_; ++x) {
        bool pixel_lost = false;
        for (int i = 0; i < nodes_; ++i) {
          const auto& n = got[(static_cast<std::size_t>(y) * width_ + x) * nodes_ + i];
          std::uint32_t v = layout_node_value(x, y, i);
          std::string where = "pixel (" + std::to_string(x) + "," + std::to_string(y) + ") node " + std::to_string(i);
          if (n[1] > expected || n[0] != n[1] * v) {
            if (inconsistent++ == 0)
              first_bad = where + " = (" + std::to_string(n[0]) + ", " + std::to_string(n[1]) + "), expected (" +
                          std::to_string(expected * v) + ", " + std::to_string(expected) + ")";
            continue;
          }
          if (n[1] < expected) {
            if (lost == 0) first_lost = where + " counted " + std::to_string(n[1]) + " of " + std::to_string(expected);
            lost += expected - n[1];
            pixel_lost = true;
          }
        }
        lost_pixels += pixel_lost;
      }
    Validation v;
    v.metrics["lost_updates"] = std::to_string(lost);
    v.metrics["lost_pixels"] = std::to_string(lost_pixels);
    v.metrics["inconsistent_nodes"] = std::to_string(inconsistent);
    const bool race_free = layers_ == 1;
    v.valid = inconsistent == 0 && (lost == 0 || !race_free);
    if (inconsistent > 0)
      v.reason =
          std::to_string(inconsistent) + " node(s) no sequence of whole updates can produce; first: " + first_bad;
    else if (lost > 0 && race_free)
      v.reason = std::to_string(lost) + " node update(s) lost in a race-free case (layers=1); first: " + first_lost;
    else if (lost > 0)
      v.reason = std::to_string(lost) +
                 " node update(s) lost to races within a draw (layers > 1, counted, not a "
                 "failure); first: " +
                 first_lost;
    return v;
  }

 private:
  StorageLayout layout_;
  int nodes_, layers_, draws_, width_, height_;
  StorageResources storage_;
  gl::Framebuffer fbo_;
  gl::VertexArray vao_;
  gl::Program program_;
};

class LayoutExperiment final : public ExperimentOf<LayoutCase> {
 public:
  LayoutExperiment()
      : ExperimentOf("layout",
                     "per-pixel storage layouts (Bruell 2018, Eq. 4.1/4.2, Table 4.1): the same node-array "
                     "read-modify-write as ssbo, texture3d, interleaved SSBO (group, alignment) or buffer-texture "
                     "reads; lost updates counted",
                     {800, 800}, {128, 128}) {}  // the thesis's
  std::vector<ParamSpec> params() const override {
    // The compared parameter last: the grid's innermost loop, so one interleaved group holds all layouts.
    return {
        ParamSpec::integer("nodes", "nodes (uvec2) per pixel", 4, 32, {"4", "8", "16"}, {"4"}),
        ParamSpec::integer("layers", "overlapping screen-filling layers per draw (1: race-free and exact)", 1, 4096,
                           {"8"}, {"4"}),
        ParamSpec::integer("draws", "draws per repetition (barrier between draws)", 1, 4096, {"2"}, {"2"}),
        ParamSpec::choice("order",
                          "store order: sequential, or scattered (a per-fragment rotation, like an unordered per-pixel "
                          "insertion's writes)",
                          {"sequential", "scattered"}, {"sequential"}),
        ParamSpec::choice("layout",
                          "storage: ssbo (Eq. 4.1), texture3d (image3D), texbuffer (Eq. 4.1 read through a "
                          "buffer texture), interleaved-GXxGY-aA (Eq. 4.2, gx x gy groups, nodes in runs of A)",
                          StorageLayout::names(), {},
                          {"ssbo", "texture3d", "texbuffer", "interleaved-2x4-a1", "interleaved-2x4-a4"})};
  }
  std::vector<MetricSpec> metric_specs() const override {
    return {{"lost_updates", ValueType::Integer, "", "writes that did not land"},
            {"lost_pixels", ValueType::Integer, "", "pixels with at least one lost write"},
            {"inconsistent_nodes", ValueType::Integer, "", "nodes whose halves disagree (a torn write)"}};
  }
  // All 15 layouts of one grid point interleaved (paired comparison): up to 82 MB each at 800x800, n=16.
  int max_interleave(Resolution) const override { return 15; }
  std::string unsupported_reason(const GlInfo&, const ParamSet& p) const override {
    auto l = StorageLayout::parse(p.get("layout"));
    if (l.kind == StorageLayout::Kind::Interleaved && p.get_int("nodes") % l.align != 0)
      return "nodes=" + p.get("nodes") + " is not a multiple of the alignment " + std::to_string(l.align);
    return "";
  }
};

}  // namespace

void register_layout(Registry& registry) { registry.add(std::make_unique<LayoutExperiment>()); }

}  // namespace oitbench
