"""Figures from oitbench's summary CSVs: the library behind scripts/plot.py (and report.py,
findings.py).

Each experiment gets its own plot function from PLOTTERS; an experiment without one gets
generic_plot(): median ms against its main numeric parameter, one line per variant, MAD as error bars.
Adding a figure for a new experiment: write `def plot_<name>(data)` returning a Figure and decorate it
with @plotter("<name>"); curves() and bars() do most of the work.
"""
import math
import os
import re
import zlib

os.environ.setdefault("MPLBACKEND", "Agg")

import matplotlib

matplotlib.use(os.environ["MPLBACKEND"])
import matplotlib.pyplot as plt
import matplotlib.patches
from matplotlib.ticker import FuncFormatter, LogLocator, NullLocator

from oitbench import results as oitres
from oitbench import techniques

PLOTTERS = {}
MAX_NOTE_LINES = 8
MAX_LEGEND_INSIDE = 8  # more entries than this go beside the axes, where they cover no curve
MAX_CURVES = 8
MANY_CASES = 14  # a view with more cases than this gets its bars a full row, and labels only on its front  # a panel with more curves is split into parts, so every curve can be told apart
# The report shows a figure about 1060 px wide: figures are laid out for that width (10 in at 120 dpi,
# 1200 px) with a few panels per row and fonts that stay readable at that size; the SVG keeps the detail.
PAGE_WIDTH_IN = 10.0
PANEL_COLUMNS = 3
PANEL_HEIGHT_IN = 3.6
FLOOR = 1e-6  # exact techniques (error ~1e-8) sit on this floor of a log error axis
plt.rcParams.update({"font.size": 10, "axes.titlesize": 10, "axes.labelsize": 10, "xtick.labelsize": 9,
                     "ytick.labelsize": 9, "legend.fontsize": 8.5, "legend.title_fontsize": 8.5,
                     "figure.titlesize": 11})

# One colour per pass in every figure (tab20's pairs split so neighbours differ); a pass not named here
# gets one from its name's checksum, the same in every figure too.
PASS_ORDER = ["capture", "count", "mask", "insert", "resolve", "readback", "accumulate", "blend", "clear",
              "update", "moments", "alpha", "stochastic", "peel", "opaque", "shadow-map", "shadow-sort", "keys",
              "sort", "composite"]
_TAB20 = [matplotlib.colormaps["tab20"](i) for i in list(range(0, 20, 2)) + list(range(1, 20, 2))]

# Axis labels with their units, for the parameters that are axes; others get the schema's description.
AXIS_LABELS = {
    "n": "n (fragments per pixel)",
    "size": "SIZE (fragments in the array)",
    "coverage": "coverage (% of the screen's rows with fragments)",
    "segments": "line segments (count)",
    "nodes": "nodes per pixel",
    "layers": "layers per draw (count)",
    "max_frags": "MAX_FRAGS (fragments per pixel)",
    "shadow_slices": "shadow map depth slices (count)",
    "draws": "draws (count)",
    "slices": "slices (count)",
}
TIME_LABEL = "median time (ms, MAD bars)"


def pass_colour(name):
    if name in PASS_ORDER:
        return _TAB20[PASS_ORDER.index(name) % len(_TAB20)]
    return _TAB20[zlib.crc32(name.encode()) % len(_TAB20)]


def axis_label(param):
    if param in AXIS_LABELS:
        return AXIS_LABELS[param]
    spec = PARAM_SPECS.get(param)
    what = (spec or {}).get("description", "").split(";")[0].split(":")[0].split("(")[0].strip()
    unit = (spec or {}).get("unit", "")
    if what and len(what) <= 40:
        return f"{param} ({what}{', ' + unit if unit else ''})"
    return f"{param} ({unit})" if unit else param


PARAM_SPECS = {c["name"]: c for c in oitres.SCHEMA["summary_columns"] if c["role"] == "parameter"}


def plotter(experiment):
    def register(fn):
        PLOTTERS[experiment] = fn
        return fn
    return register


class ExperimentData:
    """What a plot function gets: the valid rows of one experiment from one run, and its columns.

    Every valid row is a copy carrying `_row` (its index) and `_drawn` (one set shared by the experiment's
    rows, copies of copies included): mark() records the rows a figure draws, skip() why others are not,
    and draw() names every valid row that was neither drawn nor explained, so nothing drops silently."""

    def __init__(self, run, experiment):
        self.run = run
        self.experiment = experiment
        rows = run.rows_of(experiment)
        self.drawn = set()
        valid = [dict(r, _row=i, _drawn=self.drawn) for i, r in enumerate(rows) if oitres.is_ok(r)]
        self.valid = valid
        self.ok = [r for r in valid if oitres.to_float(r.get("median_ms")) is not None]
        self.skipped = {}  # reason -> rows
        self.skip([r for r in valid if oitres.to_float(r.get("median_ms")) is None], "valid but no median_ms")
        self.invalid = [r for r in rows if not oitres.is_ok(r)]
        self.params = [p for p in run.params(experiment) if p not in oitres.FRAMEWORK_PARAMS]
        self.metrics = run.metrics(experiment)
        self.passes = sorted({r["pass"] for r in self.ok}, key=lambda p: (p == "total", p))

    def skip(self, rows, reason):
        if rows:
            self.skipped.setdefault(reason, []).extend(rows)

    def total_rows(self):
        """The `total` row of every case (a case without named passes has only that one)."""
        return [r for r in self.ok if r["pass"] == "total"]

    def varying_params(self, rows=None):
        return oitres.varying(rows if rows is not None else self.ok, self.params)

    def first_param(self, candidates, numeric=False, rows=None):
        """The first of `candidates` that this experiment has and varies (numeric when asked)."""
        rows = rows if rows is not None else self.ok
        for c in candidates:
            if c in self.params and c in self.varying_params(rows):
                if not numeric or oitres.numeric_column(rows, c):
                    return c
        return None

    def main_numeric_param(self, rows=None, exclude=()):
        """The numeric parameter with the most distinct values: the natural x axis."""
        rows = rows if rows is not None else self.ok
        best, best_n = None, 1
        for p in self.varying_params(rows):
            if p in exclude or not oitres.numeric_column(rows, p):
                continue
            n = len({r[p] for r in rows})
            if n > best_n:
                best, best_n = p, n
        return best

    def counts(self):
        """(valid rows drawn, valid rows named in the note as not drawn)."""
        noted = sum(len(rows) for _, rows in self.not_drawn())
        return len(self.valid) - noted, noted

    def not_drawn(self):
        """(reason, rows) for every valid row no panel drew: the reasons plotters gave, else a general one."""
        out, explained = [], set()
        for reason, rows in self.skipped.items():
            rows = [r for r in rows if r["_row"] not in self.drawn and r["_row"] not in explained]
            explained |= {r["_row"] for r in rows}
            if rows:
                out.append((reason, rows))
        rest = [r for r in self.valid if r["_row"] not in self.drawn and r["_row"] not in explained]
        if rest:
            out.append(("no panel of this figure shows it", rest))
        return out


def mark(rows):
    """Records `rows` as drawn (in the set their ExperimentData shares with them)."""
    for r in rows:
        if "_drawn" in r:
            r["_drawn"].add(r["_row"])


def value(row, column="median_ms"):
    return oitres.to_float(row.get(column))


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
    return dict(sorted(groups.items(), key=lambda kv: [oitres.sort_key(v) for v in kv[0]]))


def case_id(row, params):
    """What makes a row's case: variant, resolution and every parameter (not the pass)."""
    return (row.get("variant", ""), row.get("width", ""), row.get("height", "")) + tuple(row.get(p, "") for p in params)


def case_labels(rows, params, base, skip=()):
    """{case_id: label}: base(row), plus name=value for each parameter that tells apart cases the label
    so far leaves alike (capture=PPPA beside PPLL, max_frags=32 beside 64, ...): bars and points are keyed
    on everything that varies, never on the technique alone. A label still shared gets #2, #3."""
    params = [p for p in params if p not in skip]
    cases = {}
    for r in rows:
        cases.setdefault(case_id(r, params), r)
    labels = {cid: base(r) for cid, r in cases.items()}
    for p in params:
        by_label = {}
        for cid, r in cases.items():
            by_label.setdefault(labels[cid], set()).add(r.get(p, ""))
        for cid, r in cases.items():
            if len(by_label[labels[cid]]) > 1 and r.get(p, "") != "":
                labels[cid] += f" {p}={r[p]}"
    seen = {}
    for cid in sorted(labels, key=lambda c: [oitres.sort_key(str(v)) for v in c]):
        n = seen[labels[cid]] = seen.get(labels[cid], 0) + 1
        if n > 1:
            labels[cid] += f" #{n}"
    return labels


def panel_grid(n, ncols=None, height=PANEL_HEIGHT_IN, width=PAGE_WIDTH_IN, sharey=False):
    """n panels wrapped into rows of `ncols` (at most PANEL_COLUMNS): (figure, list of n axes)."""
    ncols = max(1, min(n, ncols or PANEL_COLUMNS))
    nrows = max(1, math.ceil(n / ncols))
    fig, axes = plt.subplots(nrows, ncols, figsize=(width, height * nrows + 0.9), squeeze=False, sharey=sharey)
    flat = [ax for row in axes for ax in row]
    for ax in flat[n:]:
        ax.axis("off")
    return fig, flat[:n]


def rows_grid(counts, height=PANEL_HEIGHT_IN, width=PAGE_WIDTH_IN):
    """Rows of panels, counts[i] in row i, each row filling the width: (figure, axes in order)."""
    ncols = math.lcm(*[max(c, 1) for c in counts])
    fig = plt.figure(figsize=(width, height * len(counts) + 0.9))
    gs = fig.add_gridspec(len(counts), ncols)
    axes = []
    for i, c in enumerate(counts):
        span = ncols // max(c, 1)
        axes += [fig.add_subplot(gs[i, k * span:(k + 1) * span]) for k in range(c)]
    return fig, axes


def finish(fig, data, what=None, legend_from=None):
    """The two-line title above the panels, the legend of the axes `legend_from` under it for the whole
    figure, and tight spacing between the panels."""
    height = fig.get_size_inches()[1]
    fig.suptitle(title_of(data, what), y=1.0 - 0.08 / height, va="top")
    top = 1.0 - 0.55 / height
    if legend_from:
        handles, labels = [], []
        for ax in legend_from:  # one entry per label over all the panels given
            for h, lab in zip(*ax.get_legend_handles_labels()):
                if lab not in labels:
                    handles.append(h)
                    labels.append(lab)
        order = sorted(range(len(labels)), key=lambda i: (labels[i] != "total (measured)", PASS_ORDER.index(
            labels[i]) if labels[i] in PASS_ORDER else 99, labels[i]))
        handles, labels = [handles[i] for i in order], [labels[i] for i in order]
        if handles:
            lines = math.ceil(len(labels) / 8)
            fig.legend(handles, labels, loc="upper center", bbox_to_anchor=(0.5, top),
                       ncol=math.ceil(len(labels) / lines), frameon=False)
            top -= 0.28 * lines / height
    fig.tight_layout(rect=(0, 0, 1, top), h_pad=1.2, w_pad=1.0)
    return fig


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


def draw_lines(ax, rows, x, label_columns, per=1.0, per_column=None, column="median_ms", mad_column="mad_ms",
               shown=None, styles=None):
    """One line per group of `label_columns`, y = column / per (or / row[per_column]), MAD bars; with
    `shown`, the legend gives those columns' values alone (its title names them). `styles` (a list of
    every group key of the figure) gives a group the same colour and line style in every panel."""
    xs_all, ys_all = [], []
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    n_colors = len(colors)
    for i, (key, grp) in enumerate(group_rows(rows, label_columns).items()):
        i = styles.index(key) if styles and key in styles else i
        pts, used = [], []
        for r in grp:
            xv, y = oitres.to_float(r.get(x)), value(r, column)
            mad = (value(r, mad_column) or 0.0) if mad_column else 0.0
            div = (oitres.to_float(r.get(per_column)) if per_column else per) or 1.0
            if xv is not None and y is not None:
                pts.append((xv, y / div, mad / div))
                used.append(r)
        pts.sort()
        if not pts:
            continue
        xs, ys, es = zip(*pts)
        # Past the colour cycle the line style changes, so two curves never look the same.
        ax.errorbar(xs, ys, yerr=es if mad_column else None, marker="o", markersize=4, capsize=3, linewidth=1.5,
                    color=colors[i % n_colors], linestyle=("-", "--", ":", "-.")[(i // n_colors) % 4],
                    label=(", ".join(str(grp[0].get(c, "")) for c in shown) if shown is not None
                           else group_label(grp[0], label_columns)) or None)
        mark(used)
        xs_all += xs
        ys_all += ys
    return xs_all, ys_all


def scale_axes(ax, xs, ys, logy=None):
    if xs and min(xs) > 0 and max(xs) / min(xs) >= 8:
        # Sizes and counts (n, SIZE, nodes) read best on powers of two; millions of segments do not.
        if max(xs) <= 4096:
            log2_ticks(ax, xs)
        else:
            ax.set_xscale("log")
    if logy or (logy is None and spread_is_wide(ys)):
        ax.set_yscale("log")


def sort_family(variant):
    """Sorts grouped by name: insertion-*, bubble*, shell*, the merge networks (bitonic, *merge*), rbs...;
    a new sort joins its family by its name, or gets its first word as one."""
    v = (variant or "").lower()
    for pattern, family in ((r"merge|bitonic", "merge networks"), (r"^insertion", "insertion"),
                            (r"^bubble", "bubble"), (r"^shell", "shell")):
        if re.search(pattern, v):
            return family
    return re.split(r"[-_ ]", v)[0] or "other"


def chunks(items, size):
    """`items` in the fewest parts of at most `size`, the parts as even as can be."""
    n = max(1, math.ceil(len(items) / size))
    step = math.ceil(len(items) / n) if items else 1
    return [items[i:i + step] for i in range(0, len(items), step)] or [[]]


def curves(data, x_candidates=(), facet_candidates=(), ylabel=TIME_LABEL, what=None, logy=None, family=None):
    """Median vs x, one line per variant (and per other varying parameter), one panel per facet value,
    per named pass (total first) and per `family` of variants; a panel with more than MAX_CURVES curves
    is split into parts. The panels wrap into rows of PANEL_COLUMNS. An error column that is not zero
    everywhere gets panels of its own (error against x)."""
    rows = data.ok
    totals = data.total_rows()
    x = data.first_param(x_candidates, numeric=True, rows=totals) or data.main_numeric_param(totals)
    if x is None:
        return bars(data, what=what)
    facet = data.first_param([f for f in facet_candidates if f != x], rows=totals)
    others = [p for p in data.varying_params(totals) if p not in (x, facet)]
    label_columns = (["variant"] if len({r.get("variant", "") for r in rows}) > 1 else []) + others
    passes = sorted({r["pass"] for r in rows}, key=lambda p: (p != "total", PASS_ORDER.index(p)
                                                              if p in PASS_ORDER else 99, p))
    panels = []  # (title, rows)
    for fkey, frows in (group_rows(rows, [facet]) if facet else {(): rows}).items():
        for p in passes:
            prow = [r for r in frows if r["pass"] == p]
            fams = {}
            for r in prow:
                fams.setdefault(family(r.get("variant", "")) if family else "", []).append(r)
            for fam in sorted(fams):
                groups = list(group_rows(fams[fam], label_columns).items())
                parts = chunks(groups, MAX_CURVES)
                for k, part in enumerate(parts):
                    title = ", ".join(t for t in (f"{facet} = {fkey[0]}" if facet else "",
                                                  f"pass {p}" if len(passes) > 1 else "",
                                                  fam, f"part {k + 1}/{len(parts)}" if len(parts) > 1 else "") if t)
                    panels.append((title, [r for _, g in part for r in g], ylabel))
    error_col = next((c for c in ERROR_COLUMNS if any((value(r, c) or 0) > 0 for r in totals)), None)
    if error_col:
        for fkey, frows in (group_rows(totals, [facet]) if facet else {(): totals}).items():
            title = f"{error_col} against exact" + (f", {facet} = {fkey[0]}" if facet else "")
            panels.append((title, [r for r in frows if value(r, error_col) is not None], error_col))
    styles = list(group_rows(rows, label_columns).keys())
    entries = max(len(group_rows(prows, label_columns)) for _, prows, _ in panels)
    lines = entries if entries <= 4 else math.ceil(entries / 2)
    fig, axes = panel_grid(len(panels), ncols=2 if label_columns else PANEL_COLUMNS,
                           height=PANEL_HEIGHT_IN + (0.75 + 0.2 * lines if label_columns else 0))
    for ax, (title, prows, what_y) in zip(axes, panels):
        # The legend names what varies in this panel; the rest is in its title or the same for all.
        shown = [c for c in label_columns if len({r.get(c, "") for r in prows}) > 1] or label_columns[:1]
        if what_y in ERROR_COLUMNS:
            xs, ys = draw_lines(ax, prows, x, label_columns, column=what_y, mad_column=None, shown=shown,
                                styles=styles)
            ax.set_ylabel(f"{what_y} (colour units, 0 to 1)")
        else:
            xs, ys = draw_lines(ax, prows, x, label_columns, shown=shown, styles=styles)
            ax.set_ylabel(what_y)
        scale_axes(ax, xs, ys, logy)
        ax.set_xlabel(axis_label(x))
        ax.grid(True, which="both", alpha=0.3)
        if title:
            ax.set_title(title)
        if label_columns:
            ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.2), title=" \u00d7 ".join(shown),
                      ncol=2 if len(ax.get_legend_handles_labels()[1]) > 4 else 1, fontsize=8)
    return finish(fig, data, what)


def bars(data, category_candidates=(), what=None, ylabel=TIME_LABEL):
    """Grouped bars: one group per variant (or the first of `category_candidates`), one bar per
    combination of the other varying parameters, MAD as error bars; one panel per named pass (total
    first)."""
    rows = data.ok
    totals = data.total_rows()
    category = data.first_param(category_candidates, rows=totals) or "variant"
    others = [c for c in (["variant"] + data.varying_params(totals)) if c != category and
              (c != "variant" or len({r["variant"] for r in rows}) > 1)]
    categories = list(group_rows(totals or rows, [category]).keys())
    passes = sorted({r["pass"] for r in rows}, key=lambda p: (p != "total", p))
    fig, axes = panel_grid(len(passes), ncols=min(len(passes), 2 if len(categories) > 3 else 3))
    for ax, p in zip(axes, passes):
        prow = [r for r in rows if r["pass"] == p]
        series = group_rows(prow, others) if others else {(): prow}
        width = 0.8 / max(1, len(series))
        for i, (skey, srows) in enumerate(series.items()):
            by_cat = {}
            for r in srows:
                by_cat.setdefault(r.get(category, ""), r)
            xs, ys, es = [], [], []
            for j, ckey in enumerate(categories):
                r = by_cat.get(ckey[0])
                if r is not None:
                    xs.append(j + (i - (len(series) - 1) / 2) * width)
                    ys.append(value(r))
                    es.append(value(r, "mad_ms") or 0.0)
                    mark([r])
            ax.bar(xs, ys, width=width, yerr=es, capsize=3,
                   label=group_label(srows[0], others) if others else None)
        ax.set_xticks(range(len(categories)))
        # Slanted when the names would run into each other.
        slant = len(categories) > 3 or sum(len(str(c[0])) for c in categories) > 24
        ax.set_xticklabels([c[0] for c in categories], rotation=25 if slant else 0,
                           ha="right" if slant else "center")
        ax.set_xlabel(axis_label(category) if category != "variant" else "variant")
        ax.set_ylabel(ylabel)
        ax.grid(True, axis="y", alpha=0.3)
        if len(passes) > 1:
            ax.set_title(f"pass {p}")
        if others:
            legend(ax, title=" \u00d7 ".join(others))
    return finish(fig, data, what)


def legend(ax, title=None):
    """Inside the axes where it fits; a long one to the right of them (savefig's tight box keeps it)."""
    n = len(ax.get_legend_handles_labels()[1])
    if not n:
        return
    if n > MAX_LEGEND_INSIDE:
        ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0, handlelength=3.5, title=title)
    else:
        ax.legend(loc="best", title=title)


def generic_plot(data):
    rows = data.total_rows()
    if data.main_numeric_param(rows):
        return curves(data)
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

    occ = [(oitres.to_float(r.get("size")), oitres.to_float(r.get("predicted_occupancy")))
           for r in rows if oitres.to_float(r.get("predicted_occupancy")) is not None]
    # Measured where the driver could (GL_NV_shader_thread_group): one marker per variant and size.
    measured = sorted({(r.get("variant", ""), oitres.to_float(r.get("size")),
                        oitres.to_float(r.get("measured_occupancy")))
                       for r in rows if oitres.to_float(r.get("measured_occupancy")) is not None})
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
        by_size = {oitres.to_float(r["size"]): r for r in grp}
        if 32 in by_size and 33 in by_size:
            t32 = value(by_size[32]) / (oitres.to_float(by_size[32].get("draws")) or 1)
            t33 = value(by_size[33]) / (oitres.to_float(by_size[33].get("draws")) or 1)
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
                  what="per-pixel sorts against n, one panel per family", family=sort_family)


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


OIT_APPROX = set(techniques.names("approximate"))
OIT_PEEL = set(techniques.names("peel"))


def oit_label(row):
    """The technique as the papers name it, with the node count where it matters (approximate ones)."""
    t = name = row.get("technique") or row.get("variant") or "?"
    # The parameter that sizes the technique, by what the technique table says it reads.
    if techniques.reads(name, "nodes") and row.get("nodes"):
        t += f"/{row['nodes']}"
    if techniques.reads(name, "wboit_weight") and row.get("wboit_weight"):
        t += f"/{row['wboit_weight']}"
    if techniques.reads(name, "window") and row.get("window"):  # WINDOW-SORT/16: a window of 16 fragments
        t += f"/{row['window']}"
    if techniques.reads(name, "ht_variant") and row.get("ht_variant") not in (None, "", "maule"):  # HT/16/htgs
        t += f"/{row['ht_variant']}"
    if name in OIT_PEEL and row.get("max_layers") not in (None, "", "0"):
        t += f"/{row['max_layers']}"
    if techniques.reads(name, "moments") and row.get("moments"):  # /6p: 6 power moments; /3t trigonometric; /16 bits
        t += f"/{row['moments']}{'t' if row.get('moment_kind') == 'trigonometric' else 'p'}"
        if row.get("moment_bits") == "16":
            t += "/16"
    if techniques.reads(name, "wavelet_coeffs") and row.get("wavelet_coeffs"):  # /16: 16 coefficients; /16 bits
        t += f"/{row['wavelet_coeffs']}"
        if row.get("wavelet_bits") == "16":
            t += "/16"
        if row.get("wavelet_basis") not in (None, "", "haar"):  # /cosine: the smooth comparison basis
            t += f"/{row['wavelet_basis']}"
    if techniques.reads(name, "slab_layers") and row.get("slab_layers"):  # /4x8: 4 layers of 8-sample masks
        t += f"/{row['slab_layers']}x{row.get('samples_per_pixel') or '?'}"
    elif techniques.reads(name, "samples_per_pixel") and row.get("samples_per_pixel"):
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
            label += f" {oitres.to_float(row['total_fragments']):,.0f} frags"
    return label


def has_formats(rows):
    """True when the rows vary the fragment format (the precision preset)."""
    return any(r.get("frag_colour") not in (None, "", "rgba8") or r.get("frag_depth") not in (None, "", "window")
               for r in rows)


def format_cost(ax, rows, title):
    """What precision costs: each case a point at its time and its error against the truth (the geometric
    reference's truth_rmse where the scene is analytic, else rmse against the captured fragments), the
    point's area and label giving its fragment storage (node_pool_bytes)."""
    column = "truth_rmse" if any(oitres.to_float(r.get("truth_rmse")) is not None for r in rows) else "rmse"
    floor = 1e-9
    colors = {"rgba8": "tab:blue", "rgba16f": "tab:orange", "rgba32f": "tab:green"}
    for r in rows:
        t, e = value(r), oitres.to_float(r.get(column))
        if t is None or e is None:
            continue
        mib = (oitres.to_float(r.get("node_pool_bytes")) or 0.0) / 2**20
        ax.scatter(t, max(e, floor), s=20 + 30 * mib ** 0.5, color=colors.get(r.get("frag_colour"), "tab:gray"),
                   marker="o" if r.get("frag_depth") != "view" else "s", alpha=0.8, zorder=3)
        ax.annotate(f"{oit_label(r)} {mib:.2f} MiB", (t, max(e, floor)), fontsize=7, xytext=(3, 2),
                    textcoords="offset points")
        mark([r])
    for name, c in colors.items():
        ax.scatter([], [], color=c, label=name)
    ax.scatter([], [], color="black", marker="o", label="window depth")
    ax.scatter([], [], color="black", marker="s", label="view depth")
    ax.legend(fontsize=7, loc="upper right")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("total median time (ms); area: fragment storage")
    ax.set_ylabel(f"{column} (colour units 0..1, floor {floor:g})")
    ax.grid(True, which="both", alpha=0.3)
    ax.set_title(f"fragment format: time, memory, error:\n{title}")


EFFECT_INITIALS = {"opaque": "O", "transparency": "T", "self-shadowing": "S"}


def effects_short(effects):
    """opaque+transparency -> O+T (the legend spells them out)."""
    return "+".join(EFFECT_INITIALS.get(e, e) for e in (effects or "").split("+") if e)


def fmt_count(v):
    v = oitres.to_float(v)
    if v is None:
        return ""
    return f"{v / 1e6:.1f}M" if v >= 1e6 else f"{v / 1e3:.0f}k" if v >= 1e4 else f"{v:.0f}"


def effects_panel(ax, rows, passes, title, legend, label_of=oit_label):
    """Per technique one bar per effect set, side by side: the case's passes stacked (effect passes and the
    technique's alike), the fragments it captured above the bar: what each effect costs and saves."""
    totals = [r for r in rows if r["pass"] == "total"]
    techniques = sorted({label_of(r) for r in totals})
    sets = sorted({r.get("effects", "") for r in totals}, key=lambda e: (len(e.split("+")), e))
    width = 0.8 / max(len(sets), 1)
    drawn = set()
    ticks, labels = [], []
    for ti, t in enumerate(techniques):
        for si, e in enumerate(sets):
            case = [r for r in rows if label_of(r) == t and r.get("effects", "") == e]
            total = next((r for r in case if r["pass"] == "total"), None)
            if total is None:
                continue
            mark(case)
            x = ti + (si - (len(sets) - 1) / 2) * width
            own = {r["pass"]: value(r) for r in case if r["pass"] != "total"}
            if not own:  # a single-pass case writes only its total
                own = {"(single pass)": value(total)}
            bottom = 0.0
            for p in passes + ["(single pass)"]:
                if p not in own:
                    continue
                ax.bar(x, own[p], width * 0.92, bottom=bottom, color=pass_colour(p),
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
    ax.set_xticklabels(labels, fontsize=7)
    for ti, t in enumerate(techniques):
        ax.annotate(t, (ti, 0), xycoords=("data", "axes fraction"), xytext=(0, -26), textcoords="offset points",
                    ha="center", fontsize=8.5)
    ax.set_ylim(0, ax.get_ylim()[1] * 1.6)  # room for the legend above the bars
    ax.set_ylabel("median time (ms)")
    ax.grid(True, axis="y", alpha=0.3)
    ax.set_title(title + "\n(above each bar: fragments captured)")
    if legend:
        ax.legend(fontsize=7, loc="upper center", ncol=4, title=", ".join(f"{v}={k}" for k, v in EFFECT_INITIALS.items()),
                  title_fontsize=7)


@plotter("oit")
def plot_oit(data):
    """Per (scene, view, resolution): stacked pass times per case; where any technique is approximate
    (an error above the floor), the error against the exact reference against total time, every case a
    point sized by its memory (bytes_per_pixel), with the Pareto front (nothing both faster and more
    exact) marked, and the error against memory with its own front: pick by error, time and memory at
    once. Exact-only groups draw the bars alone, three views to a row; otherwise each view is a row."""
    totals = data.total_rows()
    key_cols = [c for c in ("scene", "view", "width") if any(r.get(c) for r in totals)]
    groups = group_rows(totals, key_cols)
    error_col = next((c for c in ERROR_COLUMNS if any(value(r, c) is not None for r in totals)), None)
    formats = has_formats(totals)
    panels = []  # (kind, group rows, title)
    for gkey, grows in groups.items():
        title = ", ".join(f"{c}={grows[0].get(c)}" for c in key_cols)
        # Splat scenes: the error against the analytic reference (truth_rmse), which the global sort reports too.
        gcol = "truth_rmse" if any(value(r, "truth_rmse") is not None and r.get("splat_depth") for r in grows) \
            else error_col
        approx = gcol is not None and any((value(r, gcol) or 0) > FLOOR for r in grows)
        memory = approx and any(value(r, "bytes_per_pixel") is not None for r in grows)
        # Splat scenes with a camera path: popping against time and against the error (docs/splats.md#popping).
        popping = gcol == "truth_rmse" and any(value(r, "popping") is not None for r in grows)
        kinds = ["passes"] + (["error-time"] if approx else []) + (["error-memory"] if memory else []) + \
            (["format"] if formats else []) + (["popping-time", "popping-error"] if popping else [])
        panels.append([(k, grows, title, gcol) for k in kinds])
    flat = [p for group in panels for p in group]
    wide = any(len({case_id(r, data.params) for r in g[0][1]}) > MANY_CASES or effects_vary(g[0][1])
               for g in panels)
    if all(len(g) == 1 for g in panels):
        fig, axes = panel_grid(len(flat), ncols=1 if wide else PANEL_COLUMNS, height=3.9)
    else:
        # One view per row, its panels side by side; a view with many cases gets its bars a row of their own.
        rows = []
        for group in panels:
            main = [p for p in group if not p[0].startswith("popping")]
            pops = [p for p in group if p[0].startswith("popping")]  # a row of their own, after the view's
            rows += ([main[:1], main[1:]] if wide else [main]) + ([pops] if pops else [])
        fig, axes = rows_grid([len(r) for r in rows], height=4.2)
    params = [p for p in data.params if p not in key_cols]
    legend_from = []
    for i, (ax, (kind, grows, title, gcol)) in enumerate(zip(axes, flat)):
        labels = case_labels(grows, params, oit_label)
        same = [r for r in data.ok if all(r.get(c) == grows[0].get(c) for c in key_cols)]
        if kind == "passes":
            if effects_vary(same):
                own = [p for p in params if p != "effects"]
                by_case = case_labels(grows, own, oit_label)
                effects_panel(ax, same, [p for p in data.passes if p != "total"], title, legend=(i == 0),
                              label_of=lambda r, own=own, by_case=by_case: by_case.get(case_id(r, own), oit_label(r)))
            else:
                stacked_passes(ax, same, grows, params, labels, title, legend=False)
                legend_from.append(ax)
        elif kind == "error-time":
            error_vs_time(ax, grows, gcol, title, params, labels)
        elif kind == "error-memory":
            error_vs_memory(ax, grows, gcol, title, params, labels)
        elif kind == "popping-time":
            error_vs_time(ax, grows, "popping", title, params, labels)
        elif kind == "popping-error":
            popping_vs_error(ax, grows, gcol, title, params, labels)
        else:
            format_cost(ax, grows, title)
    exact_only = all(len(g) == 1 for g in panels) and error_col is not None
    return finish(fig, data, "pass times per case" + (" (every technique exact: no error panels)" if exact_only
                                                      else ", error against time and memory"), legend_from)


def marker_area(bytes_per_pixel, largest):
    """Marker area in points^2 proportional to memory (12 to 200), 28 where a row has no bytes_per_pixel."""
    if bytes_per_pixel is None or not largest:
        return 28
    return 12 + 188 * bytes_per_pixel / largest


def error_points(rows, column, params, labels, x_column=None):
    """(x, error, label, bytes per pixel, row) for each case with both; x the total median ms, or
    `x_column`. Errors below FLOOR are drawn on it."""
    with_effects = effects_vary(rows)
    out = []
    for r in rows:
        e = value(r, column)
        x = value(r) if x_column is None else value(r, x_column)
        if e is None or x is None:
            continue
        label = labels.get(case_id(r, params), oit_label(r))
        if with_effects and "effects=" not in label:
            label += f" [{r.get('effects')}]"
        out.append((x, max(e, FLOOR), label, value(r, "bytes_per_pixel"), r))
    return out


def family_of(label):
    return label.split("/")[0].split(" ")[0]


def scatter_front(ax, points, x_label, column, title, sized):
    """Every case a point coloured by technique family (its area its bytes per pixel when `sized`), with
    the front of the cases nothing beats in both x and error. Up to MANY_CASES points each carry their
    label; more, and only the front's do (the families are in the legend, every case in the bars)."""
    families = sorted({family_of(p[2]) for p in points})
    colours = [matplotlib.colormaps["tab20"](i) for i in range(0, 20, 2)] + \
        [matplotlib.colormaps["tab20"](i) for i in range(1, 20, 2)]
    largest = max((p[3] for p in points if p[3] is not None), default=None) if sized else None
    front = pareto_front([(x, e, label) for x, e, label, _, _ in points])
    on_front = {p[2] for p in front}
    floor = []
    for x, e, label, mem, r in points:
        ax.scatter(x, e, color=colours[families.index(family_of(label)) % len(colours)],
                   s=marker_area(mem, largest) if sized else 28, alpha=0.8, zorder=3)
        if e <= FLOOR and label not in on_front:
            floor.append(label)  # the exact ones share the floor: named together, not on top of each other
        elif len(points) <= MANY_CASES or label in on_front:
            ax.annotate(label, (x, e), fontsize=7.5, xytext=(3, 2), textcoords="offset points",
                        color="tab:red" if label in on_front else "black")
    if floor and len(points) <= MANY_CASES:
        ax.text(0.98, 0.08, "on the floor (exact):\n" + "\n".join(floor), transform=ax.transAxes, ha="right",
                va="bottom", fontsize=7, bbox=dict(boxstyle="round", fc="white", ec="0.8", alpha=0.9), zorder=5)
    mark([p[4] for p in points])
    handles = []
    if front:
        handles.append(ax.step([p[0] for p in front], [p[1] for p in front], where="post", color="tab:red",
                               linewidth=1.0, linestyle="--", label="Pareto front (labelled)")[0])
        ax.scatter([p[0] for p in front], [p[1] for p in front], facecolors="none", edgecolors="tab:red", s=90,
                   zorder=4)
    if len(points) > MANY_CASES:
        handles += [plt.Line2D([], [], color=colours[i % len(colours)], marker="o", linestyle="", label=f)
                    for i, f in enumerate(families)]
        ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0, fontsize=7.5)
    # Fewer points: each is labelled, the front's in red (the title says so): no legend to cover them.
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(x_label)
    ax.set_ylabel(f"{column} against exact\n(colour units 0..1, floor {FLOOR:g})")
    ax.grid(True, which="both", alpha=0.3)
    ax.set_title(title)
    return largest


def error_vs_time(ax, rows, column, title, params, labels):
    points = error_points(rows, column, params, labels)
    largest = scatter_front(ax, points, "total median time (ms)", column, "", sized=True)
    note = f"\n(marker area: bytes/pixel, largest {largest:g})" if largest else ""
    ax.set_title((f"{column} against time" if len(title) > 30 else f"{column} against time: {title}") +
                 f" (red: Pareto front){note}")


def error_vs_memory(ax, rows, column, title, params, labels):
    """Error against bytes_per_pixel, every case a point, with the front of nothing both smaller and
    more exact."""
    points = [(max(p[0], 1.0),) + p[1:] for p in error_points(rows, column, params, labels, "bytes_per_pixel")]
    scatter_front(ax, points, "bytes per pixel (storage; 0 drawn at 1)", column,
                  (f"{column} against memory" if len(title) > 30 else f"{column} against memory: {title}") +
                  " (red: Pareto front)", sized=False)


def popping_vs_error(ax, rows, column, title, params, labels):
    """Splat scenes: popping over the camera path against the error of the case's own view (`column`,
    truth_rmse), with the front of nothing both steadier and more exact: the global sort's error and its
    popping are two faces of one order."""
    points = [(max(p[0], FLOOR),) + p[1:] for p in error_points(rows, "popping", params, labels, column)]
    largest = scatter_front(ax, points, f"{column} against the analytic reference (floor {FLOOR:g})", "popping", "",
                            sized=True)
    note = f"\n(marker area: bytes/pixel, largest {largest:g})" if largest else ""
    ax.set_title(("popping against error" if len(title) > 30 else f"popping against error: {title}") +
                 f" (red: Pareto front){note}")


def stacked_passes(ax, rows, totals, params, labels, title, legend=True):
    """One bar per case (labelled on every parameter that tells cases apart): its named passes stacked,
    each pass in its own colour (the same in every figure), the measured total as a black tick. A case
    measured more than once in the file (a baseline run in every interleaving group of the cases it is
    the baseline of) is one bar at the median of its rows, its label saying how many."""
    cases = sorted({case_id(r, params) for r in totals}, key=lambda c: labels[c])
    total_of = {}
    for r in totals:
        total_of.setdefault(case_id(r, params), []).append(r)
    passes = [p for p in sorted({r["pass"] for r in rows}, key=lambda p: (
        PASS_ORDER.index(p) if p in PASS_ORDER else 99, p)) if p != "total"]
    cell = {}
    for r in rows:
        cid = case_id(r, params)
        if cid in total_of and r.get("width") == total_of[cid][0].get("width") and r["pass"] != "total":
            cell.setdefault((cid, r["pass"]), []).append(r)

    def median_of(rs):
        vs = sorted(v for v in (value(r) for r in rs) if v is not None)
        if not vs:
            return 0.0
        mid = len(vs) // 2
        return vs[mid] if len(vs) % 2 else 0.5 * (vs[mid - 1] + vs[mid])

    bottom = [0.0] * len(cases)
    for p in passes:
        ys = []
        for cid in cases:
            rs = cell.get((cid, p), [])
            ys.append(median_of(rs))
            mark(rs)
        ax.bar(range(len(cases)), ys, bottom=bottom, label=p, color=pass_colour(p))
        bottom = [b + y for b, y in zip(bottom, ys)]
    tot = [median_of(total_of[c]) for c in cases]
    for rs in total_of.values():
        mark(rs)
    ax.scatter(range(len(cases)), tot, marker="_", s=300, color="black", zorder=3, label="total (measured)")
    ax.set_xlim(-0.6, len(cases) - 0.4)
    ax.set_xticks(range(len(cases)))
    ax.set_xticklabels([labels[c] + (f" (x{len(total_of[c])}, median)" if len(total_of[c]) > 1 else "")
                        for c in cases], rotation=40, ha="right", fontsize=8)
    ax.set_ylabel("median time (ms)")
    ax.grid(True, axis="y", alpha=0.3)
    ax.set_title(title)
    if legend:
        ax.legend(loc="upper left", fontsize=7.5, ncol=2, title="pass")


def pareto_front(points):
    """Points (time, error, ...) that no other point beats in both time and error, by time."""
    front = []
    for p in sorted(points, key=lambda q: (q[0], q[1])):
        if not front or p[1] < front[-1][1]:
            front.append(p)
    return front


def metric_short(metric):
    """'total_speedup_vs_BASE-IS' -> 'total'; 'average_resolve_speedup_vs_BASE-IS' -> 'average resolve'."""
    m = re.sub(r"_speedup_vs_.*$|_vs_.*$", "", metric)
    m = re.sub(r"_time$|_ms$", "", m)
    return m.replace("_", " ") or metric


def speedup_ticks(ax):
    """Labelled ticks on a log speedup axis whatever its range: 1x, 2x, 5x, 10x over decades, finer
    steps (1.1x, 1.2x, 1.5x, ...) when the axis spans less than one."""
    lo, hi = ax.get_ylim()
    span = hi / max(lo, 1e-9)
    subs = (1.0, 1.1, 1.2, 1.3, 1.5, 1.7, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0) if span < 3 else \
        (1.0, 1.5, 2.0, 3.0, 5.0, 7.0) if span < 12 else (1.0, 2.0, 5.0)
    ax.yaxis.set_major_locator(LogLocator(base=10, subs=subs))
    ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:.3g}x"))
    ax.yaxis.set_minor_locator(NullLocator())


def paper_figure(title, pairs, paper_hw, ours_hw):
    """Ours against the paper: per case (scene, view, size) and technique, the paper's speedup over the
    table's baseline beside ours over the same baseline (pairs: tables.figure_pairs()), one panel per
    technique (or one panel of techniques where the table has no cases), log axis with 1x marked."""
    cases = list(dict.fromkeys(c for c, _, _, _, _ in pairs))
    techniques = list(dict.fromkeys(t for _, t, _, _, _ in pairs))
    metrics = list(dict.fromkeys(m for _, _, m, _, _ in pairs))
    by_technique = len(cases) > 1
    panels = techniques if by_technique else [""]
    xs_of = cases if by_technique else techniques
    wide = len(xs_of) * len(metrics) > 24
    fig, axes = panel_grid(len(panels), ncols=1 if wide else 2, height=3.2)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    value_of = {(c, t, m): (p, o) for c, t, m, p, o in pairs}
    width = 0.8 / (2 * len(metrics))
    for ax, tech in zip(axes, panels):
        for mi, m in enumerate(metrics):
            for si, side in enumerate(("paper", "ours")):
                xs, ys = [], []
                for j, x in enumerate(xs_of):
                    v = value_of.get((x, tech, m) if by_technique else (cases[0], x, m))
                    if v is not None:
                        xs.append(j + (2 * mi + si - (2 * len(metrics) - 1) / 2) * width)
                        ys.append(v[si])
                # From 1x up or down: a slowdown reads as a bar below the line.
                ax.bar(xs, [y - 1.0 for y in ys], bottom=1.0, width=width, color=colours[mi % len(colours)],
                       alpha=0.45 if side == "paper" else 1.0,
                       hatch="//" if side == "paper" else None, edgecolor="white" if side == "ours" else "black",
                       linewidth=0.4, label=f"{side}: {metric_short(m)}")
        ax.axhline(1.0, color="black", linewidth=0.8)
        ax.set_yscale("log")
        speedup_ticks(ax)
        ax.set_xticks(range(len(xs_of)))
        slant = len(xs_of) > 4 or sum(len(x) for x in xs_of) > 30
        ax.set_xticklabels([x.replace("size ", "") for x in xs_of], rotation=35 if slant else 0,
                           ha="right" if slant else "center", fontsize=8.5)
        ax.set_ylabel("speedup over the baseline (x)")
        ax.grid(True, axis="y", which="both", alpha=0.3)
        if tech:
            ax.set_title(tech)
    fig.suptitle(f"{title}\npaper: {paper_hw}   |   ours: {ours_hw}", y=1.0 - 0.08 / fig.get_size_inches()[1],
                 va="top", fontsize=10)
    handles, labels = axes[0].get_legend_handles_labels()
    height = fig.get_size_inches()[1]
    top = 1.0 - 0.6 / height
    fig.legend(handles, labels, loc="upper center", bbox_to_anchor=(0.5, top), ncol=min(len(labels), 4), frameon=False)
    fig.tight_layout(rect=(0, 0, 1, top - 0.3 * math.ceil(len(labels) / 4) / height), h_pad=1.0)
    return fig


APPROX_TECHNIQUES = OIT_APPROX | set(techniques.names("moments", "stochastic"))


def is_exact(row):
    """An exact technique: not one of the approximate families (a peel limited to fewer layers than the
    scene's depth is approximate too), and its error, where the row has one, on the floor."""
    t = row.get("technique") or row.get("variant") or ""
    if t in APPROX_TECHNIQUES or (t in OIT_PEEL and row.get("max_layers") not in (None, "", "0")):
        return False
    errors = [value(row, c) for c in ERROR_COLUMNS if value(row, c) is not None]
    return all(e <= FLOOR for e in errors)


def driver_of(run):
    """The driver as GL_RENDERER and backend name it: the same for schema 1 files (no driver column) and
    schema 2 files of one driver, different for llvmpipe and zink over lavapipe."""
    return run.renderer()


def fastest_table(runs):
    """The exact techniques of each view ranked, per driver: a list of dicts with driver, run, view
    (scene, view, resolution), and per pass (resolve, total) the cases in order of their median ms."""
    out = []
    for run in runs:
        rows = [r for r in run.rows_of("oit") if oitres.is_ok(r) and value(r) is not None]
        params = [p for p in run.params("oit") if p not in oitres.FRAMEWORK_PARAMS]
        key_cols = ["scene", "view", "width", "height"]
        totals = [r for r in rows if r["pass"] == "total" and is_exact(r)]
        own = [p for p in params if p not in key_cols]
        for gkey, grows in group_rows(totals, key_cols).items():
            labels = case_labels(grows, own, oit_label)
            exact = {case_id(r, own) for r in grows}
            entry = {"driver": driver_of(run), "run": run.label,
                     "view": f"{gkey[0]} {gkey[1]} {gkey[2]}x{gkey[3]}".strip(), "ranked": {}}
            for p in ("resolve", "total"):
                cand = [(value(r), labels[case_id(r, own)]) for r in rows
                        if r["pass"] == p and all(r.get(c) == v for c, v in zip(key_cols, gkey))
                        and case_id(r, own) in exact]
                entry["ranked"][p] = sorted(cand)
            if len(entry["ranked"]["total"]) > 1:
                out.append(entry)
    return out


def fastest_figure(entries):
    """One panel per pass (resolve, total) and driver: views down, exact techniques across, each cell the
    case's time over the view's fastest (1.00 = fastest, ringed), the colour that ratio on a log scale."""
    from matplotlib.colors import LogNorm
    drivers = list(dict.fromkeys(e["driver"] for e in entries))
    panels = [(d, p) for d in drivers for p in ("resolve", "total")]
    techniques = sorted({t for e in entries for p in ("resolve", "total") for _, t in e["ranked"][p]})
    n_views = max(sum(1 for e in entries if e["driver"] == d) for d in drivers)
    wide = len(techniques) > 7
    fig, axes = panel_grid(len(panels), ncols=1 if wide else 2,
                           height=1.3 + 0.36 * n_views + (0.08 * max(len(t) for t in techniques) if techniques else 0))
    norm = LogNorm(vmin=1.0, vmax=4.0)
    for ax, (d, p) in zip(axes, panels):
        mine = [e for e in entries if e["driver"] == d]
        grid = [[float("nan")] * len(techniques) for _ in mine]
        for i, e in enumerate(mine):
            ranked = e["ranked"][p]
            if not ranked:
                continue
            best = ranked[0][0]
            for ms, t in ranked:
                j = techniques.index(t)
                ratio = ms / best if best > 0 else float("nan")
                grid[i][j] = min(max(ratio, 1.0), 4.0)
                bold = t == ranked[0][1]
                text = (f"{ms:.0f} ms" if ms >= 100 else f"{ms:.3g} ms") if bold else f"{ratio:.2f}"
                ax.text(j, i, text, ha="center", va="center", fontsize=7.5, fontweight="bold" if bold else "normal",
                        color="white" if ratio > 2.2 else "black")
                if bold:
                    ax.add_patch(matplotlib.patches.Rectangle((j - 0.5, i - 0.5), 1, 1, fill=False,
                                                              edgecolor="black", linewidth=1.8))
        image = ax.imshow(grid, cmap="YlOrRd", norm=norm, aspect="auto")
        bar = fig.colorbar(image, ax=ax, fraction=0.035, pad=0.01, ticks=[1, 1.5, 2, 3, 4])
        bar.ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}x"))
        bar.ax.yaxis.set_minor_formatter(FuncFormatter(lambda v, _: ""))
        bar.set_label("time / fastest (4x and above alike)", fontsize=8)
        ax.set_xticks(range(len(techniques)))
        ax.set_xticklabels(techniques, rotation=35, ha="right", fontsize=8.5)
        ax.set_yticks(range(len(mine)))
        ax.set_yticklabels([e["view"] for e in mine], fontsize=8.5)
        ax.set_title(f"{p} pass, {d}" + f" [{', '.join(dict.fromkeys(e['run'] for e in mine))}]")
    height = fig.get_size_inches()[1]
    fig.suptitle("The fastest exact technique per view and driver: each case's median time over the view's "
                 "fastest\n(ringed: the fastest, with its median ms; the others: time / fastest)",
                 y=1.0 - 0.08 / height, va="top")
    fig.tight_layout(rect=(0, 0, 1, 1.0 - 0.6 / height), h_pad=1.5)
    return fig


def fastest_lines(entries):
    """The summary table as text rows: driver, view, pass, fastest (ms), the runner-up and its ratio."""
    out = []
    for e in entries:
        for p in ("resolve", "total"):
            ranked = e["ranked"][p]
            if not ranked:
                continue
            second = f"{ranked[1][1]} ({ranked[1][0] / ranked[0][0]:.2f}x)" if len(ranked) > 1 and ranked[0][0] > 0 \
                else "\u2014"
            out.append([e["driver"], e["view"], p, ranked[0][1], f"{ranked[0][0]:.4g}", second, str(len(ranked))])
    return out


FASTEST_HEADER = ["driver", "view", "pass", "fastest exact technique", "ms", "runner-up (time / fastest)",
                  "exact cases"]


def invalid_lines(data):
    params = data.params
    seen, lines = set(), []
    for r in data.invalid:
        text = f"{oitres.describe_case(r, params)}: {oitres.status_of(r)}" + (
            f" ({r['reason']})" if r.get("reason") else "")
        if text not in seen:
            seen.add(text)
            lines.append(text)
    return lines


def not_drawn_lines(data):
    """'valid, not drawn (REASON): CASE' for every valid row no panel drew."""
    lines = []
    for reason, rows in data.not_drawn():
        for r in rows:
            text = f"{oitres.describe_case(r, data.params)}: valid, not drawn ({reason})"
            if text not in lines:
                lines.append(text)
    return lines


def add_invalid_note(fig, lines, title="not plotted (invalid or failed):"):
    """The note below the panels: what was left out and why (the first MAX_NOTE_LINES; stdout has all)."""
    if not lines:
        return
    shown = lines[:MAX_NOTE_LINES]
    if len(lines) > MAX_NOTE_LINES:
        shown.append(f"... and {len(lines) - MAX_NOTE_LINES} more (see stdout)")
    text = title + "\n" + "\n".join(s if len(s) < 130 else s[:127] + "..." for s in shown)
    # The note gets room of its own below the axes: the figure grows by it, the axes keep their size.
    width, height = fig.get_size_inches()
    extra = 0.3 + 0.16 * (len(shown) + 1)
    sub = fig.subplotpars
    fig.set_size_inches(width, height + extra)
    fig.subplots_adjust(bottom=(sub.bottom * height + extra) / (height + extra),
                        top=(sub.top * height + extra) / (height + extra))
    fig.text(0.01, 0.01, text, fontsize=8, color="firebrick", va="bottom", family="monospace")


def plot_experiment(data):
    if not data.ok:
        fig, ax = plt.subplots(figsize=(8, 3))
        ax.axis("off")
        ax.text(0.5, 0.6, "no valid rows to plot", ha="center", fontsize=12)
        fig.suptitle(title_of(data), fontsize=10)
        return fig
    return PLOTTERS.get(data.experiment, generic_plot)(data)


def unique_labels(runs):
    """Runs with the same file name (llvmpipe/presets/default.csv, zink-lavapipe/presets/default.csv) get
    as many parent folders in their label as tell them apart, so no figure overwrites another's."""
    depth = 0
    while len({r.label for r in runs}) < len(runs) and depth < 8:
        depth += 1
        for r in runs:
            parts = os.path.abspath(r.path)[:-len(".csv")].split(os.sep) if r.path.endswith(".csv") else \
                os.path.abspath(r.path).split(os.sep)
            r.label = "-".join(parts[-1 - depth:])


def figure_name(experiment, run, ambiguous):
    return f"{experiment}-{run.label}" if ambiguous else experiment


def draw(run, experiment):
    """One experiment of one run as a figure, with the note of what was not plotted: invalid and failed
    cases, and valid rows no panel drew (with the reason). Returns (ExperimentData, Figure, lines of the
    cases not plotted); data.not_drawn_lines names the valid rows not drawn, data.counts() counts them."""
    data = ExperimentData(run, experiment)
    lines = invalid_lines(data)
    fig = plot_experiment(data)
    data.not_drawn_lines = not_drawn_lines(data)
    add_invalid_note(fig, lines + data.not_drawn_lines, "not plotted (invalid or failed), and valid rows not drawn:"
                     if data.not_drawn_lines else "not plotted (invalid or failed):")
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
