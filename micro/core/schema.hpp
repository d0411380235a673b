#pragma once
// The result schema, defined once: the statuses a case can end in, the framework's columns of a
// summary row and of a --raw row (name, type, unit, meaning), and the JSON that
// `oitbench list --schema json` prints: those columns plus every registered experiment's metrics
// and parameters. scripts/oitbench/results.py reads a committed copy of that JSON (scripts/schema.json),
// which a test regenerates and compares, so no column list is typed twice.
#include <string>
#include <vector>

namespace oitbench {

class Registry;

// 2: parameters scoped to the cases they apply to (others empty), max_frags_used, sort_source,
// the output path `dump` no longer a parameter. 3: the GPU state columns (gpu_driver_version,
// gpu_*_start/end), occupancy's measured_occupancy and measured_occupancy_note. 4: samples sized by
// their statistics and paired speedups (ci_lo_ms, ci_hi_ms, ci_pct, target_ci_pct, stop, sample_runs,
// sample_units, baseline, speedup, speedup_ci_lo/hi), the new oit metrics (node_buffers, ...).
// 5: shard (--shard I/N),
// and run identity (run_id, also in raw rows; tags) and the machine's (cpu_vendor/family/model_id/stepping,
// cpu_isa, cpu_count, memory_bytes, kernel, machine_id, mesa_version, llvm_version, llvm_vector_bits).
// 6: the time account (case_wall_s and phase_*_s, on total rows; core/phases.hpp).
// 7: the GPU's identity (gpu_pci_id, gpu_vbios_version). 8: the host's memory latency during the case
// (host_mem_ns, host_mem_max_ns; core/memory_probe.hpp).
inline constexpr int kCsvSchema = 8;

enum class Status { Ok, Invalid, Unsupported, Error, Timeout };
inline constexpr Status kAllStatuses[] = {Status::Ok, Status::Invalid, Status::Unsupported, Status::Error,
                                          Status::Timeout};
const char* status_name(Status s);         // "ok", "invalid", ...
const char* status_description(Status s);  // what it means for the row's numbers

enum class ValueType { Text, Integer, Number, Flag };
const char* value_type_name(ValueType t);  // "text", "integer", "number", "flag"

struct ColumnSpec {
  std::string name;
  ValueType type = ValueType::Text;
  std::string unit;  // "ms", "bytes", "fragments/s", ...; empty: none
  std::string description;
  // Framework columns only: what the column is about. "run" (the driver, machine, code and
  // environment: never part of a case's identity when runs are compared), "case" (what ran),
  // "result" (its status) or "timing".
  std::string group = "";
};
using MetricSpec = ColumnSpec;

// The framework's columns of a summary row, in file order; the metrics and parameters follow.
const std::vector<ColumnSpec>& summary_base_columns();
// The columns of a --raw row (one per repetition and pass); the parameters follow.
const std::vector<ColumnSpec>& raw_base_columns();

// The full CSV headers for this registry: base columns, every experiment's metrics, parameters.
std::vector<std::string> summary_columns(const Registry& registry);
std::vector<std::string> raw_columns(const Registry& registry);

// `oitbench list --schema json`: schema version, statuses, and both files' columns with their role
// (base, metric, parameter), type, unit, description and the experiments that fill them.
std::string schema_json(const Registry& registry);

}  // namespace oitbench
