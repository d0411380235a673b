#!/usr/bin/python3
"""Figures from oitbench runs: one PNG and one SVG per experiment and input file.

    scripts/plot.py RUN.csv [RUN2.csv ...] [-o DIR]

Only valid rows (status ok, valid 1) are drawn; the others are listed on stdout and in a note on the
figure. Each experiment gets its own plot function from PLOTTERS; an experiment without one gets
generic_plot(): median ms against its main numeric parameter, one line per variant, MAD as error bars.
Adding a figure for a new experiment: write `def plot_<name>(data)` returning a Figure and decorate it
with @plotter("<name>"); curves() and bars() do most of the work.
"""
import argparse
import math
import os
import signal
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
os.environ.setdefault("MPLBACKEND", "Agg")

import matplotlib  # noqa: E402

matplotlib.use(os.environ["MPLBACKEND"])
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import FuncFormatter  # noqa: E402

import oitcsv  # noqa: E402

PLOTTERS = {}
MAX_FACETS = 6
MAX_NOTE_LINES = 6
MAX_LEGEND_INSIDE = 8  # more entries than this go beside the axes, where they cover no curve


def plotter(experiment):
    def register(fn):
        PLOTTERS[experiment] = fn
        return fn
    return register


class ExperimentData:
    """What a plot function gets: the valid rows of one experiment from one run, and its columns."""

    def __init__(self, run, experiment):
        self.run = run
        self.experiment = experiment
        rows = run.rows_of(experiment)
        self.ok = [r for r in rows if oitcsv.is_ok(r) and oitcsv.to_float(r.get("median_ms")) is not None]
        self.invalid = [r for r in rows if not oitcsv.is_ok(r)]
        self.params = [p for p in run.params(experiment) if p not in oitcsv.FRAMEWORK_PARAMS]
        self.metrics = run.metrics(experiment)
        self.passes = sorted({r["pass"] for r in self.ok}, key=lambda p: (p == "total", p))

    def total_rows(self):
        """The `total` row of every case (a case without named passes has only that one)."""
        return [r for r in self.ok if r["pass"] == "total"]

    def varying_params(self, rows=None):
        return oitcsv.varying(rows if rows is not None else self.ok, self.params)

    def first_param(self, candidates, numeric=False, rows=None):
        """The first of `candidates` that this experiment has and varies (numeric when asked)."""
        rows = rows if rows is not None else self.ok
        for c in candidates:
            if c in self.params and c in self.varying_params(rows):
                if not numeric or oitcsv.numeric_column(rows, c):
                    return c
        return None

    def main_numeric_param(self, rows=None, exclude=()):
        """The numeric parameter with the most distinct values: the natural x axis."""
        rows = rows if rows is not None else self.ok
        best, best_n = None, 1
        for p in self.varying_params(rows):
            if p in exclude or not oitcsv.numeric_column(rows, p):
                continue
            n = len({r[p] for r in rows})
            if n > best_n:
                best, best_n = p, n
        return best


def value(row, column="median_ms"):
    return oitcsv.to_float(row.get(column))


def resolution(data):
    sizes = sorted({f"{r['width']}x{r['height']}" for r in data.ok + data.invalid if r.get("width")})
    return ", ".join(sizes)


def title_of(data, what=None):
    head = f"{data.experiment}" + (f": {what}" if what else "")
    return f"{head}\n{data.run.renderer()}, {resolution(data)}  [{data.run.label}]"


def group_label(row, columns):
    parts = []
    for c in columns:
        if c == "variant":
            parts.append(row.get("variant", ""))
        elif c == "pass":
            parts.append(f"pass {row['pass']}")
        else:
            parts.append(f"{c}={row.get(c, '')}")
    return ", ".join(p for p in parts if p)


def group_rows(rows, columns):
    groups = {}
    for r in rows:
        groups.setdefault(tuple(r.get(c, "") for c in columns), []).append(r)
    return dict(sorted(groups.items(), key=lambda kv: [oitcsv.sort_key(v) for v in kv[0]]))


def log2_ticks(ax, xs):
    """Powers of two (and the values actually measured near a cliff) as plain numbers."""
    lo, hi = min(xs), max(xs)
    ticks = [2 ** k for k in range(int(math.floor(math.log2(lo))), int(math.ceil(math.log2(hi))) + 1)]
    ax.set_xscale("log", base=2)
    ax.set_xticks(ticks)
    ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    ax.xaxis.set_minor_formatter(FuncFormatter(lambda v, _: ""))


def spread_is_wide(values):
    pos = [v for v in values if v and v > 0]
    return len(pos) > 1 and max(pos) / min(pos) > 20


def draw_lines(ax, rows, x, label_columns, per=1.0, per_column=None):
    """One line per group of `label_columns`, y = median_ms / per (or / row[per_column]), MAD bars."""
    xs_all, ys_all = [], []
    n_colors = len(plt.rcParams["axes.prop_cycle"].by_key()["color"])
    for i, (key, grp) in enumerate(group_rows(rows, label_columns).items()):
        pts = []
        for r in grp:
            xv, y, mad = oitcsv.to_float(r.get(x)), value(r), value(r, "mad_ms") or 0.0
            div = (oitcsv.to_float(r.get(per_column)) if per_column else per) or 1.0
            if xv is not None and y is not None:
                pts.append((xv, y / div, mad / div))
        pts.sort()
        if not pts:
            continue
        xs, ys, es = zip(*pts)
        # Past the colour cycle the line style changes, so two curves never look the same.
        ax.errorbar(xs, ys, yerr=es, marker="o", markersize=4, capsize=3, linewidth=1.5,
                    linestyle=("-", "--", ":", "-.")[(i // n_colors) % 4],
                    label=group_label(grp[0], label_columns) or "all")
        xs_all += xs
        ys_all += ys
    return xs_all, ys_all


def curves(data, x_candidates=(), facet_candidates=(), ylabel="median time (ms)", what=None, logy=None):
    """Median vs x, one line per variant (and per other varying parameter), one panel per facet value."""
    rows = data.total_rows()
    x = data.first_param(x_candidates, numeric=True, rows=rows) or data.main_numeric_param(rows)
    if x is None:
        return bars(data, what=what)
    facet = data.first_param([f for f in facet_candidates if f != x], rows=rows)
    facets = group_rows(rows, [facet]) if facet else {(): rows}
    facets = dict(list(facets.items())[:MAX_FACETS])
    others = [p for p in data.varying_params(rows) if p not in (x, facet)]
    label_columns = ["variant"] + others
    fig, axes = plt.subplots(1, len(facets), figsize=(5.2 * len(facets) + 1.5, 4.6), squeeze=False,
                             sharey=True)
    for ax, (fkey, frows) in zip(axes[0], facets.items()):
        xs, ys = draw_lines(ax, frows, x, label_columns)
        if xs and min(xs) > 0 and max(xs) / min(xs) >= 8:
            # Sizes and counts (n, SIZE, nodes) read best on powers of two; millions of segments do not.
            if max(xs) <= 4096:
                log2_ticks(ax, xs)
            else:
                ax.set_xscale("log")
        if logy or (logy is None and spread_is_wide(ys)):
            ax.set_yscale("log")
        ax.set_xlabel(x)
        ax.grid(True, which="both", alpha=0.3)
        if facet:
            ax.set_title(f"{facet} = {fkey[0]}", fontsize=10)
    axes[0][0].set_ylabel(ylabel)
    legend(axes[0][-1])
    fig.suptitle(title_of(data, what), fontsize=10)
    if facet:
        fig.subplots_adjust(top=0.82)  # the two-line title above the panels' own titles
    return fig


def bars(data, category_candidates=(), what=None, ylabel="median time (ms)"):
    """Grouped bars: one group per variant (or the first of `category_candidates`), one bar per
    combination of the other varying parameters, MAD as error bars."""
    rows = data.total_rows()
    category = data.first_param(category_candidates, rows=rows) or "variant"
    others = [c for c in (["variant"] + data.varying_params(rows)) if c != category and
              (c != "variant" or len({r["variant"] for r in rows}) > 1)]
    categories = list(group_rows(rows, [category]).keys())
    series = group_rows(rows, others) if others else {(): rows}
    fig, ax = plt.subplots(figsize=(max(6.0, 1.0 + 0.5 * len(categories) * max(1, len(series))), 4.6))
    width = 0.8 / max(1, len(series))
    for i, (skey, srows) in enumerate(series.items()):
        by_cat = {r.get(category, ""): r for r in srows}
        xs, ys, es = [], [], []
        for j, ckey in enumerate(categories):
            r = by_cat.get(ckey[0])
            if r is not None:
                xs.append(j + (i - (len(series) - 1) / 2) * width)
                ys.append(value(r))
                es.append(value(r, "mad_ms") or 0.0)
        ax.bar(xs, ys, width=width, yerr=es, capsize=3,
               label=group_label(srows[0], others) if others else None)
    ax.set_xticks(range(len(categories)))
    # Slanted when the names would run into each other.
    slant = len(categories) > 4 or sum(len(str(c[0])) for c in categories) > 40
    ax.set_xticklabels([c[0] for c in categories], rotation=20 if slant else 0, ha="right" if slant else "center")
    ax.set_xlabel(category)
    ax.set_ylabel(ylabel)
    ax.grid(True, axis="y", alpha=0.3)
    if others:
        legend(ax)
    fig.suptitle(title_of(data, what), fontsize=10)
    return fig


def legend(ax):
    """Inside the axes where it fits; a long one to the right of them (savefig's tight box keeps it)."""
    if len(ax.get_legend_handles_labels()[1]) > MAX_LEGEND_INSIDE:
        ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0, handlelength=3.5)
    else:
        ax.legend(fontsize=8, loc="best")


def generic_plot(data):
    rows = data.total_rows()
    if data.main_numeric_param(rows):
        others = [p for p in data.varying_params(rows) if p != data.main_numeric_param(rows)]
        return curves(data, facet_candidates=others[:1])
    return bars(data)


@plotter("occupancy")
def plot_occupancy(data):
    """The staircase: ms per full-screen draw against the local array size, with the model's occupancy."""
    rows = data.total_rows()
    others = [p for p in data.varying_params(rows) if p not in ("size", "draws")]
    fig, ax = plt.subplots(figsize=(8.5, 5.0))
    draws_vary = "draws" in data.varying_params(rows)
    label_columns = ["variant"] + (["draws"] if draws_vary else []) + others
    xs, ys = draw_lines(ax, rows, "size", label_columns, per_column="draws")
    if not xs:
        ax.text(0.5, 0.5, "no valid rows", ha="center", transform=ax.transAxes)
        return fig
    log2_ticks(ax, xs)
    ax.set_yscale("log" if spread_is_wide(ys) else "linear")
    ax.set_xlabel("SIZE (elements in vec4 myArray[SIZE])")
    ax.set_ylabel("median ms per draw (MAD bars)")
    ax.grid(True, which="both", alpha=0.3)
    annotate_unroll_cliff(ax, data, rows, label_columns)

    occ = [(oitcsv.to_float(r.get("size")), oitcsv.to_float(r.get("predicted_occupancy")))
           for r in rows if oitcsv.to_float(r.get("predicted_occupancy")) is not None]
    # Measured where the driver could (GL_NV_shader_thread_group): one marker per variant and size.
    measured = sorted({(r.get("variant", ""), oitcsv.to_float(r.get("size")),
                        oitcsv.to_float(r.get("measured_occupancy")))
                       for r in rows if oitcsv.to_float(r.get("measured_occupancy")) is not None})
    if occ or measured:
        occ = sorted(set(occ))
        ax2 = ax.twinx()
        if occ:
            ax2.step([s for s, _ in occ], [o for _, o in occ], where="post", color="grey", linestyle="--",
                     label="predicted occupancy")
        for i, variant in enumerate(sorted({v for v, _, _ in measured})):
            pts = [(s, m) for v, s, m in measured if v == variant]
            ax2.plot([s for s, _ in pts], [m for _, m in pts], "s^o"[i % 3], color="black", fillstyle="none",
                     linestyle="none", label=f"measured occupancy ({variant})" if variant else "measured occupancy")
        label = "predicted occupancy (model, %s)" % next(
            (r.get("model_gpu_used") for r in rows if r.get("model_gpu_used")), "?") if occ else "occupancy"
        ax2.set_ylabel(label + (", measured" if measured and occ else " (measured)" if measured else ""))
        ax2.set_ylim(0, max(1.05, max(o for _, o in occ + [(0, m) for _, _, m in measured]) * 1.05))
        # One legend, drawn on the top axes so the occupancy line does not run through it.
        h1, l1 = ax.get_legend_handles_labels()
        h2, l2 = ax2.get_legend_handles_labels()
        ax2.legend(h1 + h2, l1 + l2, loc="upper left", fontsize=8, framealpha=1.0)
    else:
        ax.legend(loc="upper left", fontsize=8)
    fig.suptitle(title_of(data, "local array size vs time (Knowles 2013, fig. 3)"), fontsize=10)
    return fig


def annotate_unroll_cliff(ax, data, rows, label_columns):
    """Marks the biggest jump between SIZE 32 and 33: where llvmpipe's NIR stops unrolling loops."""
    best = None
    for key, grp in group_rows(rows, label_columns).items():
        by_size = {oitcsv.to_float(r["size"]): r for r in grp}
        if 32 in by_size and 33 in by_size:
            t32 = value(by_size[32]) / (oitcsv.to_float(by_size[32].get("draws")) or 1)
            t33 = value(by_size[33]) / (oitcsv.to_float(by_size[33].get("draws")) or 1)
            if t32 > 0 and (best is None or t33 / t32 > best[0]):
                best = (t33 / t32, t33, group_label(grp[0], label_columns))
    if best is None or best[0] < 2:
        return
    why = "llvmpipe: NIR unrolls loops up to 32 iterations" if "llvmpipe" in data.run.renderer() else \
        "the loop is no longer unrolled"
    ax.annotate(f"32 \u2192 33: {best[0]:.1f}x ({best[2]})\n{why}", xy=(33, best[1]),
                xytext=(0.04, 0.62), textcoords="axes fraction", fontsize=8,
                arrowprops=dict(arrowstyle="->", color="black"),
                bbox=dict(boxstyle="round", fc="lightyellow", alpha=0.9))


@plotter("sort")
def plot_sort(data):
    return curves(data, x_candidates=("n", "count", "size", "fragments", "depth", "layers"),
                  facet_candidates=("keys", "distribution", "order", "input", "stage"),
                  what="per-pixel sorts against n")


@plotter("insert")
def plot_insert(data):
    return curves(data, x_candidates=("n", "size", "max_frags", "k", "count", "depth", "layers"),
                  facet_candidates=("stage", "keys", "distribution", "order", "scene"),
                  what="insertion into per-pixel arrays against n")


@plotter("stencil")
def plot_stencil(data):
    return curves(data, x_candidates=("coverage", "fill", "fraction", "size", "n"),
                  facet_candidates=("size", "max_frags", "layers", "n"),
                  what="stencil-masked passes against coverage")


@plotter("layout")
def plot_layout(data):
    return bars(data, category_candidates=("layout", "storage"), what="storage layouts")


@plotter("spinlock")
def plot_spinlock(data):
    return bars(data, category_candidates=("lock", "spinlock", "mode"), what="spinlock variants")


ERROR_COLUMNS = ("rmse", "max_abs_error")


OIT_APPROX = {"MLAB", "UMLAB", "AT", "HAT", "UAT", "UHAT", "LAAT", "WBOIT", "unsorted", "HT"}
OIT_PEEL = {"DP", "DDP"}


def oit_label(row):
    """The technique as the papers name it, with the node count where it matters (approximate ones)."""
    t = row.get("technique") or row.get("variant") or "?"
    if t in OIT_APPROX and t not in ("WBOIT", "unsorted") and row.get("nodes"):
        t += f"/{row['nodes']}"
    if t == "WBOIT" and row.get("wboit_weight"):
        t += f"/{row['wboit_weight']}"
    if t in OIT_PEEL and row.get("max_layers") not in (None, "", "0"):
        t += f"/{row['max_layers']}"
    if t == "MBOIT" and row.get("moments"):  # MBOIT/6p: 6 power moments; /3t trigonometric; /16 bits
        t += f"/{row['moments']}{'t' if row.get('moment_kind') == 'trigonometric' else 'p'}"
        if row.get("moment_bits") == "16":
            t += "/16"
    if t == "STOCHASTIC" and row.get("samples_per_pixel"):
        t += f"/{row['samples_per_pixel']}"
    # Fragment formats other than the papers' (rgba8, window depth) are part of the case's name.
    for col, default in (("frag_colour", "rgba8"), ("frag_depth", "window")):
        if row.get(col) and row[col] != default:
            t += f"/{row[col]}"
    return t


def effects_vary(rows):
    """True where the rows ran more than one set of scene effects (effects=transparency,opaque+transparency)."""
    return len({r.get("effects") for r in rows if r.get("effects")}) > 1


def oit_effects_label(row, with_effects):
    """oit_label(), and the effects that ran when a figure compares effect sets (its fragments beside)."""
    label = oit_label(row)
    if with_effects and row.get("effects"):
        label += f"\n[{row['effects']}]"
        if row.get("total_fragments"):
            label += f" {oitcsv.to_float(row['total_fragments']):,.0f} frags"
    return label


def has_formats(rows):
    """True when the rows vary the fragment format (the precision preset)."""
    return any(r.get("frag_colour") not in (None, "", "rgba8") or r.get("frag_depth") not in (None, "", "window")
               for r in rows)


def format_cost(ax, rows, title):
    """What precision costs: each case a point at its time and its error against the truth (the geometric
    reference's truth_rmse where the scene is analytic, else rmse against the captured fragments), the
    point's area and label giving its fragment storage (node_pool_bytes)."""
    column = "truth_rmse" if any(oitcsv.to_float(r.get("truth_rmse")) is not None for r in rows) else "rmse"
    floor = 1e-9
    colors = {"rgba8": "tab:blue", "rgba16f": "tab:orange", "rgba32f": "tab:green"}
    for r in rows:
        t, e = value(r), oitcsv.to_float(r.get(column))
        if t is None or e is None:
            continue
        mib = (oitcsv.to_float(r.get("node_pool_bytes")) or 0.0) / 2**20
        ax.scatter(t, max(e, floor), s=20 + 30 * mib ** 0.5, color=colors.get(r.get("frag_colour"), "tab:gray"),
                   marker="o" if r.get("frag_depth") != "view" else "s", alpha=0.8, zorder=3)
        ax.annotate(f"{oit_label(r)} {mib:.2f} MiB", (t, max(e, floor)), fontsize=6, xytext=(3, 2),
                    textcoords="offset points")
    for name, c in colors.items():
        ax.scatter([], [], color=c, label=name)
    ax.scatter([], [], color="black", marker="o", label="window depth")
    ax.scatter([], [], color="black", marker="s", label="view depth")
    ax.legend(fontsize=7, loc="upper right")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("total median time (ms); area: fragment storage")
    ax.set_ylabel(f"{column} (floor {floor:g})")
    ax.grid(True, which="both", alpha=0.3)
    ax.set_title(f"fragment format: time, memory, error: {title}", fontsize=9)


class _Relabelled:
    """`data` with the variant column replaced by oit_label(), so the shared bar helpers label by technique
    (and by the effects that ran where those vary: each effect's passes are rows of their own, stacked)."""

    def __init__(self, data, rows):
        with_effects = effects_vary(rows)
        self.ok = [dict(r, variant=oit_effects_label(r, with_effects)) for r in rows]
        self.params = data.params
        self.passes = data.passes


EFFECT_INITIALS = {"opaque": "O", "transparency": "T", "self-shadowing": "S"}


def effects_short(effects):
    """opaque+transparency -> O+T (the legend spells them out)."""
    return "+".join(EFFECT_INITIALS.get(e, e) for e in (effects or "").split("+") if e)


def fmt_count(v):
    v = oitcsv.to_float(v)
    if v is None:
        return ""
    return f"{v / 1e6:.1f}M" if v >= 1e6 else f"{v / 1e3:.0f}k" if v >= 1e4 else f"{v:.0f}"


def effects_panel(ax, rows, passes, title, legend):
    """Per technique one bar per effect set, side by side: the case's passes stacked (effect passes and the
    technique's alike), the fragments it captured above the bar: what each effect costs and saves."""
    totals = [r for r in rows if r["pass"] == "total"]
    techniques = sorted({oit_label(r) for r in totals})
    sets = sorted({r.get("effects", "") for r in totals}, key=lambda e: (len(e.split("+")), e))
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    width = 0.8 / max(len(sets), 1)
    drawn = set()
    ticks, labels = [], []
    for ti, t in enumerate(techniques):
        for si, e in enumerate(sets):
            case = [r for r in rows if oit_label(r) == t and r.get("effects", "") == e]
            total = next((r for r in case if r["pass"] == "total"), None)
            if total is None:
                continue
            x = ti + (si - (len(sets) - 1) / 2) * width
            own = {r["pass"]: value(r) for r in case if r["pass"] != "total"}
            if not own:  # a single-pass case writes only its total
                own = {"(single pass)": value(total)}
            bottom = 0.0
            for p in passes + ["(single pass)"]:
                if p not in own:
                    continue
                k = (passes + ["(single pass)"]).index(p)
                ax.bar(x, own[p], width * 0.92, bottom=bottom, color=colors[k % len(colors)],
                       label=p if p not in drawn else None)
                drawn.add(p)
                bottom += own[p]
            ax.scatter([x], [value(total)], marker="_", s=120, color="black", zorder=3,
                       label="total (measured)" if "total" not in drawn else None)
            drawn.add("total")
            frags = fmt_count(total.get("total_fragments"))
            if frags:
                ax.annotate(frags, (x, max(bottom, value(total) or 0)), xytext=(0, 3), textcoords="offset points",
                            ha="center", fontsize=6, rotation=90)
            ticks.append(x)
            labels.append(effects_short(e))
    ax.set_xticks(ticks)
    ax.set_xticklabels(labels, fontsize=6)
    for ti, t in enumerate(techniques):
        ax.annotate(t, (ti, 0), xycoords=("data", "axes fraction"), xytext=(0, -18), textcoords="offset points",
                    ha="center", fontsize=8)
    ax.set_ylim(0, ax.get_ylim()[1] * 1.6)  # room for the legend above the bars
    ax.set_ylabel("median time (ms)")
    ax.grid(True, axis="y", alpha=0.3)
    ax.set_title(title + " (above each bar: fragments captured)", fontsize=9)
    if legend:
        ax.legend(fontsize=6, loc="upper center", ncol=4, title=", ".join(f"{v}={k}" for k, v in EFFECT_INITIALS.items()),
                  title_fontsize=6)


@plotter("oit")
def plot_oit(data):
    """One column per (scene, view, resolution): stacked pass times per technique on top, below it the
    error against the exact reference against total time, every technique a point sized by its memory
    (bytes_per_pixel), with the Pareto front (nothing both faster and more exact) marked, and at the
    bottom the error against memory with its own front: pick by error, time and memory at once."""
    totals = data.total_rows()
    key_cols = [c for c in ("scene", "view", "width") if any(r.get(c) for r in totals)]
    groups = dict(list(group_rows(totals, key_cols).items())[:MAX_FACETS])
    error_col = next((c for c in ERROR_COLUMNS if any(oitcsv.to_float(r.get(c)) is not None for r in totals)), None)
    ncols = max(len(groups), 1)
    formats = has_formats(totals)
    memory = error_col is not None and any(oitcsv.to_float(r.get("bytes_per_pixel")) is not None for r in totals)
    nrows = ((3 if memory else 2) if error_col else 1) + (1 if formats else 0)
    fig, axes = plt.subplots(nrows, ncols, figsize=(max(7.0, 6.0 * ncols), 5.2 * nrows + 0.8), squeeze=False)
    for i, (gkey, grows) in enumerate(groups.items()):
        title = ", ".join(f"{c}={grows[0].get(c)}" for c in key_cols)
        same = [r for r in data.ok if all(r.get(c) == grows[0].get(c) for c in key_cols)]
        if effects_vary(same):
            effects_panel(axes[0][i], same, [p for p in data.passes if p != "total"], title, legend=(i == 0))
        else:
            rel = _Relabelled(data, same)
            stacked_passes(axes[0][i], rel, [r for r in rel.ok if r["pass"] == "total"], title, legend=(i == 0))
        if error_col:
            error_vs_time(axes[1][i], grows, error_col, title)
        if memory:
            error_vs_memory(axes[2][i], grows, error_col, title)
        if formats:
            format_cost(axes[nrows - 1][i], grows, title)
    fig.suptitle(title_of(data, "techniques: pass times, error against time" + (" and memory" if memory else "")),
                 fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 0.95))
    return fig


def marker_area(bytes_per_pixel, largest):
    """Marker area in points^2 proportional to memory (12 to 200), 28 where a row has no bytes_per_pixel."""
    if bytes_per_pixel is None or not largest:
        return 28
    return 12 + 188 * bytes_per_pixel / largest


def error_vs_time(ax, rows, column, title):
    with_effects = effects_vary(rows)
    points = [(value(r), oitcsv.to_float(r.get(column)), oit_effects_label(r, with_effects).split("\n")[0] +
               (f" [{r.get('effects')}]" if with_effects else ""), oitcsv.to_float(r.get("bytes_per_pixel")))
              for r in rows if oitcsv.to_float(r.get(column)) is not None and value(r) is not None]
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    families = sorted({p[2].split("/")[0] for p in points})
    floor = 1e-6  # exact techniques (error ~1e-8) sit on the floor of the log axis
    largest = max((p[3] for p in points if p[3] is not None), default=None)
    for t, e, label, mem in points:
        fam = label.split("/")[0]
        ax.scatter(t, max(e, floor), color=colors[families.index(fam) % len(colors)], s=marker_area(mem, largest),
                   alpha=0.8, zorder=3)
        ax.annotate(label, (t, max(e, floor)), fontsize=6, xytext=(3, 2), textcoords="offset points")
    points = [p[:3] for p in points]
    front = pareto_front([(t, max(e, floor), l) for t, e, l in points])
    if front:
        ax.step([p[0] for p in front], [p[1] for p in front], where="post", color="tab:red", linewidth=1.0,
                linestyle="--", label="Pareto front")
        ax.scatter([p[0] for p in front], [p[1] for p in front], facecolors="none", edgecolors="tab:red", s=90,
                   zorder=4)
        ax.legend(fontsize=7, loc="upper right")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("total median time (ms)")
    ax.set_ylabel(f"{column} against exact (floor {floor:g})")
    ax.grid(True, which="both", alpha=0.3)
    title_note = f" (marker area: bytes/pixel, largest {largest:g})" if largest else ""
    ax.set_title(f"{column} against time: {title}{title_note}", fontsize=9)


def error_vs_memory(ax, rows, column, title):
    """Error against bytes_per_pixel, every technique a point, with the front of nothing both smaller
    and more exact."""
    points = [(oitcsv.to_float(r.get("bytes_per_pixel")), oitcsv.to_float(r.get(column)), oit_label(r))
              for r in rows if oitcsv.to_float(r.get(column)) is not None
              and oitcsv.to_float(r.get("bytes_per_pixel")) is not None]
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    families = sorted({p[2].split("/")[0] for p in points})
    floor = 1e-6
    for b, e, label in points:
        fam = label.split("/")[0]
        ax.scatter(max(b, 1.0), max(e, floor), color=colors[families.index(fam) % len(colors)], s=28, zorder=3)
        ax.annotate(label, (max(b, 1.0), max(e, floor)), fontsize=6, xytext=(3, 2), textcoords="offset points")
    front = pareto_front([(max(b, 1.0), max(e, floor), l) for b, e, l in points])
    if front:
        ax.step([p[0] for p in front], [p[1] for p in front], where="post", color="tab:red", linewidth=1.0,
                linestyle="--", label="Pareto front")
        ax.legend(fontsize=7, loc="upper right")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("bytes per pixel (the technique's storage; 0 drawn at 1)")
    ax.set_ylabel(f"{column} against exact (floor {floor:g})")
    ax.grid(True, which="both", alpha=0.3)
    ax.set_title(f"{column} against memory: {title}", fontsize=9)


def stacked_passes(ax, data, totals, title, legend=True):
    """One bar per technique: its named passes stacked, with the measured total as a black tick."""
    variants = sorted({r["variant"] for r in totals})
    case_of = {r["variant"]: r for r in totals}
    passes = [p for p in data.passes if p != "total"]
    same_case = {}
    for r in data.ok:
        t = case_of.get(r["variant"])
        if t is not None and all(r.get(p) == t.get(p) for p in data.params) and \
                r.get("width") == t.get("width"):
            same_case[(r["variant"], r["pass"])] = r
    bottom = [0.0] * len(variants)
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for k, p in enumerate(passes):
        ys = [value(same_case[(v, p)]) if (v, p) in same_case else 0.0 for v in variants]
        ax.bar(range(len(variants)), ys, bottom=bottom, label=p, color=colors[k % len(colors)])
        bottom = [b + y for b, y in zip(bottom, ys)]
    tot = [value(case_of[v]) for v in variants]
    ax.scatter(range(len(variants)), tot, marker="_", s=300, color="black", zorder=3, label="total (measured)")
    ax.set_xticks(range(len(variants)))
    ax.set_xticklabels(variants, rotation=35, ha="right", fontsize=8)
    ax.set_ylabel("median time (ms)")
    ax.grid(True, axis="y", alpha=0.3)
    ax.set_title(title, fontsize=9)
    if legend:
        ax.legend(fontsize=7, loc="upper right")


def pareto_front(points):
    """Points (time, error, ...) that no other point beats in both time and error, by time."""
    front = []
    for p in sorted(points, key=lambda q: (q[0], q[1])):
        if not front or p[1] < front[-1][1]:
            front.append(p)
    return front


def pareto_scatter(ax, data, column, group_cols, legend=True):
    totals = data.total_rows()
    variants = sorted({r["variant"] for r in totals})
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    markers = "osD^vP*X"
    groups = group_rows(totals, group_cols) if group_cols else {(): totals}
    for gi, (gkey, grows) in enumerate(groups.items()):
        points = [(value(r), oitcsv.to_float(r.get(column)), r["variant"]) for r in grows
                  if oitcsv.to_float(r.get(column)) is not None]
        for t, e, v in points:
            ax.scatter(t, e, color=colors[variants.index(v) % len(colors)], marker=markers[gi % len(markers)],
                       s=30, zorder=3)
        front = pareto_front(points)
        if front:
            ax.step([p[0] for p in front], [p[1] for p in front], where="post", color="tab:red",
                    linewidth=0.9, linestyle="--", alpha=0.7)
            ax.scatter([p[0] for p in front], [p[1] for p in front], facecolors="none", edgecolors="tab:red",
                       s=110, zorder=2)
            for t, e, v in front:
                ax.annotate(v, (t, e), fontsize=7, xytext=(5, 4), textcoords="offset points", color="tab:red")
    if legend:
        handles = [plt.Line2D([], [], color=colors[i % len(colors)], marker="o", linestyle="", label=v)
                   for i, v in enumerate(variants)]
        if group_cols:
            handles += [plt.Line2D([], [], color="black", markerfacecolor="none", marker=markers[i % len(markers)], linestyle="",
                                   label=group_label(g[0], group_cols)) for i, g in enumerate(groups.values())]
        handles.append(plt.Line2D([], [], color="tab:red", marker="o", markerfacecolor="none", linestyle="--",
                                  label="Pareto front (per group)"))
        ax.legend(handles=handles, fontsize=7, loc="center left", bbox_to_anchor=(1.02, 0.5))
    times = [value(r) for r in totals]
    if spread_is_wide(times) or (times and max(times) / max(min(times), 1e-9) > 8):
        ax.set_xscale("log")
    ax.set_xlabel("total median time (ms)")
    ax.set_ylabel(column)
    ax.grid(True, alpha=0.3)
    ax.set_title(f"{column} against time", fontsize=9)


def invalid_lines(data):
    params = data.params
    seen, lines = set(), []
    for r in data.invalid:
        text = f"{oitcsv.describe_case(r, params)}: {oitcsv.status_of(r)}" + (
            f" ({r['reason']})" if r.get("reason") else "")
        if text not in seen:
            seen.add(text)
            lines.append(text)
    return lines


def add_invalid_note(fig, lines):
    if not lines:
        return
    shown = lines[:MAX_NOTE_LINES]
    if len(lines) > MAX_NOTE_LINES:
        shown.append(f"... and {len(lines) - MAX_NOTE_LINES} more (see stdout)")
    text = "not plotted (invalid or failed):\n" + "\n".join(s if len(s) < 140 else s[:137] + "..." for s in shown)
    # The note gets room of its own below the axes: the figure grows by it, the axes keep their size.
    width, height = fig.get_size_inches()
    extra = 0.25 + 0.12 * (len(shown) + 1)
    sub = fig.subplotpars
    fig.set_size_inches(width, height + extra)
    fig.subplots_adjust(bottom=(sub.bottom * height + extra) / (height + extra),
                        top=(sub.top * height + extra) / (height + extra))
    fig.text(0.01, 0.01, text, fontsize=7, color="firebrick", va="bottom", family="monospace")


def plot_experiment(data):
    if not data.ok:
        fig, ax = plt.subplots(figsize=(8, 3))
        ax.axis("off")
        ax.text(0.5, 0.6, "no valid rows to plot", ha="center", fontsize=12)
        fig.suptitle(title_of(data), fontsize=10)
        return fig
    return PLOTTERS.get(data.experiment, generic_plot)(data)


def figure_name(experiment, run, ambiguous):
    return f"{experiment}-{run.label}" if ambiguous else experiment


def draw(run, experiment):
    """One experiment of one run as a figure, with the note of what was not plotted.
    Returns (ExperimentData, Figure, lines not plotted)."""
    data = ExperimentData(run, experiment)
    lines = invalid_lines(data)
    fig = plot_experiment(data)
    add_invalid_note(fig, lines)
    return data, fig, lines


def save(fig, stem, formats=("png", "svg")):
    """Writes `stem`.FORMAT for each format and closes the figure. The files depend only on the data:
    SVG ids come from a fixed salt and no date is written, so a rerun on the same CSV changes nothing."""
    written = []
    with plt.rc_context({"svg.hashsalt": "oitbench"}):
        for fmt in formats:
            path = f"{stem}.{fmt}"
            metadata = {"Date": None} if fmt in ("svg", "pdf") else None
            fig.savefig(path, dpi=120, bbox_inches="tight", metadata=metadata)
            written.append(path)
    plt.close(fig)
    return written


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("csv", nargs="+", help="summary CSVs written by `oitbench run --out`")
    ap.add_argument("-o", "--out-dir", help="where the figures go (default: figures/ beside the first CSV)")
    ap.add_argument("--raw", nargs="*", default=[], help="matching --raw files (make parameter columns exact)")
    ap.add_argument("--format", default="png,svg", help="comma-separated figure formats (default png,svg)")
    args = ap.parse_args(argv)
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)

    try:
        raws = args.raw + [None] * (len(args.csv) - len(args.raw))
        runs = [oitcsv.Run.load(p, r) for p, r in zip(args.csv, raws)]
    except oitcsv.ResultsError as e:
        print(f"plot.py: {e}", file=sys.stderr)
        return 2
    out_dir = args.out_dir or os.path.join(os.path.dirname(os.path.abspath(args.csv[0])), "figures")
    os.makedirs(out_dir, exist_ok=True)
    count = {}
    for run in runs:
        for exp in run.experiments():
            count[exp] = count.get(exp, 0) + 1
    formats = [f.strip() for f in args.format.split(",") if f.strip()]
    for run in runs:
        for exp in run.experiments():
            data, fig, lines = draw(run, exp)
            for line in lines:
                print(f"{run.label}: {exp}: not plotted: {line}")
            name = figure_name(exp, run, count[exp] > 1)
            save(fig, os.path.join(out_dir, name), formats)
            print(f"{run.label}: {exp}: {len(data.ok)} valid rows, {len(lines)} not plotted -> "
                  f"{os.path.join(out_dir, name)}.{{{args.format}}}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
