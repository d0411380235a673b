"""The reading and the wording of FINDINGS.md: the Results of a folder, the numbers' formats, the words that
compare (word(), verdict()), Markdown tables and the sort orders every section shares."""
import datetime
import os
import statistics

from oitbench import results as oitres
from oitbench import report
from oitbench import papers as tables
from oitbench import techniques
from oitbench import knowles


DASH = tables.DASH
EVEN_BAND = 1.10  # a time ratio within 1/1.10 .. 1.10 reads "about even": closer than this run can tell
RMSE_FLOOR = 1e-6  # exact techniques tie at this rmse, as on plot.py's error-against-time axis
# The project brief's targets for exact OIT on this renderer.
TARGET_RESOLVE_VS_CPU = 2.0  # best shader resolve within this factor of the CPU resolve's
TARGET_CAPTURE_RATE = 30e6  # fragments per second captured
SCENE_ORDER = ["planes", "hairball", "hair", "smoke", "engine-grid", "house", "planes-deep"]
PAPER_SCENE = knowles.PAPER_SCENE  # our stand-ins for the papers' models
# The exact techniques that run as shaders (not the CPU resolve), as Knowles 2014 lists them.
EXACT_SHADER = [t for t in techniques.exact_in_paper_order() if t != techniques.CPU_RESOLVE]
# The approximate techniques that keep a per-pixel array of nodes, in the table's order.
PER_PIXEL_ARRAY = tuple(techniques.reading("nodes", "approximate"))
# The approximate techniques that blend every fragment of any scene instead of keeping nodes per pixel (WBOIT,
# unsorted); the splat orders (GLOBAL-SORT, WINDOW-SORT: the table's primitives "splats") are not blends of meshes.
BLENDS = tuple(t for t in techniques.names("approximate")
               if not techniques.reads(t, "nodes") and techniques.primitives(t) != "splats")
# Among them the weighted blend (it reads a depth weight) and the no-OIT baseline (it reads the fewest parameters).
WEIGHTED_BLEND = next(b for b in BLENDS if techniques.reads(b, "wboit_weight"))
# The baseline's insertion-merge twin: the exact resolve the approximate ones are timed against.
BASE_IMS = techniques.find(family="exact", scheme=techniques.scheme(techniques.BASELINE), sort="IMS")
UNSORTED = min(BLENDS, key=lambda b: len(techniques.params(b)))


# ------------------------------------------------------------------------------------------- reading

def field(row, *names):
    """The first of `names` that `row` has filled: a column the schema renamed is read by either name."""
    for n in names:
        v = row.get(n, "")
        if v not in ("", None):
            return v
    return ""


def max_frags_used(row):
    """The MAX_FRAGS a case ran with: schema 2's metric max_frags_used, schema 1's max_frags column."""
    return field(row, "max_frags_used", "max_frags")


def num(row, *names):
    return oitres.to_float(field(row, *names)) if row is not None else None


def ms(row):
    return num(row, "median_ms")


def reps_text(rows):
    """How many repetitions the rows had: one count where the preset fixed it, else the range the stopping
    rule chose and its target (a preset without "reps" repeats until the interval is narrow enough)."""
    counts = sorted({int(float(r["reps"])) for r in rows if r.get("reps") not in ("", None)})
    if not counts:
        return "? repetitions"
    n = str(counts[0]) if len(counts) == 1 else f"{counts[0]}–{counts[-1]}"
    text = f"{n} repetition" + ("" if counts == [1] else "s")
    if {r.get("stop", "") for r in rows} - {"", "fixed"}:
        targets = sorted({r.get("target_ci_pct", "") for r in rows} - {""})
        target = f" ±{targets[0]}%" if len(targets) == 1 else ""
        text += f", until the median's 95% interval is within{target} or a limit stops it"
    return text


class Results:
    """The summary CSVs of RESULTS_DIR/presets, by preset file name, and the papers' rows."""

    def __init__(self, results_dir, paper_dir):
        presets = os.path.join(results_dir, "presets")
        if not os.path.isdir(presets):
            raise oitres.ResultsError(f"{results_dir}: no presets/ folder (scripts/reference_runs.sh writes one)")
        inputs, _, _ = report.collect([presets], None, None)
        self.runs = {}
        for inp in inputs:
            name = inp.rel[:-len(".csv")] if inp.rel.endswith(".csv") else inp.rel
            self.runs[name.replace(os.sep, "/")] = inp.run
        self.paper_rows = tables.load_paper(paper_dir) if os.path.isdir(paper_dir) else []

    def run(self, name):
        return self.runs.get(name)

    def reps(self, name, row):
        """The repetitions of preset `name`'s rows of `row`'s experiment, as text (reps_text)."""
        return reps_text(self.rows(name, row["experiment"], pass_=None, valid=False))

    def rows(self, name, experiment, pass_="total", valid=True, where=None, **eq):
        """Rows of preset `name`'s `experiment` and pass (None: any) whose columns equal `eq`."""
        run = self.runs.get(name)
        if run is None:
            return []
        out = []
        for r in run.rows_of(experiment):
            if pass_ is not None and r.get("pass") != pass_:
                continue
            if valid and not (oitres.is_ok(r) and ms(r) is not None):
                continue
            if any(r.get(k, "") != str(v) for k, v in eq.items()):
                continue
            if where is not None and not where(r):
                continue
            out.append(r)
        return out

    def median(self, name, experiment, pass_="total", where=None, **eq):
        """The median of matching valid rows' median_ms (one row: its own), None without any."""
        vals = [ms(r) for r in self.rows(name, experiment, pass_, where=where, **eq)]
        return statistics.median(vals) if vals else None

    def paper_pairs(self, name, table_name):
        """tables.py's rows for one paper table against preset `name`: the paper's number and ours, matched
        exactly as the report page matches them, keyed (technique, size, scene, view, metric)."""
        run = self.runs.get(name)
        if run is None or not self.paper_rows:
            return {}
        table = next(t for t in tables.TABLES if t.name == table_name)
        rows = tables.build_rows(table, self.paper_rows, tables.Ours([run]))
        return {(r["technique"], str(r["size"]), r["scene"], r["view"], r["metric"]): r for r in rows}

    def paper(self, source, table, technique, metric, scene=None, size=None, view=None):
        """One published number (results/published), None where the paper has none."""
        for r in self.paper_rows:
            if (r["source"], r["table"], r["technique"], r["metric"]) != (source, table, technique, metric):
                continue
            if scene is not None and r["scene"].lower() != scene.lower():
                continue
            if size is not None and r["size"] != str(size):
                continue
            if view is not None and r["view"].lower() != view.lower():
                continue
            return oitres.to_float(r["value"])
        return None


# ------------------------------------------------------------------------------------------- wording

def f_ms(x):
    return tables.fmt(x, 3)


def f_err(x):
    return tables.fmt(x, 2)


def f_x(r):
    """A ratio: 0.73, 2.46, 14.5."""
    if r is None:
        return DASH
    return f"{r:.2f}" if abs(r) < 10 else f"{r:.1f}"


def f_pct(r):
    """A ratio as a change: 1.19 -> +19%."""
    return DASH if r is None else f"{(r - 1) * 100:+.0f}%"


def f_m(x):
    """Millions: 43884720 -> 43.9 M."""
    return DASH if x is None else f"{tables.fmt(x / 1e6, 3)} M"


def f_mb(x):
    return DASH if x is None else f"{tables.fmt(x / 1e6, 3)} MB"


def span(values, fmt=f_x):
    """'0.31–0.40' over the values (one value when they print alike), DASH without any."""
    values = sorted(v for v in values if v is not None)
    if not values:
        return DASH
    lo, hi = fmt(values[0]), fmt(values[-1])
    return lo if lo == hi else f"{lo}\u2013{hi}"


def ratio(a, b):
    return a / b if a is not None and b else None


def word(r):
    """A time ratio A/B in words, for A: faster, slower or about even (within EVEN_BAND)."""
    if r is None:
        return "not measured"
    if r < 1 / EVEN_BAND:
        return "faster"
    if r > EVEN_BAND:
        return "slower"
    return "about even"


def verdict(ratios, noun="cases"):
    """word() over several time ratios: 'slower in all 8 cases', '3 faster, 2 about even of 5 views'."""
    words = [word(r) for r in ratios if r is not None]
    if not words:
        return "not measured"
    kinds = sorted(set(words), key=["faster", "about even", "slower"].index)
    if len(kinds) == 1:
        if len(words) == 1:
            return kinds[0]
        return f"{kinds[0]} in both {noun}" if len(words) == 2 else f"{kinds[0]} in all {len(words)} {noun}"
    return ", ".join(f"{words.count(k)} {k}" for k in kinds) + f" of {len(words)} {noun}"


def f_num(x):
    """A count as printed: 12,757,080."""
    return DASH if x is None else f"{x:,.0f}"


def f_paper(x):
    """A published number as the paper printed it (0.4, 5.4, 12.3)."""
    return tables.fmt(x, 3)


def table(header, rows, numeric=None):
    """Markdown table lines; numeric: which columns are right-aligned (default: all but the first)."""
    numeric = numeric if numeric is not None else [False] + [True] * (len(header) - 1)
    out = ["| " + " | ".join(header) + " |", "|" + "|".join("---:" if n else "---" for n in numeric) + "|"]
    out += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return out + [""]


def scene_key(scene):
    return (SCENE_ORDER.index(scene) if scene in SCENE_ORDER else len(SCENE_ORDER), scene)


def view_key(view):
    return ({"fwd": 0, "rev": 1}.get(view, 2), view)


def case_key(r):
    return (scene_key(r.get("scene", "")), view_key(r.get("view", "")), int(r.get("width") or 0),
            int(r.get("height") or 0))


def sizes_of(rows, column):
    return sorted({int(float(r[column])) for r in rows if oitres.to_float(r.get(column)) is not None})


def missing(name):
    return [f"_No `presets/{name}.csv` in this folder: run `oitbench run --preset {name}` "
            "(or `scripts/reference_runs.sh --only " + name + "`)._", ""]


def res(r):
    return f"{r['width']}x{r['height']}"


def stamp(text):
    try:
        return datetime.datetime.strptime(text, "%Y-%m-%dT%H:%M:%SZ")
    except (TypeError, ValueError):
        return None
