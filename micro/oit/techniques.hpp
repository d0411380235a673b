#pragma once
// The technique table: the one place that knows the oit experiment's techniques. Each entry says
// what a technique is (family, resolve scheme and sort), which parameters it reads (the parameter
// specs' `only_when` lists are derived from them), whether the default and quick grids hold it,
// what it is validated against, and the factory that builds its case. Everything else (the
// experiment's parameter grid, the viewer, `oitbench list --techniques --json`, and through that
// export the Python scripts) asks this table instead of decoding names.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "oit/oit_case.hpp"
#include "oit/resolve/resolve_sort.hpp"

namespace oitbench::oit {

enum class TechniqueFamily { Exact, Peel, Approximate, Moments, Stochastic };
// How an exact technique resolves: one program (BASE), one per depth interval (BMA), a compute pass
// (CS), blocks sorted in global memory (G), or on the CPU (CPU). None for the other families.
enum class ResolveScheme { None, Base, Bma, Compute, Global, Cpu };
// What a case's image must match to be valid.
enum class TechniqueReference { Exact, CpuModel, ExactOrPeelModel };
// What a technique draws: any scene's primitives, or only splats (it orders splats as a whole, as the 3DGS
// global sort does): make_oit_case refuses a scene without splats as Unsupported, and tests that walk every
// technique over meshes leave it out by this property.
enum class TechniquePrimitives { Any, Splats };

using CaseFactory = std::unique_ptr<OitCase> (*)(const ParamSet&, CaseContext&);

struct Technique {
  std::string name;
  TechniqueFamily family = TechniqueFamily::Exact;
  ResolveScheme scheme = ResolveScheme::None;
  std::string sort;                         // exact: IS IMS RBS-L RBS AUTO NATIVE; empty otherwise
  std::optional<ResolveSort> resolve_sort;  // the shader sort the resolve runs, where it runs one
  int variant = 0;                          // the family's own enumerator (ApproxTechnique, dual peeling)
  std::vector<std::string> params;          // the technique parameters it reads, sorted
  bool in_default = false;                  // in the default grid of `technique`
  bool in_quick = false;                    // in the --quick grid
  TechniquePrimitives primitives = TechniquePrimitives::Any;
  CaseFactory make = nullptr;

  TechniqueReference reference() const;
  // The capture storages (`capture`) the technique's own resolve reads; empty where it keeps none.
  std::vector<std::string> captures() const;
  bool reads(const std::string& param) const;
};

// Every technique in the order `oitbench list` and the viewer's T key step through them: exact,
// depth peeling, approximate, moments and stochastic, and unsorted (the no-OIT baseline) last.
const std::vector<Technique>& techniques();
// The technique named `name`, or nullptr.
const Technique* find_technique(const std::string& name);
// The technique named `name`; std::invalid_argument listing the valid names otherwise.
const Technique& technique(const std::string& name);
std::vector<std::string> technique_names();
// The technique `oitbench render` and `oitbench view` start with: the table's first (BASE-IS).
const std::string& default_technique();
std::vector<std::string> technique_names(TechniqueFamily family);
// The techniques that read `param`, in table order (a parameter spec's only_when list).
std::vector<std::string> techniques_reading(const std::string& param);
// The techniques of `family` that draw any scene (primitives Any): those a walk over mesh scenes runs.
std::vector<std::string> technique_names_on_meshes(TechniqueFamily family);
// The same technique with the other of BASE/BMA, or nullptr where it has no such twin.
const Technique* bma_twin(const Technique& t);
// The case for any technique; a malformed scene is a std::runtime_error starting "oit: file:line:column:".
std::unique_ptr<OitCase> make_oit_case(const ParamSet& p, CaseContext& ctx);

std::string family_label(TechniqueFamily family);  // exact, peel, approximate, moments, stochastic
std::string scheme_label(ResolveScheme scheme);    // BASE, BMA, CS, G, CPU, or empty
std::string reference_label(TechniqueReference reference);
std::string primitives_label(TechniquePrimitives primitives);  // any, splats
// What the `technique` parameter's description says, from the table: the exact resolves by scheme and
// sort, then each other family's techniques by name.
std::string techniques_description();
// "DP, DDP": technique names joined for a text that names them (techniques_reading(param), technique_names(family)).
std::string names_text(const std::vector<std::string>& names);
// The oit experiment's description, its techniques named by family from the table.
std::string oit_description();
// The table as the JSON that `oitbench list --techniques --json` prints (scripts/techniques.json).
std::string techniques_json();

}  // namespace oitbench::oit
