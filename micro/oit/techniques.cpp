#include "oit/techniques.hpp"

#include <algorithm>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "oit/approx/approx.hpp"
#include "oit/capture/fragment_storage.hpp"
#include "oit/moments/moments.hpp"
#include "oit/peel/peel.hpp"
#include "oit/scene/scene.hpp"
#include "oit/slab/slab.hpp"
#include "oit/splats/gpu_splats.hpp"
#include "oit/wavelets/wavelets.hpp"

namespace oitbench::oit {

namespace {

using F = TechniqueFamily;
using S = ResolveScheme;
using Params = std::vector<std::string>;

Params sorted(Params p) {
  std::sort(p.begin(), p.end());
  return p;
}
Params operator+(Params a, const Params& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// What every exact technique reads (the captured fragments' format and the first pool), and what a
// technique that resolves in a shader adds (MAX_FRAGS).
const Params kCaptured = {"frag_colour", "frag_depth", "initial_pool"};
const Params kShaderResolve = kCaptured + Params{"max_frags"};
const Params kInsertion = kShaderResolve + Params{"order_check"};  // IS, IMS: the order check
const Params kRegisters = kShaderResolve + Params{"block", "block_sort"};
const Params kRegistersLocal = kRegisters + Params{"order_check"};  // RBS-L: the order check too
const Params kCompute = {"cs_group"};
const Params kPeel = {"max_layers", "tie_rule"};
const Params kFlicker = {"flicker_runs"};
const Params kArrays = kFlicker + Params{"nodes", "storage", "sync"};  // the per-pixel node arrays
const Params kGuarded = {"guard"};
const Params kEarlyStop = {"early_stop"};  // 3DGS's early termination: the ordered techniques

Technique exact(std::string name, S scheme, std::string sort, std::optional<ResolveSort> rs, const Params& params,
                bool quick) {
  Technique t;
  t.name = std::move(name);
  t.family = F::Exact;
  t.scheme = scheme;
  t.sort = std::move(sort);
  t.resolve_sort = rs;
  t.params = sorted(params);
  t.in_default = true;
  t.in_quick = quick;
  t.make = make_exact_case;
  return t;
}
Technique other(std::string name, F family, int variant, const Params& params, CaseFactory make) {
  Technique t;
  t.name = std::move(name);
  t.family = family;
  t.variant = variant;
  t.params = sorted(params);
  t.make = make;
  return t;
}
Technique approx(std::string name, ApproxTechnique v, const Params& params) {
  return other(std::move(name), F::Approximate, static_cast<int>(v), params, make_approx_case);
}
// A technique that orders splats as a whole (primitives: splats): unsupported on a scene without them.
Technique splats_only(Technique t) {
  t.primitives = TechniquePrimitives::Splats;
  return t;
}

std::vector<Technique> build_table() {
  using R = ResolveSort;
  using A = ApproxTechnique;
  // The insertion and register-block resolves (IS, IMS, RBS-L) and the CPU's composite front to back and
  // stop early where asked (RBS-G and BMA-AUTO do not).
  const Params kInsertionStop = kInsertion + kEarlyStop;
  const Params kRegistersStop = kRegistersLocal + kEarlyStop;
  return {
      exact("BASE-IS", S::Base, "IS", R::IS, kInsertionStop, true),
      exact("BASE-IMS", S::Base, "IMS", R::IMS, kInsertionStop, false),
      exact("BASE-RBS-L", S::Base, "RBS-L", R::RBS_L, kRegistersStop, true),
      exact("BMA-IS", S::Bma, "IS", R::IS, kInsertionStop, true),
      exact("BMA-IMS", S::Bma, "IMS", R::IMS, kInsertionStop, false),
      exact("BMA-RBS-L", S::Bma, "RBS-L", R::RBS_L, kRegistersStop, true),
      exact("CPU-NATIVE", S::Cpu, "NATIVE", std::nullopt, kCaptured + kEarlyStop, true),
      exact("CS-IS", S::Compute, "IS", R::IS, kInsertionStop + kCompute, false),
      exact("CS-IMS", S::Compute, "IMS", R::IMS, kInsertionStop + kCompute, false),
      exact("CS-RBS-L", S::Compute, "RBS-L", R::RBS_L, kRegistersStop + kCompute, false),
      exact("RBS-G", S::Global, "RBS", R::RBS_G, kRegisters, false),
      exact("BMA-AUTO", S::Bma, "AUTO", std::nullopt, kShaderResolve + Params{"block", "bma_auto_cache"}, false),
      other("DP", F::Peel, static_cast<int>(PeelKind::Depth), kPeel, make_peel_case),
      other("DDP", F::Peel, static_cast<int>(PeelKind::Dual), kPeel, make_peel_case),
      approx("MLAB", A::Mlab, kArrays),
      approx("UMLAB", A::Umlab, kArrays),
      approx("HT", A::Ht, kArrays + Params{"ht_variant"}),
      approx("FIRST-K", A::FirstK, kArrays),
      approx("AT", A::At, kArrays + kGuarded),
      approx("HAT", A::Hat, kArrays + kGuarded),
      approx("UAT", A::Uat, kArrays + kGuarded),
      approx("UHAT", A::Uhat, kArrays + kGuarded),
      approx("LAAT", A::Laat, kArrays + kGuarded),
      approx("WBOIT", A::Wboit, kFlicker + kGuarded + Params{"wboit_weight"}),
      other("MBOIT", F::Moments, 0, kFlicker + Params{"moments", "moment_kind", "moment_bits"}, make_mboit_case),
      other("WOIT", F::Moments, 1, kFlicker + Params{"wavelet_coeffs", "wavelet_basis", "wavelet_bits"},
            make_woit_case),
      other("STOCHASTIC", F::Stochastic, 0, kFlicker + Params{"samples_per_pixel"}, make_stochastic_case),
      other("SLAB", F::Stochastic, 1, kFlicker + Params{"samples_per_pixel", "slab_layers"}, make_slab_case),
      splats_only(approx("GLOBAL-SORT", A::GlobalSort, kFlicker + kEarlyStop)),
      splats_only(approx("WINDOW-SORT", A::WindowSort, kFlicker + Params{"storage", "sync", "window"})),
      approx("unsorted", A::Unsorted, kFlicker),
  };
}

}  // namespace

TechniqueReference Technique::reference() const {
  switch (family) {
    case F::Exact:
      return TechniqueReference::Exact;
    case F::Peel:
      return TechniqueReference::ExactOrPeelModel;
    default:
      return TechniqueReference::CpuModel;
  }
}

std::vector<std::string> Technique::captures() const {
  return family == F::Exact ? capture_storage_names() : std::vector<std::string>{};
}

bool Technique::reads(const std::string& param) const {
  return std::binary_search(params.begin(), params.end(), param);
}

const std::vector<Technique>& techniques() {
  static const std::vector<Technique> table = build_table();
  return table;
}

const Technique* find_technique(const std::string& name) {
  for (const auto& t : techniques())
    if (t.name == name) return &t;
  return nullptr;
}

const Technique& technique(const std::string& name) {
  if (const Technique* t = find_technique(name)) return *t;
  std::string valid;
  for (const auto& t : techniques()) valid += (valid.empty() ? "" : ", ") + t.name;
  throw std::invalid_argument("unknown technique '" + name + "'; valid: " + valid);
}

const std::string& default_technique() { return techniques().front().name; }

std::vector<std::string> technique_names() {
  std::vector<std::string> out;
  for (const auto& t : techniques()) out.push_back(t.name);
  return out;
}

std::vector<std::string> technique_names(TechniqueFamily family) {
  std::vector<std::string> out;
  for (const auto& t : techniques())
    if (t.family == family) out.push_back(t.name);
  return out;
}

std::vector<std::string> techniques_reading(const std::string& param) {
  std::vector<std::string> out;
  for (const auto& t : techniques())
    if (t.reads(param)) out.push_back(t.name);
  return out;
}

std::vector<std::string> technique_names_on_meshes(TechniqueFamily family) {
  std::vector<std::string> out;
  for (const auto& t : techniques())
    if (t.family == family && t.primitives == TechniquePrimitives::Any) out.push_back(t.name);
  return out;
}

const Technique* bma_twin(const Technique& t) {
  if (t.scheme != S::Base && t.scheme != S::Bma) return nullptr;
  const S other_scheme = t.scheme == S::Base ? S::Bma : S::Base;
  for (const auto& u : techniques())
    if (u.family == t.family && u.scheme == other_scheme && u.sort == t.sort) return &u;
  return nullptr;
}

std::unique_ptr<OitCase> make_oit_case(const ParamSet& p, CaseContext& ctx) {
  try {
    const Technique& t = technique(p.get("technique"));
    if (t.primitives == TechniquePrimitives::Splats) {
      const SceneDesc scene = load_scene(p.get("scene"));
      if (!scene_has_splats(scene))
        throw Unsupported(t.name + " draws only splats (the technique table's primitives: splats): scene '" +
                          scene.name + "' (" + scene.path + ") has none");
    }
    return t.make(p, ctx);
  } catch (const SceneError& e) {
    throw std::runtime_error(std::string("oit: ") + e.what());
  }
}

std::string family_label(TechniqueFamily family) {
  switch (family) {
    case F::Exact:
      return "exact";
    case F::Peel:
      return "peel";
    case F::Approximate:
      return "approximate";
    case F::Moments:
      return "moments";
    case F::Stochastic:
      return "stochastic";
  }
  return "?";
}

std::string scheme_label(ResolveScheme scheme) {
  switch (scheme) {
    case S::None:
      return "";
    case S::Base:
      return "BASE";
    case S::Bma:
      return "BMA";
    case S::Compute:
      return "CS";
    case S::Global:
      return "G";
    case S::Cpu:
      return "CPU";
  }
  return "?";
}

std::string reference_label(TechniqueReference reference) {
  switch (reference) {
    case TechniqueReference::Exact:
      return "exact";
    case TechniqueReference::CpuModel:
      return "cpu-model";
    case TechniqueReference::ExactOrPeelModel:
      return "exact-or-peel-model";
  }
  return "?";
}

std::string primitives_label(TechniquePrimitives primitives) {
  return primitives == TechniquePrimitives::Splats ? "splats" : "any";
}

namespace {

std::string scheme_text(ResolveScheme scheme) {
  static const std::map<ResolveScheme, std::string> text = {{S::Base, "one program with MAX_FRAGS"},
                                                            {S::Bma, "one per depth interval under a stencil mask"},
                                                            {S::Compute, "a compute pass"},
                                                            {S::Global, "blocks sorted in place in global memory"},
                                                            {S::Cpu, "sorted and blended on the CPU"}};
  const auto it = text.find(scheme);
  return it == text.end() ? "" : it->second;
}

std::string sort_text(const std::string& sort) {
  if (sort == "IS") return "insertion";
  if (sort == "IMS") return "insertion+merge";
  if (sort == "RBS-L") return "register block sort";
  if (sort == "AUTO") return "the per-interval sort calibrated on this driver (cached)";
  return "";  // a scheme's only sort (NATIVE, RBS): the scheme says it
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

std::string techniques_description() {
  std::vector<ResolveScheme> schemes;
  std::vector<std::string> sorts;
  for (const auto& t : techniques()) {
    if (t.family != F::Exact) continue;
    if (std::find(schemes.begin(), schemes.end(), t.scheme) == schemes.end()) schemes.push_back(t.scheme);
    if (!sort_text(t.sort).empty() && std::find(sorts.begin(), sorts.end(), t.sort) == sorts.end())
      sorts.push_back(t.sort);
  }
  std::string out = "resolve: ";
  for (ResolveScheme s : schemes) {
    std::vector<std::string> names;
    for (const auto& t : techniques())
      if (t.family == F::Exact && t.scheme == s) names.push_back(t.name);
    out += (names.size() == 1 ? names[0] : scheme_label(s) + "-*") + " " + scheme_text(s) + "; ";
  }
  std::vector<std::string> sort_parts;
  for (const auto& sort : sorts) sort_parts.push_back(sort + " " + sort_text(sort));
  out += "sorts: " + joined(sort_parts);
  for (F family : {F::Peel, F::Approximate, F::Moments, F::Stochastic})
    if (auto names = technique_names(family); !names.empty())
      out += "; " + joined(names) + ": " + (family == F::Peel ? "depth peeling" : family_label(family));
  return out;
}

std::string names_text(const std::vector<std::string>& names) { return joined(names); }

std::string oit_description() {
  const auto names = [](F family) { return joined(technique_names(family)); };
  return "exact OIT (Knowles 2013 BMA, 2014 RBS): fragments captured from a scene file into per-pixel linked lists "
         "(PPLL) or packed per-pixel arrays (PPPA), resolved by " +
         names(F::Exact) + "; validated against a double-precision CPU compositor. Approximate OIT (Bruell 2018: " +
         names(F::Approximate) + "; Muenstermann 2018, Aizenshtein 2022: " + names(F::Moments) +
         "; Enderton 2010: " + names(F::Stochastic) +
         ") is validated against each technique's own CPU model, its error vs the exact image reported as data. "
         "Depth peeling (Everitt 2001, Bavoil & Myers 2008: " +
         names(F::Peel) +
         ") is exact when it peels every layer, validated against a CPU model of the layers it peeled when "
         "max_layers stops it. Each technique's family, resolve and parameters: oitbench list --techniques";
}

std::string techniques_json() {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const auto& t : techniques()) {
    list.push_back({{"name", t.name},
                    {"family", family_label(t.family)},
                    {"scheme", scheme_label(t.scheme)},
                    {"sort", t.sort},
                    {"captures", t.captures()},
                    {"params", t.params},
                    {"default", t.in_default},
                    {"quick", t.in_quick},
                    {"reference", reference_label(t.reference())},
                    {"primitives", primitives_label(t.primitives)}});
  }
  nlohmann::ordered_json out = {
      {"format", 1},
      {"experiment", "oit"},
      {"techniques", list},
      {"note",
       "The oit experiment's technique table (micro/oit/techniques.cpp) as `oitbench list --techniques --json` "
       "prints it. Scripts read techniques from here, never from copies of their own; "
       "tests/scripts/test_technique_table.py checks that this file equals what the binary prints."}};
  return out.dump(2) + "\n";
}

}  // namespace oitbench::oit
