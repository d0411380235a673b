"""Comparing runs case by case (ratios, intervals, noise bands): the library behind scripts/compare.py
and report.py --compare."""
import csv
import math
import os
import random

from oitbench import cli
from oitbench import casekey
from oitbench import results as oitres
from oitbench.stats import bootstrap_ratio_ci

Z95 = 1.959964
# Standard error of a sample median relative to the standard deviation of the samples (normal data).
MEDIAN_SE_FACTOR = math.sqrt(math.pi / 2)
ROWS_PER_FIGURE = 40
SMALL_N = 10  # fewer repetitions than this: their full range is the noise
MIN_EFFECT = 1.5  # --min-effect's default: identical code moves 20-30% between runs on the 2-core VM
NOISE_K = 2.0
BOOTSTRAP = 1000
SEED = 1

# Verdict classes of a comparison (Comparison.kind), in the order the summary line counts them.
NO_DIFFERENCE, IN_BAND, OVERLAP, CHANGED = "none", "band", "overlap", "changed"
KINDS = (NO_DIFFERENCE, IN_BAND, OVERLAP, CHANGED)


class Case:
    """One row of one run: its median, spread and (with --raw) its repetitions."""

    def __init__(self, row, samples=None):
        self.row = row
        self.median = oitres.to_float(row.get("median_ms"))
        self.mad = oitres.to_float(row.get("mad_ms")) or 0.0
        self.n = int(oitres.to_float(row.get("samples")) or 1)
        self.samples = samples or []

    def cv(self):
        """Robust coefficient of variation of single repetitions."""
        return oitres.robust_sigma(self.mad) / self.median if self.median else 0.0

    def log_se(self):
        """Standard error of log(median)."""
        return MEDIAN_SE_FACTOR * self.cv() / math.sqrt(max(1, self.n))

    def typical_range(self):
        """Where this case's repetitions fall: min to max for a handful of them (a single stalled
        repetition among 3 leaves the MAD small but is real noise), else the 10-90% quantiles, or
        median +- 2 robust sigma when only the summary is known."""
        lo = oitres.to_float(self.row.get("min_ms"))
        hi = oitres.to_float(self.row.get("max_ms"))
        if len(self.samples) >= SMALL_N:
            s = sorted(self.samples)
            return s[int(0.1 * (len(s) - 1))], s[int(math.ceil(0.9 * (len(s) - 1)))]
        if self.n >= SMALL_N or lo is None or hi is None:
            sigma = oitres.robust_sigma(self.mad)
            return self.median - 2 * sigma, self.median + 2 * sigma
        return lo, hi


def param_columns(runs, experiment):
    """The same parameter columns for every run: a raw file's header is exact, so it wins."""
    exact = next((r._raw_params for r in runs if r._raw_params is not None), None)
    cols = []
    for run in runs:
        for c in (exact if exact is not None else run.params(experiment)):
            if c not in cols and any(row.get(c, "") != "" for row in run.rows_of(experiment)):
                cols.append(c)
    return cols


def case_key(row, params):
    """What joins the runs. A parameter the schema scopes away from this row (applies_where: `block` only
    for the RBS techniques, ...) is left out, so schema 1 files, which filled every parameter, join schema
    2 files, which leave those empty."""
    return casekey.key(row, params)


def load_raw_samples(path, summary_rows, params_of):
    """{raw_key(summary row): [ms]}: each ok summary row's repetitions from a raw file, in its timer. A raw
    row belongs to a summary row when experiment, variant, pass, resolution (where the raw file has it) and
    every parameter the summary row names in `parameters` agree; a parameter the raw file fills but the case
    does not use is ignored, so summary and raw rows pair for every experiment."""
    header, rows = oitres.read_csv(path)
    if not oitres.is_raw_header(header):
        raise oitres.ResultsError(f"{path}: not an oitbench --raw CSV (no rep/cpu_ms columns)")
    raw_params = set(oitres.raw_param_columns(header))
    has_size = "width" in header and "height" in header
    by_case = {}
    for r in rows:
        by_case.setdefault((r["experiment"], r["variant"], r["pass"]), []).append(r)
    samples = {}
    for s in summary_rows:
        names = [p for p in row_param_names(s, params_of.get(s["experiment"], [])) if p in raw_params]
        timer = s.get("timer", "cpu")
        for r in by_case.get((s["experiment"], s["variant"], s["pass"]), []):
            if has_size and r.get("width") and (r.get("width"), r.get("height")) != (s.get("width"), s.get("height")):
                continue
            if any(r.get(p, "") != s.get(p, "") for p in names):
                continue
            x = oitres.to_float(r.get("gpu_ms" if timer == "gpu" else "cpu_ms"))
            if x is not None and x >= 0:
                samples.setdefault(raw_key(s, params_of.get(s["experiment"], [])), []).append(x)
    return samples


row_param_names = casekey.used_params


def raw_key(row, params):
    """A summary row's identity among the raw rows: its case and the values of the parameters it uses."""
    return casekey.named_key(row, params=params, pairs=True)


class Comparison:
    """One case of one run against the same case of the first run."""

    def __init__(self, key, label, base, other, args, rng, floor=None):
        self.key, self.label, self.base, self.other = key, label, base, other
        self.ratio = other.median / base.median if base.median else float("nan")
        if len(base.samples) >= 2 and len(other.samples) >= 2:
            self.ci = bootstrap_ratio_ci(base.samples, other.samples, args.bootstrap, rng)
            self.ci_method = "bootstrap"
        else:
            se = math.sqrt(base.log_se() ** 2 + other.log_se() ** 2)
            self.ci = (self.ratio * math.exp(-Z95 * se), self.ratio * math.exp(Z95 * se))
            self.ci_method = "mad"
        self.band = max(args.min_effect if floor is None else floor,
                        math.exp(args.noise_k * math.hypot(base.cv(), other.cv())))
        excludes_one = self.ci[0] > 1 or self.ci[1] < 1
        beyond_band = self.ratio > self.band or self.ratio < 1 / self.band
        (alo, ahi), (blo, bhi) = base.typical_range(), other.typical_range()
        separate = blo > ahi if self.ratio > 1 else bhi < alo
        self.changed = excludes_one and beyond_band and separate
        band = f"{self.band:.2f}x"
        if not excludes_one:
            self.kind, self.verdict = NO_DIFFERENCE, "no measurable difference (the 95% CI includes 1)"
        elif not beyond_band:
            self.kind = IN_BAND
            self.verdict = (f"resolved, but inside the between-run noise band ({band}): not attributable to "
                            "the driver or code from one run of each")
        elif not separate:
            self.kind = OVERLAP
            self.verdict = (f"beyond the noise band ({band}), but the repetitions overlap: not attributable "
                            "from one run of each")
        else:
            self.kind, self.verdict = CHANGED, "SLOWER" if self.ratio > 1 else "FASTER"


def describe_key(key, params, constant=()):
    """'dynamic size=33 pass=resolve 800x600', leaving out what every case of the experiment shares."""
    exp, variant, pas, w, h = key[:5]
    parts = [variant] if variant and "variant" not in constant else []
    for p, v in zip(params, key[5:]):
        if v == "" or p in constant or p == "seed" or (p == "fault" and v == "none"):
            continue
        parts.append(f"{p}={v}")
    if pas != "total":
        parts.append(f"pass={pas}")
    if "resolution" not in constant:
        parts.append(f"{w}x{h}")
    return " ".join(parts) or variant


def constant_fields(keys, params):
    """Names of the key fields that are the same in every one of `keys`: said once, not per row."""
    names = ["experiment", "variant", "pass", "resolution"] + list(params)
    values = [(k[0], k[1], k[2], (k[3], k[4])) + tuple(k[5:]) for k in keys]
    return {n for i, n in enumerate(names) if len({v[i] for v in values}) == 1 and n != "pass"}


def shared_text(key, params, constant):
    parts = [f"{p}={v}" for p, v in zip(params, key[5:]) if p in constant and v != "" and p != "seed"
             and not (p == "fault" and v == "none")]
    if "variant" in constant and key[1]:
        parts.insert(0, key[1])
    if "resolution" in constant:
        parts.append(f"{key[3]}x{key[4]}")
    return " ".join(parts)


def run_identity(run):
    """Driver, renderer, backend, threads, environment, code, time, machine: what makes two runs differ
    (an LP_NUM_THREADS=1 run must not read like the default)."""
    r = next(iter(run.rows), {})
    return (f"{run.label}: driver {r.get('driver') or '?'} ({r.get('gl_renderer', '?')} via "
            f"{r.get('backend', '?')}), LP_NUM_THREADS {r.get('lp_num_threads') or '?'}, "
            f"env {r.get('env') or '-'}, git {r.get('git_sha', '?')}, {r.get('timestamp_utc', '?')}, "
            f"{r.get('hostname', '?')}")


def compare(runs, raw_paths, args):
    """All comparisons, the cases missing from some run, and the invalid ones."""
    rng = random.Random(args.seed)
    experiments = []
    for run in runs:
        for e in run.experiments():
            if e not in experiments:
                experiments.append(e)
    per_run = []  # [{key: Case}]
    params_of = {e: param_columns(runs, e) for e in experiments}
    notes = []
    for run, raw_path in zip(runs, raw_paths):
        cases = {}
        for row in run.rows:
            params = params_of[row["experiment"]]
            if not oitres.is_ok(row) or oitres.to_float(row.get("median_ms")) is None:
                continue
            key = case_key(row, params)
            if key in cases:
                notes.append(f"{run.label}: {describe_key(key, params)} appears twice; the first row is used")
                continue
            cases[key] = row
        samples = load_raw_samples(raw_path, list(cases.values()), params_of) if raw_path else {}
        per_run.append({k: Case(r, samples.get(raw_key(r, params_of[k[0]]))) for k, r in cases.items()})

    comparisons, missing = [], []
    base = per_run[0]
    bands = repeat_bands(base, getattr(args, "repeat", None) or [], params_of)
    args.data_bands = bands
    all_keys = []
    for cases in per_run:
        for k in cases:
            if k not in all_keys:
                all_keys.append(k)
    for key in all_keys:
        if key not in base or any(key not in c for c in per_run[1:]):
            absent = [run.label for run, c in zip(runs, per_run) if key not in c]
            missing.append((key, absent))
        if key not in base:
            continue
        for run, cases in zip(runs[1:], per_run[1:]):
            if key in cases:
                comparisons.append(Comparison(key, run.label, base[key], cases[key], args, rng,
                                              bands.get(key[0])))
    return comparisons, missing, params_of, notes


def repeat_bands(base, repeat_paths, params_of):
    """{experiment: noise band} from runs that repeat the first configuration (--repeat): the 95th
    percentile over its cases of how far a repeat's median lies from the first run's, max(r, 1/r). Identical
    code on the same machine moves this much between runs, so only a ratio beyond it can be the change."""
    logs = {}
    for path in repeat_paths:
        run = oitres.Run.load(path)
        for row in run.rows:
            m = oitres.to_float(row.get("median_ms"))
            if not oitres.is_ok(row) or m is None or m <= 0 or row["experiment"] not in params_of:
                continue
            b = base.get(case_key(row, params_of[row["experiment"]]))
            if b and b.median:
                logs.setdefault(row["experiment"], []).append(abs(math.log(m / b.median)))
    bands = {}
    for exp, v in logs.items():
        v.sort()
        bands[exp] = math.exp(v[min(len(v) - 1, int(math.ceil(0.95 * len(v))) - 1)])
    return bands


def fmt_ms(x):
    return f"{x:.4g}"


def print_report(runs, comparisons, missing, params_of, notes, args):
    print("runs (ratios are against the first):")
    for run in runs:
        print(f"  {run_identity(run)}")
    bands = getattr(args, "data_bands", {})
    if bands:
        print("noise band from --repeat (95th percentile of identical runs' differences): " +
              ", ".join(f"{e} {b:.3g}x" for e, b in sorted(bands.items())))
    else:
        print(f"noise band: --min-effect {args.min_effect:g}x (no --repeat runs of the first configuration to take "
              "it from the data)")
    header = f"{'case':<52} {'run':<14} {'base ms':>9} {'ms':>9} {'ratio':>7} {'95% CI':>17} {'noise':>7}  verdict"
    current = None
    constant = {}
    for c in sorted(comparisons, key=lambda c: (c.key[0], [oitres.sort_key(v) for v in c.key[1:]], c.label)):
        exp = c.key[0]
        if exp != current:
            current = exp
            constant = constant_fields([d.key for d in comparisons if d.key[0] == exp], params_of[exp])
            shared = shared_text(c.key, params_of[exp], constant)
            print(f"\n{exp}" + (f" (every case: {shared})" if shared else "") + f":\n{header}")
        desc = describe_key(c.key, params_of[exp], constant)
        ci = f"[{c.ci[0]:.2f}, {c.ci[1]:.2f}]" + ("*" if c.ci_method == "bootstrap" else " ")
        print(f"{desc:<52} {c.label:<14} {fmt_ms(c.base.median):>9} {fmt_ms(c.other.median):>9} "
              f"{c.ratio:>6.2f}x {ci:>17} {format(c.band, '.2f') + 'x':>7}  {c.verdict}")
    if any(c.ci_method == "bootstrap" for c in comparisons):
        print("\n* bootstrap over raw repetitions; otherwise from each median's MAD")
    for key, absent in missing:
        print(f"not in every run: {key[0]} {describe_key(key, params_of[key[0]])} (missing from {', '.join(absent)})")
    for n in notes:
        print(f"note: {n}")
    for run in runs:
        bad = [r for r in run.rows if not oitres.is_ok(r)]
        for r in bad:
            params = params_of.get(r["experiment"], [])
            print(f"not compared ({run.label}): {r['experiment']} {oitres.describe_case(r, params)}: "
                  f"{oitres.status_of(r)} {r.get('reason', '')}".rstrip())
    vs = f" against {runs[0].label}" + (f" ({len(runs) - 1} runs compared with it)" if len(runs) > 2 else "")
    extra = f"; {len(missing)} not in every run" if missing else ""
    print(f"\n{summary_text(comparisons, args.min_effect)}{vs}{extra}")


def tally(comparisons):
    """{kind: count} over KINDS, and the changed ones split into slower and faster."""
    counts = {k: sum(1 for c in comparisons if c.kind == k) for k in KINDS}
    counts["slower"] = sum(1 for c in comparisons if c.kind == CHANGED and c.ratio > 1)
    counts["faster"] = counts[CHANGED] - counts["slower"]
    return counts


def summary_text(comparisons, min_effect):
    """'3 no measurable difference, 5 inside the between-run noise band (at least 1.5x), 0 beyond it with
    overlapping repetitions, 4 changed (0 slower, 4 faster)': every comparison in exactly one count."""
    n = tally(comparisons)
    return (f"{n[NO_DIFFERENCE]} no measurable difference, {n[IN_BAND]} inside the between-run noise band "
            f"(at least {min_effect:g}x), {n[OVERLAP]} beyond it with overlapping repetitions, "
            f"{n[CHANGED]} changed ({n['slower']} slower, {n['faster']} faster)")


def write_csv(path, comparisons, params_of):
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(["experiment", "case", "run", "base_median_ms", "median_ms", "ratio", "ci_low", "ci_high",
                    "ci_method", "noise_band", "changed", "class", "verdict"])
        for c in comparisons:
            w.writerow([c.key[0], describe_key(c.key, params_of[c.key[0]]), c.label, c.base.median,
                        c.other.median, f"{c.ratio:.6g}", f"{c.ci[0]:.6g}", f"{c.ci[1]:.6g}", c.ci_method,
                        f"{c.band:.6g}", int(c.changed), c.kind, c.verdict])


def plain_log_formatter():
    """Matplotlib's choice of which log ticks to label, written 0.5 rather than 5x10^-1."""
    import matplotlib.ticker

    class Plain(matplotlib.ticker.LogFormatter):
        def _num_to_string(self, x, vmin, vmax):
            return f"{x:g}"
    return Plain


def key_order(key):
    """Cases in the order of their key fields: variant, pass, resolution, parameters."""
    return [oitres.sort_key(v) for v in key[1:]]


def draw_figures(out_dir, runs, comparisons, params_of, args, order=key_order):
    """compare-<experiment>.png and .svg (-1, -2, ... past ROWS_PER_FIGURE cases) in out_dir, cases from
    top to bottom in `order` (a key function of a case key); returns the paths written."""
    os.environ.setdefault("MPLBACKEND", "Agg")
    import matplotlib
    matplotlib.use(os.environ["MPLBACKEND"])
    import matplotlib.pyplot as plt
    PlainLogFormatter = plain_log_formatter()

    written = []
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    labels = [r.label for r in runs[1:]]
    by_exp = {}
    for c in comparisons:
        by_exp.setdefault(c.key[0], []).append(c)
    for exp, comps in by_exp.items():
        keys = sorted({c.key for c in comps}, key=order)
        pages = [keys[i:i + ROWS_PER_FIGURE] for i in range(0, len(keys), ROWS_PER_FIGURE)]
        for page_no, page in enumerate(pages):
            fig, ax = plt.subplots(figsize=(9.5, 1.6 + 0.32 * len(page) * max(1, len(labels)) ** 0.5))
            index = {k: i for i, k in enumerate(page)}
            offset = 0.6 / max(1, len(labels))
            for c in comps:
                if c.key not in index:
                    continue
                j = labels.index(c.label)
                y = index[c.key] + (j - (len(labels) - 1) / 2) * offset
                ax.plot([1 / c.band, c.band], [y, y], color="lightgrey", linewidth=6, solid_capstyle="butt",
                        zorder=1)
                ax.errorbar(c.ratio, y, xerr=[[c.ratio - c.ci[0]], [c.ci[1] - c.ratio]], fmt="o",
                            color=colors[j % len(colors)], capsize=3, zorder=3,
                            markeredgecolor="red" if c.changed else colors[j % len(colors)],
                            markeredgewidth=2 if c.changed else 1, markersize=8 if c.changed else 5)
                if c.changed:
                    ax.annotate(c.verdict.lower(), (c.ci[1], y), xytext=(4, -3), textcoords="offset points",
                                fontsize=7, color="red")
            for j, lab in enumerate(labels):
                ax.plot([], [], "o", color=colors[j % len(colors)], label=f"{lab} / {runs[0].label}")
            ax.plot([], [], color="lightgrey", linewidth=6, label="noise band")
            ax.axvline(1.0, color="black", linewidth=0.8)
            ax.set_xscale("log")
            ax.xaxis.set_major_formatter(PlainLogFormatter())
            ax.xaxis.set_minor_formatter(PlainLogFormatter(labelOnlyBase=False))
            ax.tick_params(axis="x", which="minor", labelsize=7)
            ax.set_yticks(range(len(page)))
            constant = constant_fields(keys, params_of[exp])
            ax.set_yticklabels([describe_key(k, params_of[exp], constant) for k in page], fontsize=8)
            ax.invert_yaxis()
            ax.set_xlabel(f"median time ratio against {runs[0].label} (95% CI; >1 is slower)")
            ax.grid(True, axis="x", which="both", alpha=0.3)
            ax.legend(fontsize=8, loc="best")
            n_changed = sum(1 for c in comps if c.changed and c.key in index)
            shared = shared_text(page[0], params_of[exp], constant)
            ax.set_title(f"{exp}" + (f" ({shared})" if shared else "") + f": {n_changed} of {sum(1 for c in comps if c.key in index)} comparisons changed"
                         f"\n{runs[0].renderer()}" + (" (and others)" if len({r.renderer() for r in runs}) > 1
                                                       else ""), fontsize=10)
            suffix = f"-{page_no + 1}" if len(pages) > 1 else ""
            # The files depend only on the data: fixed SVG ids and no date, so a rerun changes nothing.
            with plt.rc_context({"svg.hashsalt": "oitbench"}):
                for fmt in ("png", "svg"):
                    path = os.path.join(out_dir, f"compare-{exp}{suffix}.{fmt}")
                    fig.savefig(path, dpi=120, bbox_inches="tight",
                                metadata={"Date": None} if fmt == "svg" else None)
                    written.append(path)
            plt.close(fig)
    return written


def add_statistics_options(ap):
    """The options that decide ratios, intervals and verdicts (report.py --compare takes them too)."""
    ap.add_argument("--min-effect", type=cli.number(float, low=1.0), default=MIN_EFFECT,
                    help=f"smallest ratio (or 1/ratio) that counts as a change: the between-run noise band "
                         f"(default {MIN_EFFECT:g})")
    ap.add_argument("--noise-k", type=cli.non_negative(), default=NOISE_K,
                    help=f"noise band width in robust standard deviations of log time (default {NOISE_K:g})")
    ap.add_argument("--bootstrap", type=cli.positive(int), default=BOOTSTRAP,
                    help=f"bootstrap resamples (default {BOOTSTRAP})")
    ap.add_argument("--seed", type=cli.number(int), default=SEED, help=f"bootstrap seed (default {SEED})")
