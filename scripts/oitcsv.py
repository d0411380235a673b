"""Reading oitbench's tidy CSV: shared by plot.py, compare.py and tables.py.

A summary file (`oitbench run ... --out f.csv`) has the framework's fixed columns (BASE_COLUMNS), then
the metric columns of every registered experiment, then one column per parameter of every experiment.
A raw file (`--raw f.csv`) has RAW_BASE_COLUMNS and the same parameter columns, one row per repetition.

The summary header does not say where the metrics end and the parameters begin, so parameter_columns()
uses, in order: the header of a raw file from the same build (exact), the metric names the scripts know
(KNOWN_METRICS and METRIC_PATTERN), and otherwise treats a filled column as a parameter.
"""
import csv
import math
import os
import re
import statistics

# Mirrors base_columns() in micro/core/runner.cpp: describe the case, the run or the timing.
BASE_COLUMNS = [
    "schema", "experiment", "variant", "pass", "status", "valid", "reason", "backend", "device", "gl_vendor",
    "gl_renderer", "gl_version", "width", "height", "reps", "warmup", "median_ms", "mad_ms", "min_ms", "max_ms",
    "mean_ms", "stddev_ms", "samples", "outliers", "cpu_median_ms", "cpu_mad_ms", "gpu_median_ms", "gpu_mad_ms",
    "timer", "compile_ms", "program_cache", "warmup_ms", "preset", "git_sha", "timestamp_utc", "hostname",
    "cpu_model", "lp_num_threads", "env", "parameters",
]
RAW_BASE_COLUMNS = ["schema", "experiment", "variant", "pass", "rep", "cpu_ms", "gpu_ms", "backend", "gl_renderer",
                    "git_sha", "timestamp_utc", "preset"]
# Parameters every experiment has (Registry::framework_params()).
FRAMEWORK_PARAMS = ["fault", "seed"]
# Metric columns declared by experiments (Experiment::metric_columns()). An experiment whose metrics
# are not listed here still works when its names match METRIC_PATTERN or a raw file is given.
KNOWN_METRICS = {
    # every experiment's metric_columns() as of this build (files without a `parameters` column need them)
    "lost_updates", "inconsistent_nodes", "line_segments", "peak_depth", "frac_pixels_off", "nonfinite",
    "polygons", "mean_depth", "node_pool", "bma_intervals", "bma_auto_choice", "bma_auto_source",
    "bma_auto_timings", "model_max_diff", "capped_updates", "flicker", "flicker_max", "lock_extension",
    "touched_outside", "sort_source",
    "predicted_occupancy", "predicted_threads_per_sm", "model_gpu_used", "mismatched_pixels",
    "rmse", "max_abs_error", "mean_abs_error", "psnr", "max_error", "mismatches", "overflow_pixels",
    "lost_fragments", "total_fragments", "peak_depth_complexity",
}
METRIC_PATTERN = re.compile(r"(error|rmse|psnr|mismatch|predicted|_used$|pixels$|overflow|_bytes$|_mb$|"
                            r"^measured_|_rate$|throughput|_per_s$)")

# Where a run's identity lives: different drivers, machines and commits, never part of a case's key.
RUN_COLUMNS = ["backend", "device", "gl_vendor", "gl_renderer", "gl_version", "git_sha", "timestamp_utc",
               "hostname", "cpu_model", "lp_num_threads", "env", "preset"]


class ResultsError(Exception):
    """A file that is not an oitbench CSV, or lacks what a script needs; the message names the file."""


def read_csv(path):
    """Rows as dicts, plus the header. Raises ResultsError naming the file on anything unreadable."""
    try:
        with open(path, newline="", encoding="utf-8") as f:
            reader = csv.DictReader(f)
            header = reader.fieldnames or []
            rows = [dict(r) for r in reader]
    except OSError as e:
        raise ResultsError(f"{path}: cannot read ({e.strerror})") from e
    except csv.Error as e:
        raise ResultsError(f"{path}: not valid CSV ({e})") from e
    except UnicodeDecodeError as e:
        raise ResultsError(f"{path}: not a text file (not UTF-8 at byte {e.start})") from e
    return header, rows


def is_summary_header(header):
    return "experiment" in header and "median_ms" in header


def is_raw_header(header):
    return "experiment" in header and "rep" in header and "cpu_ms" in header


def to_float(value):
    """float(value), or None for an empty or non-numeric field."""
    if value is None:
        return None
    value = value.strip()
    if not value:
        return None
    try:
        x = float(value)
    except ValueError:
        return None
    return x if math.isfinite(x) else None


def is_ok(row):
    return row.get("status") == "ok" and row.get("valid") == "1"


def status_of(row):
    """'invalid' for a case that ran but failed validation, else the status column."""
    return "invalid" if row.get("status") == "ok" and row.get("valid") != "1" else row.get("status", "?")


class Run:
    """One summary CSV: its rows, its parameter columns, and a label for legends and tables."""

    def __init__(self, path, header, rows, raw_params=None, label=None):
        self.path = path
        self.header = header
        self.rows = rows
        self.label = label or os.path.splitext(os.path.basename(path))[0]
        self._raw_params = raw_params
        self._params_by_exp = {}

    @classmethod
    def load(cls, path, raw_path=None, label=None):
        header, rows = read_csv(path)
        if not is_summary_header(header):
            if is_raw_header(header):
                raise ResultsError(f"{path}: this is a --raw file (one row per repetition); "
                                   "pass the --out summary file, and the raw file with --raw")
            raise ResultsError(f"{path}: not an oitbench summary CSV (no experiment/median_ms columns)")
        raw_params = None
        if raw_path:
            raw_header, _ = read_csv(raw_path)
            if not is_raw_header(raw_header):
                raise ResultsError(f"{raw_path}: not an oitbench --raw CSV (no rep/cpu_ms columns)")
            raw_params = raw_param_columns(raw_header)
        return cls(path, header, rows, raw_params, label)

    def experiments(self):
        seen = []
        for r in self.rows:
            if r["experiment"] not in seen:
                seen.append(r["experiment"])
        return seen

    def rows_of(self, experiment):
        return [r for r in self.rows if r["experiment"] == experiment]

    def params(self, experiment):
        """Parameter columns used by `experiment` (not `variant`, which has its own column)."""
        if experiment not in self._params_by_exp:
            rows = self.rows_of(experiment)
            if "parameters" in self.header and any(r.get("parameters") for r in rows):
                # Exact: the runner names each case's parameters (schema 1 files from this build on).
                candidates = []
                for r in rows:
                    for name in r.get("parameters", "").split(";"):
                        if name and name not in candidates:
                            candidates.append(name)
            elif self._raw_params is not None:
                candidates = [c for c in self._raw_params if c in self.header]
            else:
                candidates = [c for c in self.header if c not in BASE_COLUMNS]
                candidates = [c for c in candidates if c in FRAMEWORK_PARAMS or not is_metric_name(c)]
            self._params_by_exp[experiment] = [c for c in candidates if any(r.get(c, "") != "" for r in rows)]
        return self._params_by_exp[experiment]

    def metrics(self, experiment):
        params = set(self.params(experiment))
        rows = self.rows_of(experiment)
        return [c for c in self.header if c not in BASE_COLUMNS and c not in params
                and any(r.get(c, "") != "" for r in rows)]

    def renderer(self):
        """'llvmpipe (...) via egl' from the first row, for titles."""
        for r in self.rows:
            if r.get("gl_renderer"):
                return f"{r['gl_renderer']} via {r.get('backend', '?')}"
        return "unknown renderer"


def is_metric_name(column):
    return column in KNOWN_METRICS or bool(METRIC_PATTERN.search(column))


def raw_param_columns(raw_header):
    return [c for c in raw_header if c not in RAW_BASE_COLUMNS]


def varying(rows, columns):
    """The columns among `columns` that take more than one value over `rows`."""
    return [c for c in columns if len({r.get(c, "") for r in rows}) > 1]


def numeric_column(rows, column):
    """True when every filled value of `column` in `rows` is a number."""
    values = [r.get(column, "") for r in rows if r.get(column, "") != ""]
    return bool(values) and all(to_float(v) is not None for v in values)


def sort_key(value):
    """Numbers in numeric order before strings in text order."""
    x = to_float(value)
    return (0, x, "") if x is not None else (1, 0.0, value)


def robust_sigma(mad):
    """MAD to a normal-consistent standard deviation."""
    return 1.4826 * mad


def median(values):
    return statistics.median(values)


def describe_case(row, params, skip=("fault", "seed")):
    """'dynamic size=33 draws=8' for notes and table rows."""
    parts = [row.get("variant", "")]
    parts += [f"{p}={row[p]}" for p in params if p not in skip and row.get(p, "") != ""]
    if row.get("pass") and row["pass"] != "total":
        parts.append(f"pass={row['pass']}")
    return " ".join(x for x in parts if x)
