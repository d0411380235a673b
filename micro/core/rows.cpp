#include "core/rows.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/provenance.hpp"
#include "core/stats.hpp"

namespace oitbench {

std::string fmt_number(double v, int prec) {
  if (!std::isfinite(v)) return "";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", prec + 3, v);
  return buf;
}

void CaseRecord::fail(Status s, const std::string& why) {
  if (status != Status::Ok) return;
  status = s;
  reason = why;
}

void CaseRecord::add_note(const std::string& text) {
  std::string& r = status == Status::Ok ? note : reason;
  r += (r.empty() ? "" : "; ") + text;
}

double CaseRecord::add_repetition(const std::vector<PassSample>& samples, double total_ms) {
  double gpu_total = samples.empty() ? -1 : 0;
  for (const auto& s : samples) {
    if (std::find(pass_names.begin(), pass_names.end(), s.pass) == pass_names.end()) pass_names.push_back(s.pass);
    cpu[s.pass].push_back(s.cpu_ms);
    gpu[s.pass].push_back(s.gpu_ms);
    gpu_total = (gpu_total < 0 || s.gpu_ms < 0) ? -1 : gpu_total + s.gpu_ms;
  }
  cpu["total"].push_back(total_ms);
  gpu["total"].push_back(gpu_total);
  return gpu_total;
}

namespace {

Row case_columns(const RowSettings& s, const CaseRecord& c) {
  Row row = s.run;
  row["experiment"] = s.experiment;
  row["variant"] = c.variant;
  row["width"] = std::to_string(s.res.width);
  row["height"] = std::to_string(s.res.height);
  row["reps"] = std::to_string(c.cpu.count("total") ? c.cpu.at("total").size() : static_cast<size_t>(s.reps));
  row["warmup"] = std::to_string(s.warmup - c.warmup_kept);  // the repetitions that were warm-up
  row["timestamp_utc"] = utc_now();
  std::string names;
  for (const auto& [k, v] : c.params.used_values())
    if (k != "variant") {
      row[k] = v;
      names += (names.empty() ? "" : ";") + k;
    }
  row["parameters"] = names;  // which of the columns after the base ones are this case's parameters
  return row;
}

}  // namespace

std::vector<Row> summary_rows(const RowSettings& s, const CaseRecord& c) {
  Row base = case_columns(s, c);
  base["status"] = status_name(c.status);
  base["valid"] = c.status == Status::Ok ? "1" : "0";
  base["compile_ms"] = fmt_number(c.compile_ms);
  base["warmup_ms"] = fmt_number(c.warmup_ms);
  base["program_cache"] = c.program_cache;
  base["pass_sync"] = s.synchronised ? "1" : "0";
  for (const auto& [k, v] : c.metrics) base[k] = v;
  base["sample_runs"] = std::to_string(c.sample_runs);
  if (c.sample_units > 0) base["sample_units"] = std::to_string(c.sample_units);
  base["stop"] = c.stop;
  if (!c.mem_ns.empty()) {
    base["host_mem_ns"] = fmt_number(median_of(c.mem_ns));
    base["host_mem_max_ns"] = fmt_number(*std::max_element(c.mem_ns.begin(), c.mem_ns.end()));
  }
  if (s.target_ci > 0) base["target_ci_pct"] = fmt_number(s.target_ci * 100);
  base["baseline"] = c.baseline;
  std::vector<std::string> passes;
  if (c.pass_names.size() > 1) passes = c.pass_names;
  passes.push_back("total");
  std::vector<Row> rows;
  for (const auto& pass : passes) {
    Row row = base;
    row["pass"] = pass;
    if (pass == "total" && c.accounted) {  // the case's time, once: on its total row
      row["case_wall_s"] = fmt_number(c.phases.total());
      for (Phase ph : kAllPhases) row[phase_column(ph)] = fmt_number(c.phases[ph]);
    }
    std::string reason = c.status == Status::Ok ? c.note : c.reason;
    auto cpu = c.cpu.find(pass);
    if (c.status == Status::Ok && cpu != c.cpu.end()) {
      auto cs = summarize(cpu->second);
      std::vector<double> g;
      const auto& gpu = c.gpu.at(pass);
      for (double x : gpu)
        if (x >= 0) g.push_back(x);
      bool have_gpu = !g.empty() && g.size() == gpu.size();
      auto gs = have_gpu ? summarize(g) : Summary{};
      // `total` is the CPU clock around the whole repetition (glFinish before and after) on every
      // driver: the frame's time, CPU work between passes included. A pass without queries (CPU
      // work) keeps its CPU time whatever the primary clock.
      bool gpu_primary = s.gpu_primary && have_gpu && pass != "total";
      const auto& st = gpu_primary ? gs : cs;
      row["timer"] = gpu_primary ? "gpu" : "cpu";
      row["median_ms"] = fmt_number(st.median);
      row["mad_ms"] = fmt_number(st.mad);
      row["min_ms"] = fmt_number(st.min);
      row["max_ms"] = fmt_number(st.max);
      row["mean_ms"] = fmt_number(st.mean);
      row["stddev_ms"] = fmt_number(st.stddev);
      row["samples"] = std::to_string(st.n);
      row["outliers"] = std::to_string(st.outliers);
      const auto& primary = gpu_primary ? g : cpu->second;
      if (auto ci = median_interval(primary); ci.ok) {
        row["ci_lo_ms"] = fmt_number(ci.lo);
        row["ci_hi_ms"] = fmt_number(ci.hi);
        const double rel = relative_half_width(ci, st.median);
        row["ci_pct"] = fmt_number(rel * 100, 2);
        // The stopping rule watches the total; a pass whose own interval missed the target says so.
        if (pass != "total" && c.stop != "fixed" && s.target_ci > 0 && rel > s.target_ci)
          reason += (reason.empty() ? "" : "; ") + std::string("this pass: ci +-") + fmt_number(rel * 100, 2) +
                    "% > target +-" + fmt_number(s.target_ci * 100) + "% (the stopping rule watches the total)";
      }
      if (c.baseline_record)
        if (auto sp = paired_speedup(*c.baseline_record, c, pass, s.gpu_primary)) {
          row["speedup"] = fmt_number(sp->median);
          if (sp->ci.ok) {
            row["speedup_ci_lo"] = fmt_number(sp->ci.lo);
            row["speedup_ci_hi"] = fmt_number(sp->ci.hi);
          }
        }
      row["cpu_median_ms"] = fmt_number(cs.median);
      row["cpu_mad_ms"] = fmt_number(cs.mad);
      if (have_gpu) {
        row["gpu_median_ms"] = fmt_number(gs.median);
        row["gpu_mad_ms"] = fmt_number(gs.mad);
      }
      if (gpu_primary && s.synchronised && gs.median > 0 &&
          (cs.median / gs.median > kTimerDisagreement || gs.median / cs.median > kTimerDisagreement)) {
        reason += (reason.empty() ? "" : "; ") + std::string("timer-disagreement: cpu ") + fmt_number(cs.median, 3) +
                  " ms vs gpu " + fmt_number(gs.median, 3) + " ms";
      }
    }
    row["reason"] = reason;
    rows.push_back(std::move(row));
  }
  return rows;
}

std::vector<Row> raw_rows(const RowSettings& s, const CaseRecord& c, int rep, const std::vector<PassSample>& samples,
                          double total_ms, double gpu_total_ms) {
  Row row;
  for (const auto& col : raw_base_columns())
    if (auto it = s.run.find(col.name); it != s.run.end()) row[col.name] = it->second;
  row["experiment"] = s.experiment;
  row["variant"] = c.variant;
  row["rep"] = std::to_string(rep);
  row["width"] = std::to_string(s.res.width);
  row["height"] = std::to_string(s.res.height);
  row["group"] = std::to_string(s.group);
  row["sample_runs"] = std::to_string(c.sample_runs);
  if (c.sample_units > 0) row["sample_units"] = std::to_string(c.sample_units);
  row["timestamp_utc"] = utc_now();
  for (const auto& [k, v] : c.params.used_values())
    if (k != "variant") row[k] = v;
  std::vector<Row> rows;
  auto put = [&](const std::string& pass, double cpu, double gpu) {
    row["pass"] = pass;
    row["cpu_ms"] = fmt_number(cpu);
    row["gpu_ms"] = gpu >= 0 ? fmt_number(gpu) : "";
    rows.push_back(row);
  };
  if (samples.size() > 1)
    for (const auto& p : samples) put(p.pass, p.cpu_ms, p.gpu_ms);
  put("total", total_ms, gpu_total_ms);
  return rows;
}

namespace {

// The primary clock's samples of one pass: the queries where they are primary and every sample has one.
std::vector<double> primary_samples(const CaseRecord& c, const std::string& pass, bool gpu_primary) {
  auto cpu = c.cpu.find(pass);
  if (cpu == c.cpu.end()) return {};
  if (gpu_primary && pass != "total") {
    const auto& gpu = c.gpu.at(pass);
    if (!gpu.empty() && std::all_of(gpu.begin(), gpu.end(), [](double x) { return x >= 0; })) return gpu;
  }
  return cpu->second;
}

}  // namespace

std::optional<Speedup> paired_speedup(const CaseRecord& base, const CaseRecord& c, const std::string& pass,
                                      bool gpu_primary) {
  if (base.status != Status::Ok || c.status != Status::Ok) return std::nullopt;
  const auto b = primary_samples(base, pass, gpu_primary), x = primary_samples(c, pass, gpu_primary);
  const size_t n = std::min(b.size(), x.size());
  std::vector<double> ratios;
  for (size_t i = 0; i < n; ++i)
    if (x[i] > 0 && b[i] > 0) ratios.push_back(b[i] / x[i]);
  if (ratios.empty()) return std::nullopt;
  Speedup sp;
  sp.median = median_of(ratios);
  sp.ci = median_interval(ratios);
  sp.pairs = ratios.size();
  return sp;
}

}  // namespace oitbench
