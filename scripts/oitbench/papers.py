"""The papers' tables beside ours: the library behind scripts/tables.py (and report.py, findings.py).
Knowles 2014's speedups and table-1 figures are computed in knowles.py."""
import glob
import os
import re
import statistics

from oitbench import knowles
from oitbench import results as oitres

DASH = "\u2014"
# The papers' tables and technique names (data, beside the papers' numbers it describes).
TABLES_PATH = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                           "results", "published", "tables.json")


def norm(text):
    return re.sub(r"[^a-z0-9=_]", "", text.lower())


def words(text):
    """'no-early-out' -> {'no', 'early', 'out', 'noearlyout'}."""
    parts = [w for w in re.split(r"[^a-z0-9]+", text.lower()) if w]
    return set(parts) | ({"".join(parts)} if parts else set())


def alternative_words(text):
    """'bubble early_out=0' -> {'bubble', 'earlyout=0'}: what a row must contain."""
    out = set()
    for item in text.split():
        if "=" in item:
            out.add(norm(item).replace("_", ""))
        else:
            out |= {w for w in re.split(r"[^a-z0-9]+", item.lower()) if w}
    return out


class Technique:
    """How one paper technique string is found among our rows."""

    def __init__(self, experiment, alternatives, exclude=(), size_column=None):
        self.experiment = experiment
        self.alternatives = [alternative_words(a) for a in alternatives]
        self.exclude = set().union(*(alternative_words(e) for e in exclude)) if exclude else set()
        # The parameter the paper's size means for this technique (the oit experiment has both
        # max_frags, for exact resolves, and nodes, for the approximate ones); None: the first of
        # SIZE_COLUMNS a row has.
        self.size_column = size_column

    def matches(self, row_words):
        if row_words & self.exclude:
            return False
        return any(a <= row_words for a in self.alternatives)


# Which of our passes a paper metric is.
METRIC_PASSES = {
    "total_time": ("total",),
    "resolve_time": ("resolve", "sort", "composite", "resolve_sort"),
    "fullscreen_pass_time": ("resolve", "fullscreen", "composite", "blend"),
}
SIZE_COLUMNS = ("size", "n", "nodes", "k", "max_frags", "layers", "depth", "fragments", "count", "array_size")
SCENE_COLUMNS = ("scene",)
VIEW_COLUMNS = ("view", "camera")
GENERIC_SCENES = {"sort-bench", "all", ""}
# The papers' models we cannot ship, and the scenes standing in for them (scenes/*.json). A stand-in
# has its own peak depth, so its MAX_FRAGS may differ from the paper's: where no row of ours has the
# paper's size, the stand-in's own MAX_FRAGS is used.
STAND_INS = {"powerplant": "enginegrid", "atrium": "house"}


class PaperTable:
    def __init__(self, name, source, table, title, baseline, kind="times", any_scene=False, presets=(),
                 baseline_own_size=False, compare=(), ours=None):
        self.name, self.source, self.table, self.title, self.baseline, self.kind = \
            name, source, table, title, baseline, kind
        # The baseline row has a size of its own (MLAB's 4 layers against MBOIT's 6 moments): paper and
        # ours compare with the baseline at that size, not at the row's.
        self.baseline_own_size = baseline_own_size
        # The paper's scenes (powerplant, village, ...) are not shipped: compare with the median over ours.
        self.any_scene = any_scene
        # The presets that rerun this table: where the given CSVs hold rows of one of them, only those
        # rows count, so runs of other grids (other resolutions, other block sizes) never mix in.
        self.presets = tuple(presets)
        # The pairs of rows FINDINGS.md sets side by side, [row, against, our storage, its storage], and the
        # paper row for each of our layouts (Table 4.1).
        self.compare = [tuple(c) for c in compare]
        self.ours = dict(ours or {})


def table(name):
    """The paper table named `name` (PaperTable.name)."""
    return next(t for t in TABLES if t.name == name)


def load_tables(path=TABLES_PATH):
    """The papers' tables and technique names of results/published/tables.json: (TABLES, TECHNIQUES).
    ResultsError names the file and what is wrong with it."""
    data = oitres.read_json(path, "the papers' tables")
    try:
        tables = [PaperTable(**t) for t in data["tables"]]
        techniques = {name: Technique(t["experiment"], t["any"], t.get("exclude", ()), t.get("size"))
                      for name, t in data["techniques"].items()}
    except (KeyError, TypeError, AttributeError) as e:
        raise oitres.ResultsError(f"{path}: not the papers' tables ({type(e).__name__}: {e})") from e
    return tables, techniques


# Paper technique -> our experiment and the words that identify it, and the papers' tables: data, in
# results/published/tables.json (its README says what each field means).
TABLES, TECHNIQUES = load_tables()


def row_words(row, params):
    out = words(row.get("variant", ""))
    for p in params:
        v = row.get(p, "")
        if v == "":
            continue
        if oitres.to_float(v) is None:
            out |= words(v)
        out.add(f"{norm(p).replace('_', '')}={norm(v).replace('_', '')}")
    return out


def load_paper(paper_dir):
    files = sorted(glob.glob(os.path.join(paper_dir, "*.csv")))
    if not files:
        raise oitres.ResultsError(f"{paper_dir}: no paper tables (*.csv) there; give --paper DIR")
    rows = []
    for f in files:
        header, part = oitres.read_csv(f)
        if "technique" not in header or "value" not in header:
            raise oitres.ResultsError(f"{f}: not a paper table (needs source,table,...,technique,metric,value)")
        rows += part
    return rows


class Ours:
    """Our valid rows, by experiment, with the words that identify their technique."""

    def __init__(self, runs, rows=None):
        self.rows = [] if rows is None else rows  # (run, row, words, params)
        for run in runs:
            for exp in run.experiments():
                params = run.params(exp)
                for r in run.rows_of(exp):
                    # The papers captured into per-pixel linked lists: packed-array rows (capture=PPPA)
                    # are our extension and stay out of their tables.
                    if r.get("capture", "") not in ("", "PPLL"):
                        continue
                    if oitres.is_ok(r) and oitres.to_float(r.get("median_ms")) is not None:
                        self.rows.append((run, r, row_words(r, params), params))

    def scoped(self, presets):
        """Only the rows of `presets` where there are any, else all rows."""
        mine = [x for x in self.rows if x[1].get("preset", "") in presets]
        return Ours([], mine) if mine else self

    def describe(self, experiment):
        found = [(run, r) for run, r, _, _ in self.rows if r["experiment"] == experiment]
        if not found:
            return None
        res = sorted({f"{r['width']}x{r['height']}" for _, r in found})
        return f"{found[0][0].renderer()}, {', '.join(res)}"

    def lookup(self, technique, size, scene, metric, view=""):
        """Median ms of our rows matching a paper row (median over several matching rows), or None."""
        found = self._lookup(technique, size, scene, metric, view)
        if found[0] is None and size and norm(scene) in STAND_INS:
            found = self._lookup(technique, "", scene, metric, view)
        return found

    def _lookup(self, technique, size, scene, metric, view):
        rule = TECHNIQUES.get(technique)
        if rule is None:
            return None, 0
        scene = STAND_INS.get(norm(scene), scene)
        passes = METRIC_PASSES.get(metric_base(metric), ("total",))
        hits = []
        for _, r, ws, params in self.rows:
            if r["experiment"] != rule.experiment or r["pass"] not in passes or not rule.matches(ws):
                continue
            if size and not size_matches(r, params, size, rule.size_column):
                continue
            scene_col = next((c for c in SCENE_COLUMNS if c in params and r.get(c)), None)
            if scene_col and scene not in GENERIC_SCENES and norm(r[scene_col]) != norm(scene):
                continue
            view_col = next((c for c in VIEW_COLUMNS if c in params and r.get(c)), None)
            if view_col and view and norm(r[view_col]) != norm(view):
                continue
            hits.append((passes.index(r["pass"]), oitres.to_float(r["median_ms"])))
        if not hits:
            return None, 0
        best_pass = min(h[0] for h in hits)
        values = [v for p, v in hits if p == best_pass]
        return statistics.median(values), len(values)

    def cases(self, experiment, size_column=None):
        """Our (size, scene, view, resolution) groups for an experiment: where summary speedups are taken."""
        groups = {}
        for _, r, _, params in self.rows:
            if r["experiment"] != experiment or r["pass"] != "total":
                continue
            size_col = size_column if size_column in params else next(
                (c for c in SIZE_COLUMNS if c in params and r.get(c)), None)
            scene_col = next((c for c in SCENE_COLUMNS if c in params and r.get(c)), None)
            view_col = next((c for c in VIEW_COLUMNS if c in params and r.get(c)), None)
            key = (size_value(r, size_col) if size_col else "", r.get(scene_col, "") if scene_col else "",
                   r.get(view_col, "") if view_col else "", r["width"], r["height"])
            groups.setdefault(key, None)
        return list(groups)


def size_value(row, column):
    """A row's size in `column`. For max_frags, the MAX_FRAGS the resolve ran with: schema 2 records it
    in the metric max_frags_used (the parameter may be 0, auto); schema 1 wrote it over the parameter."""
    if column == "max_frags" and row.get("max_frags_used", "") != "":
        return row["max_frags_used"]
    return row.get(column, "")


def size_matches(row, params, size, column=None):
    want = oitres.to_float(size)
    if column:
        return column in params and oitres.to_float(size_value(row, column)) == want
    for c in SIZE_COLUMNS:
        if c in params and row.get(c, "") != "":
            return oitres.to_float(size_value(row, c)) == want
    return False


def metric_base(metric):
    """'total_speedup_vs_BASE-IS' -> 'total_time'; 'average_resolve_speedup_vs_BASE-IS' -> 'resolve_time'."""
    if "resolve" in metric:
        return "resolve_time"
    if "fullscreen" in metric:
        return "fullscreen_pass_time"
    return "total_time"


def fmt(x, digits=3):
    if x is None:
        return DASH
    return f"{x:.{digits}g}" if abs(x) < 1000 else f"{x:.0f}"


def baseline_name(table, technique):
    """A.2's baseline depends on the row ('MLAB insertion x16, ...' against 'x16, no early out')."""
    if "{}" in table.baseline:
        m = re.search(r"x(\d+)", technique)
        return table.baseline.format(m.group(1) if m else "")
    return table.baseline


def build_rows(table, paper_rows, ours):
    ours = ours.scoped(table.presets)
    rows = [r for r in paper_rows if r["source"] == table.source and r["table"] == table.table and r["technique"]]
    out = []
    if table.kind == "summary":
        return summary_rows(table, rows, ours)
    if table.kind == "lines":
        return lines_rows(table, rows, ours)
    for r in rows:
        # Tables of scenes we do not ship compare with the median over our scenes.
        our_scene, our_view = ("", "") if table.any_scene else (r["scene"], r["view"])
        paper_value = oitres.to_float(r["value"])
        ours_ms, n = ours.lookup(r["technique"], r["size"], our_scene, r["metric"], our_view)
        base_tech = baseline_name(table, r["technique"])
        base_size = r["size"]
        if table.kind == "speedups":
            paper_speedup = paper_value
        else:
            base = next((b for b in rows if b["technique"] == base_tech and b["scene"] == r["scene"] and
                         b["view"] == r["view"] and (table.baseline_own_size or b["size"] == r["size"]) and
                         b["metric"] == r["metric"]), None)
            base_v = oitres.to_float(base["value"]) if base else None
            paper_speedup = base_v / paper_value if base_v and paper_value else None
            if table.baseline_own_size and base:
                base_size = base["size"]
        metric = metric_base(r["metric"]) if table.kind == "speedups" else r["metric"]
        ours_base, _ = ours.lookup(base_tech, base_size, our_scene, metric, our_view)
        if table.kind == "speedups":
            ours_ms, n = ours.lookup(r["technique"], r["size"], our_scene, metric, our_view)
        ours_speedup = ours_base / ours_ms if ours_base and ours_ms else None
        out.append({
            "table": table.name, "scene": r["scene"], "view": r["view"], "size": r["size"],
            "technique": r["technique"], "metric": r["metric"],
            "paper": paper_value if table.kind != "speedups" else None, "unit": r["unit"],
            "paper_speedup": paper_speedup,
            "ours_ms": ours_ms if table.kind != "speedups" else ours_ms, "ours_speedup": ours_speedup,
            "ours_cases": n,
        })
    return out


def lines_rows(table, rows, ours):
    """The poster's frame rates per model (segment count) beside ours: 1000 / total ms of the lines
    experiment's slices technique at the same segment count, and our per-fragment exact OIT."""
    out = []
    segments = {r["scene"]: r["value"] for r in rows if r["metric"] == "line_segments"}
    for r in rows:
        if r["metric"] != "frame_rate":
            continue
        n = segments.get(r["scene"], "")
        got = {}
        for tech in ("slices", "exact"):
            ms = [oitres.to_float(x["median_ms"]) for _, x, _, _ in ours.rows
                  if x["experiment"] == "lines" and x["pass"] == "total" and x.get("technique") == tech
                  and oitres.to_float(x.get("segments")) == oitres.to_float(n)]
            got[tech] = 1000.0 / statistics.median(ms) if ms else None
        out.append({"table": table.name, "scene": r["scene"], "view": "", "size": n, "technique": r["technique"],
                    "metric": "frame_rate", "paper": oitres.to_float(r["value"]), "unit": "fps",
                    "paper_speedup": None, "ours_ms": got["slices"], "ours_speedup": got["exact"],
                    "ours_cases": int(got["slices"] is not None)})
    return out


def lines_layout(table, rows):
    header = ["model", "segments", "poster fps", "ours fps (slices)", "ours fps (per-fragment exact)"]
    cells = [[r["scene"], r["size"], fmt(r["paper"]), fmt(r["ours_ms"]), fmt(r["ours_speedup"])] for r in rows]
    notes = ["Poster: a GPU of its day. Ours: frames per second of the `lines` experiment (1000 / total median ms)."]
    return TableLayout(table.title, notes, header, [False] + [True] * 4, cells, [r["ours_cases"] > 0 for r in rows])


def summary_rows(table, rows, ours):
    """Knowles 2014 table 1: average and best speedup over its baseline; ours over our own cases."""
    out = []
    for r in rows:
        tech = r["technique"]
        speedups = []
        base_rule = TECHNIQUES[knowles.BASELINE]
        for size, scene, view, w, h in ours.cases(base_rule.experiment, base_rule.size_column):
            if tech not in TECHNIQUES:
                break
            base, _ = ours.lookup(knowles.BASELINE, size, scene or "all", metric_base(r["metric"]), view)
            mine, _ = ours.lookup(tech, size, scene or "all", metric_base(r["metric"]), view)
            if base and mine:
                speedups.append(base / mine)
        ours_value = knowles.summarize(speedups, r["metric"])
        out.append({"table": table.name, "scene": r["scene"], "view": "", "size": "", "technique": tech,
                    "metric": r["metric"], "paper": None, "unit": r["unit"],
                    "paper_speedup": oitres.to_float(r["value"]), "ours_ms": None, "ours_speedup": ours_value,
                    "ours_cases": len(speedups)})
    return out


class TableLayout:
    """A table as text cells, whatever it is printed as: title, notes (Markdown: `code`), header, which
    columns are numbers (right-aligned), the cells, and for each row whether any of ours is in it."""

    def __init__(self, title, notes, header, numeric, cells, ours_found):
        self.title, self.notes, self.header, self.numeric, self.cells, self.ours_found = \
            title, notes, header, numeric, cells, ours_found


def table_layout(table, rows, ours, paper_rows):
    if table.kind == "lines":
        return lines_layout(table, rows)
    ours = ours.scoped(table.presets)
    gpu = next((r["gpu"] for r in paper_rows if r["source"] == table.source and r["table"] == table.table), "?")
    res = next((r["resolution"] for r in paper_rows if r["source"] == table.source and r["table"] == table.table
                and r["resolution"]), "")
    exp = TECHNIQUES.get(table.baseline.format("16"), TECHNIQUES.get(knowles.BASELINE)).experiment
    mine = ours.describe(exp)
    baseline_text = ("the same scene's no-early-out row" if "{}" in table.baseline else table.baseline)
    notes = [f"Paper: {gpu}{', ' + res if res else ''}. Ours: `{exp}` on " +
             (mine if mine else f"— (no valid `{exp}` rows in the given CSVs)") + ".",
             f"Speedup = time of {baseline_text} / time (paper and ours alike)."]
    cols = [("scene", "scene"), ("view", "view"), ("size", "size"), ("technique", "technique"),
            ("metric", "metric")]
    cols = [c for c in cols if len({r[c[0]] for r in rows}) > 1 or c[0] == "technique"]
    if table.kind == "times":
        value_cols = [("paper", "paper"), ("paper_speedup", "paper speedup"), ("ours_ms", "ours ms"),
                      ("ours_speedup", "ours speedup")]
    else:
        value_cols = [("paper_speedup", "paper speedup"), ("ours_speedup", "ours speedup")]
    header = [name for _, name in cols] + [name for _, name in value_cols]
    cells = []
    for r in rows:
        line = [str(r[k]) for k, _ in cols]
        for k, _ in value_cols:
            v = r[k]
            if k == "paper" and v is not None:
                line.append(f"{fmt(v, 4)} {r['unit']}")
            elif k.endswith("speedup"):
                line.append(f"{fmt(v)}x" if v is not None else DASH)
            else:
                line.append(fmt(v, 4))
        cells.append(line)
    return TableLayout(table.title, notes, header, [False] * len(cols) + [True] * len(value_cols), cells,
                       [r["ours_cases"] > 0 for r in rows])


def render_markdown(table, rows, ours, paper_rows):
    layout = table_layout(table, rows, ours, paper_rows)
    lines = [f"### {layout.title}", ""] + layout.notes + [""]
    lines.append("| " + " | ".join(layout.header) + " |")
    lines.append("|" + "|".join("---:" if n else "---" for n in layout.numeric) + "|")
    lines += ["| " + " | ".join(line) + " |" for line in layout.cells]
    return "\n".join(lines) + "\n"


def figure_hardware(table, ours, paper_rows):
    """(the paper's hardware, ours) as a figure's title names them: 'NVIDIA GTX Titan, 1920x1080' and
    'llvmpipe (...) via egl, 128x128'. For plot.py's paper_figure()."""
    mine = [r for r in paper_rows if r["source"] == table.source and r["table"] == table.table]
    gpu = next((r["gpu"] for r in mine if r.get("gpu")), "?")
    res = next((r["resolution"] for r in mine if r.get("resolution")), "")
    exp = TECHNIQUES.get(table.baseline.format("16"), TECHNIQUES.get(knowles.BASELINE)).experiment
    if table.kind == "lines":
        exp = "lines"
    return gpu + (f", {res}" if res else ""), ours.scoped(table.presets).describe(exp) or "\u2014"


def figure_pairs(table, rows):
    """The rows of build_rows() that have both the paper's speedup and ours, as (case, technique, metric,
    paper speedup, our speedup): what plot.py's paper_figure() draws. The baseline's own rows (1x on both
    sides by definition) and the lines table (frame rates, not speedups) give none."""
    if table.kind == "lines":
        return []
    out = []
    for r in rows:
        if r["paper_speedup"] is None or r["ours_speedup"] is None or r["technique"] == baseline_name(table, r["technique"]):
            continue
        case = " ".join(str(x) for x in (r["scene"] if r["scene"] not in GENERIC_SCENES else "", r["view"],
                                          f"size {r['size']}" if r["size"] else "") if x)
        out.append((case, r["technique"], r["metric"], r["paper_speedup"], r["ours_speedup"]))
    return out


CSV_COLUMNS = ["table", "scene", "view", "size", "technique", "metric", "paper", "unit", "paper_speedup",
               "ours_ms", "ours_speedup", "ours_cases"]


def default_paper_dir():
    """results/published in the repository this script lives in, whatever the working directory."""
    repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    return os.path.join(repo, "results", "published")


def select_tables(name):
    if not name:
        return TABLES
    exact = [t for t in TABLES if t.name.lower() == name.lower()]
    if exact:
        return exact
    found = [t for t in TABLES if name.lower() in t.name.lower()]
    if not found:
        raise oitres.ResultsError(f"no table '{name}'; tables: {', '.join(t.name for t in TABLES)}")
    return found


def paired_speedups(rows):
    """The speedups the runner paired per repetition (a preset's or --baseline's baseline, run in the same
    interleaved group as each case: the `speedup` column and its interval): one dict per ok row that has
    one, with experiment, technique, scene, view, pass, resolution, baseline, speedup, ci_lo, ci_hi."""
    out = []
    for r in rows:
        sp = oitres.to_float(r.get("speedup"))
        if not oitres.is_ok(r) or sp is None:
            continue
        out.append({"experiment": r["experiment"], "technique": r.get("technique", "") or r.get("variant", ""),
                    "scene": r.get("scene", ""), "view": r.get("view", ""), "pass": r["pass"],
                    "resolution": f"{r.get('width', '')}x{r.get('height', '')}", "baseline": r.get("baseline", ""),
                    "speedup": sp, "ci_lo": oitres.to_float(r.get("speedup_ci_lo")),
                    "ci_hi": oitres.to_float(r.get("speedup_ci_hi"))})
    return out


def best_paired_speedups(rows, pass_name="resolve"):
    """Per (scene, view, resolution): the technique with the largest paired speedup of `pass_name` (Knowles
    2014's best resolve speedup per view), as a dict of paired_speedups()."""
    best = {}
    for p in paired_speedups(rows):
        if p["pass"] != pass_name:
            continue
        key = (p["scene"], p["view"], p["resolution"])
        if key not in best or p["speedup"] > best[key]["speedup"]:
            best[key] = p
    return best


def paired_markdown(rows):
    """--paired: every paired speedup, and the best per view, as Markdown."""
    lines = ["## Paired speedups (baseline and case in the same interleaved group, per repetition)", "",
             "| scene | view | resolution | technique | pass | baseline | speedup | 95% interval |",
             "|---|---|---|---|---|---|---:|---|"]
    for p in paired_speedups(rows):
        ci = f"{p['ci_lo']:.3g}-{p['ci_hi']:.3g}" if p["ci_lo"] is not None else DASH
        lines.append(f"| {p['scene']} | {p['view']} | {p['resolution']} | {p['technique']} | {p['pass']} | "
                     f"{p['baseline']} | {p['speedup']:.3g} | {ci} |")
    lines += ["", "Best resolve speedup per view:", "", "| scene | view | resolution | technique | speedup |",
              "|---|---|---|---|---:|"]
    for (scene, view, res), p in sorted(best_paired_speedups(rows).items()):
        lines.append(f"| {scene} | {view} | {res} | {p['technique']} | {p['speedup']:.3g} |")
    return "\n".join(lines)
