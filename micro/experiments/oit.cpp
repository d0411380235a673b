// oit: exact order-independent transparency (Knowles, Leach, Zambetta 2013 BMA and 2014 RBS;
// micro/oit/exact/exact_case.cpp) and approximate OIT (Brüll 2018; micro/oit/approx/approx_case.cpp) on scenes kept
// as data (scenes/*.json). This file declares the parameter grid; the cases live in micro/oit/
// so that `oitbench view` renders with the same code.
#include <algorithm>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "core/registry.hpp"
#include "oit/approx/approx.hpp"
#include "oit/capture/fragment_storage.hpp"
#include "oit/case_support.hpp"
#include "oit/moments/moments.hpp"
#include "oit/oit_case.hpp"
#include "oit/peel/peel.hpp"
#include "oit/reference/metrics.hpp"
#include "oit/resolve/resolve_sort.hpp"
#include "oit/scene/scene.hpp"
#include "oit/scene/scene_passes.hpp"
#include "oit/slab/slab.hpp"
#include "oit/splats/gpu_splats.hpp"
#include "oit/splats/popping.hpp"
#include "oit/techniques.hpp"
#include "oit/wavelets/wavelets.hpp"

namespace oitbench {

namespace {

using namespace oit;

// Whether a case's scene and effects hold self-shadowing, each (scene, effects) loaded once. A scene
// that does not load counts as holding it: check_cases reports it (FILE:LINE:COLUMN).
std::function<bool(const ParamSet&)> holds_self_shadowing() {
  auto known = std::make_shared<std::map<std::pair<std::string, std::string>, bool>>();
  return [known](const ParamSet& c) {
    if (!c.has("scene") || !c.has("effects")) return true;
    const auto key = std::make_pair(c.get("scene"), c.get("effects"));
    if (auto it = known->find(key); it != known->end()) return it->second;
    bool holds = true;
    try {
      const auto effects = select_effects(load_scene(key.first), key.second);
      holds = std::find(effects.begin(), effects.end(), "self-shadowing") != effects.end();
    } catch (const std::exception&) {
    }
    return (*known)[key] = holds;
  };
}

std::vector<std::string> techniques_where(bool Technique::*member) {
  std::vector<std::string> out;
  for (const auto& t : techniques())
    if (t.*member) out.push_back(t.name);
  return out;
}

// The exact techniques' parameters (each scoped by the technique table to the techniques that read it).
struct ExactParams {
  ParamSpec block, pool, max_frags, cs_group, auto_cache, frag_colour, frag_depth, block_sort, order_check;
};
ExactParams exact_params() {
  ParamSpec block =
      ParamSpec::choice("block", "RBS block size MAX_REGISTERS (the paper: 32)", {"4", "8", "16", "32"}, {"32"}, {"8"});
  ParamSpec pool = ParamSpec::integer(
      "initial_pool",
      "first node pool in fragments (0: sized by a count pass, so the first capture never overflows); later "
      "frames size it from the last count",
      0, 1e9, {"0"});
  ParamSpec max_frags = ParamSpec::integer(
      "max_frags", "MAX_FRAGS (0: next power of two at or above the view's peak depth)", 0, 4096, {"0"});
  ParamSpec cs_group =
      ParamSpec::choice("cs_group",
                        "compute resolve's work group in pixels; sides that are multiples of 4 (8x8, the default, "
                        "and 4x4) run in 4x4 blocks as a fragment shader's vectors do, others (8x1, ...) in rows "
                        "(shaders/resolve/resolve.comp)",
                        {"8x1", "8x8", "4x4", "16x1", "32x1", "64x1"}, {"8x8"});
  ParamSpec auto_cache = ParamSpec::choice("bma_auto_cache",
                                           "on: reads and writes the per-driver choice cache "
                                           "($XDG_CACHE_HOME/oitbench/bma_auto.json); off calibrates every case afresh",
                                           {"on", "off"}, {"on"});
  ParamSpec frag_colour = ParamSpec::choice(
      "frag_colour",
      "what a captured fragment keeps of its colour: rgba8 (packUnorm4x8, the papers' 8-byte node with the depth), "
      "rgba16f (binary16, 12-byte node), rgba32f (float, 20-byte node); docs/precision.md",
      frag_colour_names(), {"rgba8"});
  ParamSpec frag_depth =
      ParamSpec::choice("frag_depth",
                        "the depth a fragment is sorted by: window (gl_FragCoord.z) or view (float32 view-space "
                        "distance along the view axis: relative precision 6e-8 at every distance)",
                        frag_depth_names(), {"window"});
  ParamSpec block_sort = ParamSpec::choice(
      "block_sort",
      "how RBS sorts each register block: insertion (RS, Knowles 2014 Listing 5: an insertion network with branches), "
      "bitonic or odd-even-merge (branchless register networks, fully unrolled: shaders/sorts/network.glsl)",
      block_sort_names(), {"insertion"});
  ParamSpec order_check = ParamSpec::choice(
      "order_check",
      "on checks each pixel's list order while loading it and skips the sort (and RBS-L's "
      "merge) of a list already far-to-near and blends one near-to-far backwards in O(n) (the lists of front-to-back "
      "or back-to-front submission); off sorts every list (the papers)",
      {"off", "on"}, {"off"});
  return {block, pool, max_frags, cs_group, auto_cache, frag_colour, frag_depth, block_sort, order_check};
}

// The self-shadowing effect's parameters (micro/oit/scene/shadow_map.hpp): read only where the scene declares it.
std::pair<ParamSpec, ParamSpec> shadow_params() {
  ParamSpec shadow_slices = ParamSpec::integer("shadow_slices",
                                               "self-shadowing: depth slices of the opacity shadow map (scenes whose "
                                               "effects hold self-shadowing; others run no shadow pass)",
                                               2, 1024, {"64"});
  ParamSpec shadow_resolution =
      ParamSpec::integer("shadow_resolution", "self-shadowing: the opacity shadow map's width and height in texels", 8,
                         4096, {"256"}, {"128"});
  // Read only where the case's scene and effects hold self-shadowing: elsewhere unused (empty in the
  // rows), so a list of them does not multiply those cases in a grid that mixes scenes, and a list
  // where no case holds it is a usage error (CaseGrid::check_overrides_apply).
  const auto shadowing = holds_self_shadowing();
  for (ParamSpec* s : {&shadow_slices, &shadow_resolution}) {
    s->applies_if = shadowing;
    s->applies_if_text = "the case's scene and effects hold self-shadowing";
    s->applies_if_reads = {"scene", "effects"};
  }
  return {shadow_slices, shadow_resolution};
}

class OitExperiment final : public Experiment {
 public:
  std::string name() const override { return "oit"; }
  std::string description() const override { return oit_description(); }
  std::vector<ParamSpec> params() const override {
    ParamSpec scene = ParamSpec::text("scene",
                                      "scene name in scenes/ (shipped: planes, planes-deep, hairball, hair, smoke, "
                                      "engine-grid, house) or a path to a scene .json",
                                      {"planes", "hairball", "smoke"}, {"planes", "hairball"});
    ParamSpec view = ParamSpec::text(
        "view", "camera view named in the scene file (fwd: lists arrive sorted, rev: reverse sorted)", {"fwd", "rev"});
    ParamSpec technique{"technique", techniques_description(), techniques_where(&Technique::in_default),
                        techniques_where(&Technique::in_quick), technique_names()};
    ParamSpec detail = ParamSpec::choice("detail", "scene size: full, or the scene file's small overrides",
                                         {"full", "small"}, {"full"}, {"small"});
    ParamSpec capture = ParamSpec::choice(
        "capture",
        "where the captured fragments live (Knowles 2014 section 2.2): PPLL per-pixel linked lists (one pass, global "
        "counter, re-rendered when the pool overflows); PPPA packed per-pixel arrays (a count pass, a prefix sum that "
        "sizes the buffer exactly, a fill pass; no next pointers)",
        capture_storage_names(), {"PPLL"});
    const auto [shadow_slices, shadow_resolution] = shadow_params();
    ExactParams x = exact_params();
    std::vector<ParamSpec> ps = {scene,
                                 view,
                                 technique,
                                 effects_param(),
                                 capture,
                                 detail,
                                 x.block,
                                 x.pool,
                                 x.max_frags,
                                 x.cs_group,
                                 x.auto_cache,
                                 shadow_slices,
                                 shadow_resolution,
                                 x.frag_colour,
                                 x.frag_depth,
                                 x.block_sort,
                                 x.order_check,
                                 splat_depth_param(),
                                 early_stop_param()};
    for (auto& a : popping_params()) ps.push_back(std::move(a));
    for (auto& a : approx_params()) ps.push_back(std::move(a));
    for (auto& a : peel_params()) ps.push_back(std::move(a));
    for (auto& a : moment_params()) ps.push_back(std::move(a));
    for (auto& a : wavelet_params()) ps.push_back(std::move(a));
    for (auto& a : slab_params()) ps.push_back(std::move(a));
    // Each technique parameter is scoped to the techniques that read it (the technique table says
    // which), so a row carries only its own.
    for (auto& spec : ps)
      if (auto readers = techniques_reading(spec.name); !readers.empty()) spec.only_when("technique", readers);
    return ps;
  }
  std::vector<MetricSpec> metric_specs() const override {
    using T = ValueType;
    // The techniques a metric is filled by, named from the technique table.
    const std::string bma_auto = names_text(techniques_reading("bma_auto_cache"));
    const std::string peeling = names_text(techniques_reading("max_layers"));
    const std::string moments = names_text(techniques_reading("moments"));
    std::vector<MetricSpec> m = fragment_metrics();
    std::vector<MetricSpec> own = {
        {"fragments_per_s", T::Number, "fragments/s", "capture throughput: total_fragments over the capture median"},
        {"max_frags_used", T::Integer, "",
         "MAX_FRAGS the resolve was compiled with (max_frags, or the view's "
         "next power of two when max_frags=0)"},
        {"truncated_pixels", T::Integer, "", "pixels deeper than max_frags_used (their deepest fragments dropped)"},
        {"node_pool", T::Integer, "", "fragment slots allocated"},
        {"overflow_rerenders", T::Integer, "",
         "captures redone because the node pool overflowed (the exact techniques: 0 unless initial_pool set the "
         "first pool; a count pass sizes it otherwise)"},
        {"bma_intervals", T::Text, "", "BMA: pixels per depth interval, TOP:COUNT;..."},
        {"node_pool_bytes", T::Integer, "bytes", "fragment storage allocated (nodes, next pointers, heads or offsets)"},
        {"node_buffers", T::Integer, "",
         "texel buffers each node array is split into (1 unless the pool passes GL_MAX_TEXTURE_BUFFER_SIZE)"},
        {"capture_count_ms", T::Number, "ms", "PPPA: the count pass and prefix sum, median"},
        {"bma_auto_choice", T::Text, "", bma_auto + ": the sort chosen per interval"},
        {"bma_auto_source", T::Text, "", bma_auto + ": calibrated now or read from the cache"},
        {"bma_auto_timings", T::Text, "", bma_auto + ": the calibration's medians per candidate"},
        {"bad_pixels", T::Integer, "", "pixels more than the tolerance off the exact reference"},
        {"visit_errors", T::Integer, "", "pixels resolved zero or several times (BMA must resolve each once)"},
        {"tied_pixels", T::Integer, "", "pixels with fragments of equal depth (their order is by colour)"},
        {"hidden_fragments", T::Integer, "",
         "opaque effect: transparent fragments behind the opaque depth, never captured (the CPU's count)"},
        // the geometric reference of analytic (planes-only) scenes and the analytic reference of splat scenes
        // (micro/oit/splats/splat_check.hpp): empty elsewhere (docs/precision.md)
        {"truth_rmse", T::Number, "",
         "rmse against the scene's planes composited in double in their true order, colours as described "
         "(no format's quantisation); splat scenes: against the analytic splat reference (every splat's alpha at "
         "every pixel centre in double, sorted by the splat_depth key)"},
        {"truth_max_abs_error", T::Number, "", "largest channel error against that composite"},
        {"geometric_bad_pixels", T::Integer, "",
         "pixels off the geometric composite with the fragment format's quantisation by more than the tolerance; "
         "splat scenes: off the analytic splat reference"},
        {"splat_tied_pixels", T::Integer, "",
         "splat scenes: pixels whose analytic order is a float tie (neighbouring keys within 1e-5 relative that a "
         "float key may order either way): their tolerance grows by what swapping the tied pairs moves them"},
        {"ambiguous_pixels", T::Integer, "",
         "pixels left out of the geometric comparison: a plane edge, the near or the far plane at the pixel centre"},
        // approximate techniques (micro/oit/approx/approx_case.cpp)
        {"model_rmse", T::Number, "", "rmse of the technique's CPU model against the exact reference"},
        {"model_max_diff", T::Number, "", "largest channel difference between the GPU image and the CPU model"},
        {"capped_updates", T::Integer, "", "insertions that gave up on the spinlock after SPIN_CAP tries"},
        {"flicker", T::Number, "", "per-pixel variance across flicker_runs frames, mean over pixels"},
        {"flicker_max", T::Number, "", "its largest pixel"},
        {"flicker_pixels", T::Integer, "", "pixels whose value changed between frames"},
        // self-shadowing (micro/oit/scene/shadow_map.cpp), only where the scene declares it
        {"shadow_rmse", T::Number, "",
         "self-shadowing: rmse of the opacity map's transmittance against the deep shadow map's (exact) at every "
         "fragment seen from the light"},
        {"shadow_max_abs_error", T::Number, "", "self-shadowing: the largest of those transmittance errors"},
        {"shadow_map_max_diff", T::Number, "",
         "self-shadowing: largest optical-depth difference between the GPU map and the CPU map of the same slices"},
        {"shadow_light_fragments", T::Integer, "", "self-shadowing: fragments seen from the light"},
        {"shadow_map_bytes", T::Integer, "bytes",
         "self-shadowing: GPU memory of the map (3D texture) and of its primitive sort"},
        // depth peeling (micro/oit/peel/peel_case.cpp)
        {"layers_peeled", T::Integer, "", peeling + ": layers peeled in the deepest pixel"},
        {"peel_passes", T::Integer, "", peeling + ": geometry passes of one frame (two per iteration)"},
        {"peel_complete", T::Text, "",
         peeling + ": yes when the occlusion query found no fragment left (exact), no when max_layers stopped it"},
        {"bytes_per_pixel", T::Number, "bytes",
         "the technique's per-pixel storage at this resolution (fragment pool, node arrays, accumulation and "
         "peeling targets; not the output image)"},
        // MBOIT and STOCHASTIC (micro/oit/moments/moments.hpp)
        {"moment_bias", T::Number, "", moments + ": the moment bias used (the paper's value for the variant)"},
        {"moment_rebiased", T::Number, "",
         moments + ": fraction of fragments whose pixel's moments were inconsistent at that bias (rounded "
                   "storage), so the reconstruction raised it tenfold (up to 1000x; the CPU model's count)"},
        {"model_off_channels", T::Integer, "",
         names_text(technique_names(TechniqueFamily::Moments)) +
             ": channel values more than the tolerance from the CPU model (up to 1% allowed)"},
        {"half_blend_rounding", T::Text, "",
         names_text(techniques_reading("wavelet_bits")) +
             " with 16-bit coefficients: how the driver's blender rounds a sum into a half-float target, probed "
             "at setup (nearest or toward-zero); the CPU model rounds its sums the same way"},
        {"msaa_samples", T::Integer, "",
         "stochastic transparency's MSAA samples per pass (samples_per_pixel / passes)"}};
    for (auto& x : own) m.push_back(std::move(x));
    m.push_back(sort_source_metric());
    for (auto& x : image_error_metrics()) m.push_back(std::move(x));
    for (auto& x : popping_metrics()) m.push_back(std::move(x));
    return m;
  }
  // An effect the case's scene does not declare is a usage error before anything runs (exit 2);
  // a scene that does not load is left to the case (its FILE:LINE:COLUMN error).
  void check_cases(const std::vector<ParamSet>& cases) const override {
    std::set<std::tuple<std::string, std::string, std::string>> seen;
    for (const auto& c : cases) {
      if (!seen.insert({c.get("scene"), c.get("view"), c.get("effects")}).second) continue;
      SceneDesc s;
      try {  // a scene or view that is not there is bad input (exit 2), as in render and view
        s = load_scene(c.get("scene"));
        s.view(c.get("view"));
        check_model_files(s);
      } catch (const SceneError& e) {
        throw UsageError(e.what());
      }
      try {
        select_effects(s, c.get("effects"));
      } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
      }
    }
  }
  std::vector<std::string> checked_params() const override { return {"scene", "view", "effects"}; }
  Resolution default_resolution() const override { return {512, 512}; }
  Resolution quick_resolution() const override { return {128, 128}; }
  // Each case holds its node pool (pixels x depth): up to 8 cases while they hold at most 2^20 pixels
  // together (8 at 128x128 and 256x256, 4 at 512x512), never fewer than 2 (a case and its baseline).
  int max_interleave(Resolution res) const override {
    const long long pixels = std::max(1LL, static_cast<long long>(res.width) * res.height);
    return static_cast<int>(std::clamp((1LL << 20) / pixels, 2LL, 8LL));
  }
  // Every technique's case on a splat scene measures its popping after its validation.
  std::unique_ptr<CaseInstance> prepare(const ParamSet& p, CaseContext& ctx) override {
    return with_popping(make_oit_case(p, ctx), p, ctx);
  }
};

}  // namespace

void register_oit(Registry& registry) { registry.add(std::make_unique<OitExperiment>()); }

}  // namespace oitbench
