#!/usr/bin/python3
"""FINDINGS.md for a results folder: what the reference runs found, every number computed from its CSVs.

    scripts/findings.py RESULTS_DIR [-o FILE] [--paper DIR]

RESULTS_DIR holds presets/NAME.csv, one `oitbench run --preset NAME` each (NAME_raw.csv beside it), as
scripts/reference_runs.sh writes them into results/llvmpipe. The output (Markdown, stdout or FILE) is
tables and sentences whose every number is read or computed from those CSVs, and for the papers' numbers
from results/published (tables.py's --paper default), so new runs give new findings and nobody types a
measurement. Words that compare ("faster", "slower", "about even") come from the numbers too (word()).
Fixed text says why, never how much. The same CSVs give the same bytes: nothing here reads the clock,
the machine or the order of files on disk.

Columns are read by name, and by either name where the schema renamed one (max_frags_used, schema 2,
was max_frags in schema 1): see field(). A preset whose CSV is missing gets a line saying so.
Exit codes: 0 written; 2 no presets/ folder, no summary CSV in it, or an unreadable CSV.
"""
import argparse
import datetime
import os
import re
import signal
import statistics
import sys

from oitbench import results as oitres  # noqa: E402
from oitbench import figures as plot  # noqa: E402  (pareto_front, oit_label: the figure's front and labels, so the text agrees)
from oitbench import report  # noqa: E402  (collect: summary CSVs by header, NAME_raw.csv beside them)
from oitbench import papers as tables  # noqa: E402  (load_paper, build_rows, fmt: the paper tables as the report shows them)
from oitbench import cli  # noqa: E402
from oitbench import techniques  # noqa: E402
from oitbench import knowles  # noqa: E402  (Knowles 2014's speedups and table 1, computed once)

DASH = tables.DASH
EVEN_BAND = 1.10  # a time ratio within 1/1.10 .. 1.10 reads "about even": closer than this run can tell
RMSE_FLOOR = 1e-6  # exact techniques tie at this rmse, as on plot.py's error-against-time axis
# The project brief's targets for exact OIT on this renderer.
TARGET_RESOLVE_VS_CPU = 2.0  # best shader resolve within this factor of CPU-NATIVE's
TARGET_CAPTURE_RATE = 30e6  # fragments per second captured
SCENE_ORDER = ["planes", "hairball", "hair", "smoke", "engine-grid", "house", "planes-deep"]
PAPER_SCENE = knowles.PAPER_SCENE  # our stand-ins for the papers' models
# The exact techniques that run as shaders (not CPU-NATIVE), as Knowles 2014 lists them.
EXACT_SHADER = techniques.exact_in_paper_order(("BASE", "G", "CS", "BMA"))
PER_PIXEL_ARRAY = ("MLAB", "UMLAB", "AT", "HAT", "UAT", "UHAT", "LAAT")
# The approximate techniques that blend every fragment instead of keeping nodes per pixel (WBOIT, unsorted).
BLENDS = tuple(t["name"] for t in techniques.TABLE if t["family"] == "approximate" and "nodes" not in t["params"])


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


# ------------------------------------------------------------------------------------------- sections

def section_runs(f):
    lines = ["## The runs", ""]
    every = [r for run in f.runs.values() for r in run.rows]
    facts = []
    for col, label in (("gl_renderer", "renderer"), ("gl_version", "GL"), ("backend", "backend"),
                       ("device", "device"), ("cpu_model", "CPU"), ("lp_num_threads", "LP_NUM_THREADS"),
                       ("timer", "primary clock"), ("hostname", "host")):
        values = sorted({r.get(col, "") for r in every if r.get(col, "")})
        if values:
            facts.append(f"{label} {', '.join(f'`{v}`' for v in values)}")
    envs = sorted({r.get("env", "") for r in every if r.get("env", "")})
    facts.append("environment " + (", ".join(f"`{e}`" for e in envs) if envs else "none recorded"))
    lines += ["On " + "; ".join(facts) + ".", ""]
    rows = []
    for name, run in sorted(f.runs.items()):
        totals = [r for r in run.rows if r.get("pass") == "total"]
        count = {s: sum(1 for r in totals if oitres.status_of(r) == s)
                 for s in ("ok", "invalid", "unsupported", "error", "timeout")}
        times = sorted(t for t in (stamp(r.get("timestamp_utc")) for r in run.rows) if t)
        took = ""
        if times:
            secs = int((times[-1] - times[0]).total_seconds())
            took = f"{secs // 60}m{secs % 60:02d}s"
        rows.append([f"`{name}`", len(totals)] + [count[s] for s in count] +
                    [", ".join(sorted({res(r) for r in totals}, key=lambda s: [int(x) for x in s.split("x")])),
                     ", ".join(sorted({r.get("reps", "") for r in totals}, key=int)),
                     ", ".join(sorted({r.get("git_sha", "") for r in run.rows})),
                     times[0].strftime("%Y-%m-%d %H:%M") if times else "", took])
    lines += ["One CSV per preset in [presets/](presets/). Cases count `total` rows; *rows span* is the time "
              "between the first and the last row's timestamp, a lower bound of the preset's wall time.", ""]
    lines += table(["preset", "cases", "ok", "invalid", "unsupported", "error", "timeout", "resolution", "reps",
                    "commit", "first row (UTC)", "rows span"], rows,
                   [False] + [True] * 6 + [False] * 3 + [False, True])
    return lines


def normalised_reason(reason):
    """The reason's first line with its numbers blanked: cases failing the same way group together."""
    return re.sub(r"[0-9][0-9.e+-]*", "#", (reason.strip().splitlines() or [""])[0])


# Parameters that name a case in the list of failures (the rest vary or say little).
IDENTIFYING = ("technique", "scene", "view", "capture", "memory", "layers", "n", "size")


def section_not_ok(f):
    lines = ["## Cases that are not ok", "",
             "Every case whose status is not `ok`, grouped where only the numbers in the reason differ. An "
             "`invalid` case ran but its result differs from the CPU reference, so it carries no time; an "
             "`unsupported` one needs what this driver lacks.", ""]
    rows = []
    for name, run in sorted(f.runs.items()):
        groups = {}
        for exp in run.experiments():
            params = [p for p in run.params(exp) if p not in oitres.FRAMEWORK_PARAMS]
            for r in run.rows_of(exp):
                if r.get("pass") != "total" or oitres.is_ok(r):
                    continue
                key = (exp, oitres.status_of(r), normalised_reason(r.get("reason", "")))
                groups.setdefault(key, (params, []))[1].append(r)
        for (exp, status, _), (params, group) in groups.items():
            vary = oitres.varying(group, params)
            # What the cases have in common that names them, then each case (or each varying value).
            same = [f"{p}={group[0][p]}" for p in IDENTIFYING if p in params and p not in vary and group[0].get(p)]
            head = " ".join(x for x in [group[0].get("variant", "")] + same if x)
            if len(group) <= 4:
                each = "; ".join(" ".join(f"{p}={r[p]}" for p in vary if r.get(p)) for r in group)
            else:
                each = "; ".join(f"{p} " + ", ".join(sorted({r[p] for r in group}, key=oitres.sort_key))
                                 for p in vary)
            cases = ": ".join(x for x in (head, each) if x)
            first = (group[0].get("reason", "").strip().splitlines() or [""])[0]
            first = first if len(first) <= 240 else first[:239] + "\u2026"
            rows.append([f"`{name}`", exp, status, len(group), cases.replace("|", "/"),
                         first.replace("|", "/")])
    if not rows:
        return lines + ["Every case of every preset is `ok`.", ""]
    lines += table(["preset", "experiment", "status", "cases", "which", "reason (of the first)"], rows,
                   [False, False, False, True, False, False])
    return lines


def case_label(row, vary):
    """'oit hairball rev MLAB/8 interleaved' or 'sort rbs n=32 memory=registers': what a reader needs to find
    the case. oit rows are named by technique (plot.oit_label), so a parameter that does not apply to a
    technique, empty in schema 2, changes nothing."""
    if row.get("experiment") == "oit":
        parts = [row.get("scene", ""), row.get("view", ""), approx_label(row)]
        if row.get("capture", "") not in ("", "PPLL"):
            parts.append(row["capture"])
        if "detail" in vary:
            parts.append(f"detail={row.get('detail', '')}")
        return "oit " + " ".join(p for p in parts if p)
    return f"{row.get('experiment', '')} " + oitres.describe_case(row, [p for p in vary if p != "max_frags"])


def section_warmup(f):
    lines = ["## Preparation and the first draw", "",
             "`compile_ms` is compile, link and set-up; `warmup_ms` the first warm-up repetition, where "
             "llvmpipe JIT-compiles the shader; neither enters the statistics. `program_cache` counts how "
             "many cases' programs came from oitbench's program cache.", ""]
    rows = []
    for name, run in sorted(f.runs.items()):
        cases = []
        for exp in run.experiments():
            params = [p for p in run.params(exp) if p not in oitres.FRAMEWORK_PARAMS]
            vary = oitres.varying(run.rows_of(exp), params)
            cases += [(r, vary) for r in run.rows_of(exp) if r.get("pass") == "total"]
        out = [f"`{name}`"]
        for col in ("compile_ms", "warmup_ms"):
            best = max(cases, key=lambda c: num(c[0], col) or -1.0)
            x = num(best[0], col)
            out.append(f"{f_ms(x)} ({case_label(best[0], best[1])})" if x is not None else DASH)
        cache = {}
        for r, _ in cases:
            if r.get("program_cache"):
                cache[r["program_cache"]] = cache.get(r["program_cache"], 0) + 1
        out.append(", ".join(f"{k} {v}" for k, v in sorted(cache.items())) or DASH)
        rows.append(out)
    lines += table(["preset", "largest compile_ms (case)", "largest warmup_ms (case)", "program_cache"], rows,
                   [False, False, False, False])
    return lines


def section_occupancy(f):
    name = "occupancy-fig3"
    lines = ["## Occupancy", "",
             "Knowles 2013 figure 3, local array size against time: the `occupancy` experiment.", ""]
    rows = f.rows(name, "occupancy")
    if not rows:
        return lines + missing(name)
    per = {}
    for r in rows:
        per[(r["variant"], int(r["size"]))] = ms(r) / float(r["draws"])
    sizes = sorted({s for _, s in per})
    r0 = rows[0]
    lines += [f"`presets/{name}.csv`: {res(r0)}, {r0['draws']} full-screen draws per repetition, "
              f"{f.reps(name, r0)}; milliseconds per draw (`median_ms / draws`).", ""]
    body = [[s, f_ms(per.get(("dynamic", s))), f_ms(per.get(("unrolled", s))),
             f_x(ratio(per.get(("dynamic", s)), per.get(("unrolled", s))))] for s in sizes]
    lines += table(["SIZE", "dynamic ms/draw", "unrolled ms/draw", "dynamic / unrolled"], body)
    unrolled = [(s, per[("unrolled", s)]) for s in sizes if ("unrolled", s) in per]
    dynamic = {s: per[("dynamic", s)] for s in sizes if ("dynamic", s) in per}
    if len(unrolled) > 1:
        steps = [(b[1] / a[1], a, b) for a, b in zip(unrolled, unrolled[1:])]
        step, (s0, t0), (s1, t1) = max(steps)
        after = [t / s for s, t in unrolled if s >= s1]
        below = [s for s in dynamic if 1 < s < s1 and ("unrolled", s) in per]
        lines.append(f"- `unrolled`: the largest step between neighbouring sizes is from SIZE {s0} "
                     f"({f_ms(t0)} ms per draw) to {s1} ({f_ms(t1)} ms), {f_x(step)}x. From SIZE {s1} on it "
                     f"costs {span(after, f_ms)} ms per draw per element.")
        if below:
            rs = [dynamic[s] / per[("unrolled", s)] for s in below]
            lines.append(f"- `dynamic` takes {span(rs)}x the time of `unrolled` from SIZE {min(below)} to "
                         f"{max(below)} (`unrolled`: {verdict([1 / r for r in rs], 'sizes')}); at SIZE "
                         f"{sizes[0]} they take {f_ms(dynamic.get(sizes[0]))} and "
                         f"{f_ms(per.get(('unrolled', sizes[0])))} ms.")
        d_below = [dynamic[s] / s for s in dynamic if 8 <= s < s1]
        d_after = [dynamic[s] / s for s in dynamic if s >= s1]
        if d_below and d_after and s0 in dynamic and s1 in dynamic:
            lines.append(f"- `dynamic` per element: {span(d_below, f_ms)} ms per draw from SIZE 8 to {s0}, "
                         f"{span(d_after, f_ms)} from {s1} on; from {s0} to {s1} it steps "
                         f"{f_x(dynamic[s1] / dynamic[s0])}x.")
        around = [dynamic[s] for s in (63, 64, 65) if s in dynamic]
        if len(around) == 3:
            lines.append(f"- `dynamic` at SIZE 63, 64 and 65: {', '.join(f_ms(x) for x in around)} ms per draw, within "
                         f"{(max(around) / min(around) - 1) * 100:.0f}% of each other.")
        both = [per[("unrolled", s)] / dynamic[s] for s in dynamic if s >= s1 and ("unrolled", s) in per]
        if both:
            lines.append(f"- From SIZE {s1} on `unrolled` takes {span(both)}x the time of `dynamic` "
                         f"(`unrolled`: {verdict(both, 'sizes')}).")
    models = sorted({r.get("model_gpu_used", "") for r in rows if r.get("model_gpu_used", "")})
    predicted = [r for r in rows if num(r, "predicted_occupancy") is not None]
    if models:
        lines.append(f"- `model_gpu_used`: {', '.join(f'`{m}`' for m in models)}; `predicted_occupancy` filled in "
                     f"{len(predicted)} of {len(rows)} cases.")
    quick = f.rows("default", "occupancy", variant="unrolled")
    qs = {int(r["size"]): ms(r) for r in quick}
    if 32 in qs and 33 in qs:
        q = quick[0]
        lines.append(f"- The `default` preset's grid ({res(q)}, {q['draws']} draws) shows the same step: "
                     f"`unrolled` {f_x(qs[33] / qs[32])}x from SIZE 32 to 33.")
    lines += ["", "llvmpipe has no occupancy: the shader runs as JIT-compiled SIMD code on CPU threads. The "
              "step is the compiler's own switch from an unrolled array in registers to one indexed in "
              "scratch memory, where NIR stops unrolling loops; it is this driver's version of the papers' "
              "register-against-local-memory effect; the occupancy model has no GPU to match here. See "
              "[docs/experiments/occupancy.md]"
              "(../../docs/experiments/occupancy.md).", ""]
    return lines


def paper_ratio_rows(pairs, comparisons):
    """[comparison, sizes, thesis ratios, ours ratios] for (label, scene, a, b, metric) comparisons."""
    out = []
    for label, scene, a, b, metric in comparisons:
        sizes = sorted({int(k[1]) for k in pairs if k[0] == a and k[2] == scene and k[4] == metric})
        th, ours = [], []
        for s in sizes:
            pa, pb = pairs.get((a, str(s), scene, "", metric)), pairs.get((b, str(s), scene, "", metric))
            th.append(f_x(ratio(pa["paper"], pb["paper"])) if pa and pb else DASH)
            ours.append(f_x(ratio(pa["ours_ms"], pb["ours_ms"])) if pa and pb else DASH)
        out.append([label, ", ".join(map(str, sizes)), ", ".join(th), ", ".join(ours)])
    return out


def section_sort(f):
    name = "bruell2018-sorting"
    lines = ["## Sort and insert", "",
             "Brüll 2018 §4.3–4.5, Tables A.1–A.3, figures 4.7/4.8: the `sort` and `insert` experiments.", ""]
    if not f.run(name):
        return lines + missing(name)
    sort = f.rows(name, "sort")
    r0 = sort[0] if sort else {}
    lines += [f"`presets/{name}.csv`: {res(r0) if r0 else '?'}, {r0.get('stage', '?')} stage, "
              f"{r0.get('keys', '?')} keys, {f.reps(name, r0)}; time ratios of `total` medians "
              "(A / B below 1: A is faster). The thesis's from results/published (GTX 1080, 800x800).", ""]
    a1 = "naive insertion, dynamic index assignment: "
    comparisons = [(f"A.1: {v} / loop", "sort-bench", a1 + v, a1 + "loop", "total_time")
                   for v in ("direct", "switch", "if-else")]
    body = paper_ratio_rows(f.paper_pairs(name, "bruell-A.1"), comparisons)
    body += paper_ratio_rows(f.paper_pairs(name, "bruell-A.3"), [
        ("A.3: bubble with early out / without (ours: both memories' median)", "sort-bench",
         "bubble sort, early out", "bubble sort, no early out",
         "total_time")])
    body += paper_ratio_rows(f.paper_pairs(name, "bruell-A.2"), [
        ("A.2: insertion with early out / without (Village x128; ours: random keys)", "village",
         "MLAB insertion x128, early out", "MLAB insertion x128, no early out", "total_time")])
    lines += table(["comparison", "n", "thesis", "llvmpipe"], body, [False, False, False, False])

    def t(variant, memory, n):
        return f.median(name, "sort", variant=variant, memory=memory, n=n, assign="listing")

    ns = sizes_of(sort, "n")
    v2 = {n: ratio(t("insertion-v2", "local", n), t("insertion-v2", "registers", n)) for n in ns}
    lines.append(f"Figure 4.7 (the thesis: registers faster than local memory): insertion-v2 local / registers "
                 f"at n = {', '.join(map(str, ns))}: {', '.join(f_x(v2[n]) for n in ns)} "
                 f"(registers: {verdict([1 / r for r in v2.values() if r], 'sizes')}).")
    lines.append("")
    variants = []
    for r in sort:
        if r["variant"] not in variants and r.get("assign", "listing") == "listing":
            variants.append(r["variant"])
    top = max(ns) if ns else None
    base = t("insertion-v2", "registers", top)
    body, best = [], []
    for v in variants:
        loc, reg = t(v, "local", top), t(v, "registers", top)
        fastest = min(x for x in (loc, reg) if x is not None) if (loc or reg) else None
        best.append((ratio(fastest, base), v))
        body.append([v, f_ms(loc), f_ms(reg), f_x(ratio(loc, reg)), f_x(ratio(fastest, base))])
    body.sort(key=lambda row: (oitres.to_float(row[4]) is None, oitres.to_float(row[4]) or 0.0))
    lines += [f"Every sort at n = {top} (ms; {DASH}: not valid or no such form):", ""]
    lines += table(["variant", "local ms", "registers ms", "local / registers", "fastest form / insertion-v2"],
                   body)
    ranked = sorted(b for b in best if b[0] is not None)
    if ranked:
        place = [v for _, v in ranked].index("insertion-v2") + 1 if "insertion-v2" in [v for _, v in ranked] else None
        lines.append(f"- At n = {top} the fastest sort is `{ranked[0][1]}` ({f_x(ranked[0][0])}x insertion-v2's "
                     f"time); insertion-v2 ranks {place} of {len(ranked)} valid sorts.")
    both = []
    for v in variants:
        for n in ns:
            r = ratio(t(v, "local", n), t(v, "registers", n))
            if r is not None:
                both.append((r, v, n))
    if both:
        hi = max(both)
        lines.append(f"- local / registers over every sort with both forms valid and every n: "
                     f"{span([b[0] for b in both])} (median {f_x(statistics.median(b[0] for b in both))}; the "
                     f"largest: `{hi[1]}` at n = {hi[2]}).")
    rbs = [ratio(t("rbs", "registers", n), t("insertion-v2", "registers", n)) for n in ns]
    if any(rbs):
        lines.append(f"- `rbs` (the hand-unrolled network, the one true register array here) takes "
                     f"{span(rbs)}x insertion-v2's time in registers: {verdict(rbs, 'sizes')}.")
    bub = [ratio(t("bubble-early", m, n), t("bubble", m, n)) for m in ("local", "registers") for n in ns]
    if any(bub):
        lines.append(f"- `bubble-early` takes {span(bub)}x the time of `bubble` (both memories, every n): "
                     f"with the early out {verdict(bub)}.")
    ins = f.rows(name, "insert")
    for keys in sorted({r["keys"] for r in ins}):
        sz = sizes_of([r for r in ins if r["keys"] == keys], "size")
        rs = [ratio(f.median(name, "insert", variant="early-out", keys=keys, size=s),
                    f.median(name, "insert", variant="no-early-out", keys=keys, size=s)) for s in sz]
        if any(rs):
            lines.append(f"- `insert` with `{keys}` keys: early-out / no-early-out {span(rs)} over sizes "
                         f"{sz[0]}..{sz[-1]} ({f_x(rs[0])} at {sz[0]}, {f_x(rs[-1])} at {sz[-1]}): "
                         f"with the early out {verdict(rs, 'sizes')}.")
    bad = f.rows(name, "sort", valid=False, where=lambda r: not oitres.is_ok(r) and oitres.status_of(r) == "invalid")
    for v in sorted({r["variant"] for r in bad}):
        mine = [r for r in bad if r["variant"] == v]
        grid = [r for r in f.rows(name, "sort", valid=False, variant=v)]
        full = [int(r["n"]) for r in mine if num(r, "unsorted_pixels") == int(r["width"]) * int(r["height"])]
        lines.append(f"- `{v}` is invalid in {len(mine)} of its {len(grid)} cases (memories "
                     f"{', '.join(sorted({r['memory'] for r in mine}))}; n {span([int(r['n']) for r in mine], str)})"
                     + (f"; from n = {min(full)} on every pixel is out of order" if full else "") + ".")
    lines += ["", "llvmpipe runs `if` as masked straight-line code, so an early exit only adds work, and it "
              "does not unroll nested loops whose inner bound depends on the outer index, so a loop-based "
              "sort's `registers` form stays dynamically indexed like its `local` one. The invalid rows are "
              "miscompiles the validators catch ([docs/experiments/sort.md](../../docs/experiments/sort.md), "
              "[insert.md](../../docs/experiments/insert.md)).", ""]
    ins_rows = []
    for keys in sorted({r["keys"] for r in ins}):
        for s in sizes_of([r for r in ins if r["keys"] == keys], "size"):
            ins_rows.append([keys, s] + [f_ms(f.median(name, "insert", variant=v, keys=keys, size=s))
                                         for v in ("early-out", "no-early-out", "two-moves")])
    if ins_rows:
        r0 = ins[0]
        lines += [f"`insert`, {r0['repeat']} insertions per pixel, {r0['memory']} (ms):", ""]
        lines += table(["keys", "size", "early-out", "no-early-out", "two-moves"], ins_rows,
                       [False, True, True, True, True])
    return lines


def section_layout(f):
    lines = ["## Storage layouts", "", "Brüll 2018 §4.1, Table 4.1: the `layout` experiment.", ""]
    name = "bruell2018-storage"
    layout = f.rows(name, "layout")
    if not layout:
        return lines + missing(name)
    r0 = layout[0]
    nodes = sizes_of(layout, "nodes")
    pairs = f.paper_pairs(name, "bruell-4.1")
    scenes = sorted({k[2] for k in pairs}, key=["powerplant", "village", "sanmiguel"].index)
    thesis = {"texture3d": "MLAB texture3d", "interleaved-2x4-a1": "MLAB interleaved-ssbo 2x4",
              "interleaved-2x4-a4": "MLAB interleaved-ssbo 2x4"}

    def lt(lay, n, src=name):
        return f.median(src, "layout", layout=lay, nodes=n)

    layouts = [x for x in dict.fromkeys(r["layout"] for r in layout) if x != "ssbo"]
    body = []
    for lay in layouts:
        row = [f"`{lay}`"] + [f_x(ratio(lt(lay, n), lt("ssbo", n))) for n in nodes]
        for n in nodes:
            th = []
            for s in scenes:
                a, b = pairs.get((thesis.get(lay, ""), str(n), s, "", "total_time")), \
                    pairs.get(("MLAB ssbo", str(n), s, "", "total_time"))
                th.append(f_x(ratio(a["paper"], b["paper"])) if a and b else DASH)
            row.append(" / ".join(th))
        body.append(row)
    lines += [f"`presets/{name}.csv` ({res(r0)}, {r0['layers']} layers, {f.reps(name, r0)}): time / "
              f"`ssbo` of the `total` medians; the thesis's MLAB times ({' / '.join(scenes)}) likewise.", ""]
    lines += table(["layout"] + [f"nodes {n}" for n in nodes] + [f"thesis, {n} nodes" for n in nodes], body)
    for lay, label in (("texture3d", "`texture3d` (image load/store)"), ("texbuffer", "The buffer-texture read path")):
        rs = [ratio(lt(lay, n), lt("ssbo", n)) for n in nodes]
        if any(rs):
            lines.append(f"- {label} takes {span(rs)}x the time of `ssbo`: {verdict(rs, 'node counts')}.")
    inter = [ratio(lt(x, n), lt("ssbo", n)) for x in layouts if x.startswith("interleaved")
             and x != "interleaved-1x1-a1" for n in nodes]
    if any(inter):
        lines.append(f"- The interleaved layouts take {span(inter)}x the time of `ssbo`: {verdict(inter)}.")
    ctl = [ratio(lt("interleaved-1x1-a1", n), lt("ssbo", n)) for n in nodes]
    if any(ctl):
        lines.append(f"- The control `interleaved-1x1-a1`, byte for byte `ssbo`, takes {span(ctl)}x: the "
                     "noise of this comparison.")
    q = [ratio(lt("texture3d", n, "default"), lt("ssbo", n, "default")) for n in sizes_of(
        f.rows("default", "layout"), "nodes")]
    if any(q):
        q0 = f.rows("default", "layout")[0]
        lines.append(f"- The `default` preset's quick grid ({res(q0)}, {q0['layers']} layers): `texture3d` / "
                     f"`ssbo` {span(q)}.")
    every = f.rows(name, "layout", pass_=None) + f.rows("default", "layout", pass_=None)
    lost = sum(num(r, "lost_updates") or 0 for r in every if r["pass"] == "total")
    incons = sum(num(r, "inconsistent_nodes") or 0 for r in every if r["pass"] == "total")
    lines.append(f"- Lost updates over every layout case of both presets: {lost:.0f}; inconsistent nodes: "
                 f"{incons:.0f}.")
    lines += ["", "A CPU rasteriser has no memory transactions to coalesce, and llvmpipe shades a tile's "
              "fragments in primitive order, so the races that interleaved storage invites on a GPU cannot "
              "happen here.", ""]
    return lines


def section_spinlock(f):
    lines = ["## Spinlocks", "", "Brüll 2018 §4.2, Listings 4.1–4.3: the `spinlock` experiment.", ""]
    name = "bruell2018-spinlock"
    spin = f.rows(name, "spinlock", valid=False)
    if not spin:
        return lines + missing(name)
    layers = sizes_of(spin, "layers")
    variants = list(dict.fromkeys(r["variant"] for r in spin))
    body = []
    for n in layers:
        naive = f.median(name, "spinlock", variant="naive", layers=n)
        row = [n]
        for v in variants:
            r = next((x for x in spin if x["variant"] == v and x["layers"] == str(n)), None)
            if r is not None and oitres.is_ok(r):
                row.append(f"{f_ms(ms(r))} ({f_x(ratio(ms(r), naive))}x)")
            else:
                row.append(oitres.status_of(r) if r else DASH)
        body.append(row)
    r0 = spin[0]
    lines += [f"`presets/{name}.csv` ({res(r0)}, {f.reps(name, r0)}, each case in a child process "
              "under the watchdog): `total` ms, and the time over `naive` in brackets.", ""]
    lines += table(["layers"] + [f"`{v}`" for v in variants], body)
    ok = [r for r in spin if oitres.is_ok(r)]
    capped = sum(num(r, "capped_updates") or 0 for r in ok)
    lost = sum(num(r, "lost_updates") or 0 for r in ok)
    timeouts = sum(1 for r in spin if oitres.status_of(r) == "timeout")
    loops = [ratio(f.median(name, "spinlock", variant=v, layers=n), f.median(name, "spinlock", variant="naive",
                                                                           layers=n))
             for v in ("loop", "helper-guard") for n in layers]
    lines.append(f"- Capped updates {capped:.0f}, lost updates {lost:.0f}, timeouts {timeouts}. The loop "
                 f"forms (Listings 4.2/4.3) take {span(loops)}x the naive lock's time: {verdict(loops)}.")
    lines += ["", "The naive lock does not deadlock on llvmpipe, so passing here says nothing about it on a "
              "GPU, where it can hang.", ""]
    return lines


def section_stencil(f):
    lines = ["## Stencil-masked resolve", "", "Brüll 2018 §4.6, Tables A.4/A.5: the `stencil` experiment.", ""]
    name = "bruell2018-stencil"
    st = f.rows(name, "stencil", pass_=None)
    if not st:
        return lines + missing(name)
    cov = sizes_of(st, "coverage")
    resolves = list(dict.fromkeys(r["resolve"] for r in st))

    def s(variant, resolve, c, pass_):
        return f.median(name, "stencil", pass_=pass_, variant=variant, resolve=resolve, coverage=c)

    body, capture, clear = [], [], []
    for c in cov:
        row = [f"{c} %"]
        for rv in resolves:
            for p in ("resolve", "total"):
                row.append(f_x(ratio(s("stencil", rv, c, p), s("no-stencil", rv, c, p))))
            capture.append(ratio(s("stencil", rv, c, "capture"), s("no-stencil", rv, c, "capture")))
            clear.append(ratio(s("no-stencil", rv, c, "clear"), s("no-stencil", rv, c, "total")))
        body.append(row)
    r0 = st[0]
    lines += [f"`presets/{name}.csv` ({res(r0)}, {r0['nodes']} nodes, {r0['layers']} layers, {f.reps(name, r0)}"
              "): stencil / no stencil, by the band's coverage of the screen.", ""]
    lines += table(["coverage"] + [f"{rv} {p}" for rv in resolves for p in ("resolve", "total")], body)
    a4 = f.paper_pairs(name, "bruell-A.4")
    a5 = f.paper_pairs(name, "bruell-A.5")
    th_full = [ratio(a4[k]["paper"], a4[("MLAB no stencil",) + k[1:]]["paper"]) for k in a4
               if k[0] == "MLAB stencil" and k[4] == "fullscreen_pass_time" and ("MLAB no stencil",) + k[1:] in a4]
    th_tot = [ratio(a4[k]["paper"], a4[("MLAB no stencil",) + k[1:]]["paper"]) for k in a4
              if k[0] == "MLAB stencil" and k[4] == "total_time" and ("MLAB no stencil",) + k[1:] in a4]
    th_u = [ratio(a5[k]["paper"], a5[("UMLAB no stencil",) + k[1:]]["paper"]) for k in a5
            if k[0] == "UMLAB stencil" and ("UMLAB no stencil",) + k[1:] in a5]
    if th_full:
        lines.append(f"- The thesis (Village, every node count of Tables A.4/A.5): MLAB's full-screen pass with "
                     f"the mask takes {span(th_full)}x its time without, its total {span(th_tot)}x; UMLAB's total "
                     f"{span(th_u)}x.")
    lines.append(f"- Here the stencil writes change the capture pass by {span([c for c in capture if c], f_pct)} "
                 f"(with them: {verdict(capture)}); the `clear` pass, the same with and without the mask, is "
                 f"{span(clear)} of the unmasked total, which bounds what the total can gain.")
    lines += ["", "The masked resolve skips the pixels outside the band, so its time follows the coverage; "
              "on llvmpipe `layout(early_fragment_tests)` in the resolve is what lets the mask skip the work.", ""]
    return lines


def pairs_by_capture(f, name):
    """{(scene, view, technique, WxH): {capture: {pass: row}}} of the valid oit rows of a preset."""
    out = {}
    for r in f.rows(name, "oit", pass_=None):
        key = (r["scene"], r["view"], r["technique"], res(r))
        out.setdefault(key, {}).setdefault(r.get("capture") or "PPLL", {})[r["pass"]] = r
    return out


def section_capture(f):
    lines = ["## Exact OIT: capture storage", "",
             "Linked lists (PPLL) against packed per-pixel arrays (PPPA), Knowles 2014 §2.2.", ""]
    if not f.run("capture-storage"):
        return lines + missing("capture-storage")
    body, stats = [], []
    for name in ("capture-storage", "oit-scale"):
        pairs = pairs_by_capture(f, name)
        for key in sorted(pairs, key=lambda k: (scene_key(k[0]), view_key(k[1]), k[2], k[3])):
            c = pairs[key]
            if "PPLL" not in c or "PPPA" not in c or "total" not in c["PPLL"] or "total" not in c["PPPA"]:
                continue
            a, b = c["PPLL"], c["PPPA"]
            rr = {p: ratio(ms(b.get(p)), ms(a.get(p))) for p in ("capture", "resolve", "total")}
            mem = ratio(num(b["total"], "node_pool_bytes"), num(a["total"], "node_pool_bytes"))
            share = ratio(num(b.get("capture"), "capture_count_ms"), ms(b.get("capture")))
            stats.append((name, key, rr, mem))
            body.append([f"`{name}`", key[0], key[1], key[2], key[3], f_x(rr["capture"]), f_x(rr["resolve"]),
                         f_x(rr["total"]), f_x(mem), f"{f_ms(ms(a['total']))} \u2192 {f_ms(ms(b['total']))}",
                         f_x(share)])
    lines += ["PPPA / PPLL time of each pass for the same case (below 1: PPPA is faster), the memory of the "
              "fragment storage (`node_pool_bytes`), the `total` ms PPLL \u2192 PPPA, and the share of PPPA's "
              "capture that is its count pass and prefix sum (`capture_count_ms`). Sources: "
              "`presets/capture-storage.csv` and the cases of `presets/oit-scale.csv` run in both layouts.", ""]
    lines += table(["preset", "scene", "view", "technique", "resolution", "capture", "resolve", "total", "memory",
                    "total ms", "count+scan share"], body, [False] * 5 + [True] * 6)

    def over(pass_, name=None, scene=None, technique=None):
        return [rr[pass_] for n, k, rr, _ in stats if (name is None or n == name) and
                (scene is None or k[0] == scene) and (technique is None or k[2] == technique)]

    for pass_ in ("resolve", "capture", "total"):
        parts = []
        for name in ("capture-storage", "oit-scale"):
            scenes = sorted({k[0] for n, k, _, _ in stats if n == name}, key=scene_key)
            per = [f"{sc} {span(over(pass_, name, sc))}" for sc in scenes if over(pass_, name, sc)]
            if per:
                parts.append(f"`{name}`: " + ", ".join(per))
        rs = over(pass_)
        lines.append(f"- {pass_.capitalize()}: PPPA takes {span(rs)}x PPLL's time ({verdict(rs)}); by scene, "
                     + "; ".join(parts) + ".")
    cpu = over("resolve", "capture-storage", technique="CPU-NATIVE")
    if cpu:
        lines.append(f"- CPU-NATIVE's resolve gains most from contiguous fragments: {span(cpu)}x in "
                     "`capture-storage`.")
    lines.append(f"- Memory: PPPA needs {span([m for _, _, _, m in stats])}x PPLL's bytes.")
    lines += ["", "PPPA stores each pixel's fragments side by side, so a resolve reads them in order, but it "
              "draws the geometry twice (a count pass, then the fill): it pays where fragment work dominates "
              "and costs where vertex work does (the CAD stand-ins, the hairball's many thin tubes).", ""]
    return lines


def section_targets(f):
    lines = ["## Exact OIT: targets", "",
             f"Two targets of the project brief: a shader resolve within {f_paper(TARGET_RESOLVE_VS_CPU)}x of "
             f"CPU-NATIVE's, and capture at {tables.fmt(TARGET_CAPTURE_RATE / 1e6, 3)} M fragments/s.", ""]
    body = []
    for name in ("capture-storage", "knowles2014"):
        pairs = pairs_by_capture(f, name)
        groups = {}
        for (scene, view, tech, wh), caps in pairs.items():
            for cap, passes in caps.items():
                if "resolve" in passes:
                    groups.setdefault((scene, view, wh, cap), {})[tech] = ms(passes["resolve"])
        for key in sorted(groups, key=lambda k: (scene_key(k[0]), view_key(k[1]), k[3])):
            techs = groups[key]
            shaders = {t: v for t, v in techs.items() if t != "CPU-NATIVE"}
            if not shaders or "CPU-NATIVE" not in techs:
                continue
            best = min(shaders, key=lambda t: (shaders[t], t))
            r = shaders[best] / techs["CPU-NATIVE"]
            body.append([f"`{name}`", key[0], key[1], key[2], key[3], f"{best} {f_ms(shaders[best])}",
                         f_ms(techs["CPU-NATIVE"]), f_x(r), "yes" if r <= TARGET_RESOLVE_VS_CPU else "no"])
    if body:
        lines += ["The fastest shader resolve of each case against CPU-NATIVE's resolve (ms); `capture-storage` "
                  "runs two shader resolves, `knowles2014` all of them.", ""]
        lines += table(["preset", "scene", "view", "resolution", "capture", "best shader resolve", "CPU-NATIVE",
                        "ratio", "met"], body, [False] * 5 + [False, True, True, False])
        for name in ("capture-storage", "knowles2014"):
            for cap in ("PPLL", "PPPA"):
                mine = [b for b in body if b[0] == f"`{name}`" and b[4] == cap]
                if mine:
                    lines.append(f"- `{name}`, {cap}: met in {sum(b[8] == 'yes' for b in mine)} of {len(mine)} "
                                 f"cases (ratios {span([oitres.to_float(b[7]) for b in mine])}).")
        lines.append("")
    body = []
    for name in ("capture-storage", "oit-scale", "knowles2014"):
        groups = {}
        for r in f.rows(name, "oit"):
            x = num(r, "fragments_per_s")
            if x is not None:
                groups.setdefault((r["scene"], res(r), r.get("capture") or "PPLL"), []).append(x)
        for key in sorted(groups, key=lambda k: (scene_key(k[0]), [int(v) for v in k[1].split("x")], k[2])):
            xs = groups[key]
            met = "yes" if min(xs) >= TARGET_CAPTURE_RATE else ("no" if max(xs) < TARGET_CAPTURE_RATE else "in part")
            body.append([f"`{name}`", key[0], key[1], key[2], len(xs), span([x / 1e6 for x in xs], f_ms), met])
    if body:
        lines += ["Capture rate (`fragments_per_s`, fragments captured per second of the capture pass) over "
                  "every valid case of a scene, resolution and layout:", ""]
        lines += table(["preset", "scene", "resolution", "capture", "cases", "M fragments/s", "met"], body,
                       [False] * 4 + [True, True, False])
    lines += ["On a software renderer capture is CPU rasterisation: the big triangles of the planes reach the "
              "rate, the CAD stand-ins spend their time on vertices, not fragments.", ""]
    return lines


def speedups(f, name, pass_):
    """knowles.view_speedups of a preset's per-pixel-linked-list oit rows (paired where they carry it)."""
    return knowles.view_speedups(f.rows(name, "oit", pass_=pass_, capture="PPLL"), pass_)


def section_knowles2014(f):
    name = "knowles2014"
    lines = ["## Exact OIT: Knowles 2014", "",
             "The resolve sorts of Knowles 2014 (RBS), tables 1 and 3.", ""]
    if not f.run(name):
        return lines + missing(name)
    paper = knowles.Paper(f.paper_rows)
    rsp, tsp = speedups(f, name, "resolve"), speedups(f, name, "total")
    views = sorted(rsp, key=lambda k: (scene_key(k[0]), view_key(k[1])))
    techs = [t for t in EXACT_SHADER + ["CPU-NATIVE"] if t != "BASE-IS" and any(t in rsp[v] for v in views)]
    r0 = f.rows(name, "oit")[0]
    blocks = ", ".join(sorted({r["block"] for r in f.rows(name, "oit", pass_=None, valid=False) if r.get("block")}, key=int)) or "?"
    lines += [f"`presets/{name}.csv` ({res(r0)}, {f.reps(name, r0)}, register blocks of {blocks}): "
              "speedup over BASE-IS (time of BASE-IS / time; paired per repetition where the rows carry it) per view, the paper's (GTX Titan, 1920x1080) in "
              "brackets; the engine grid stands in for the power plant, the house for the atrium, CS-* for the "
              "paper's CUDA-* rows.", ""]
    for label, sp, metric in (("Resolve", rsp, "resolve"), ("Total", tsp, "total")):
        body = []
        for t in techs:
            row = [t]
            for v in views:
                ours = sp.get(v, {}).get(t)
                p = paper.speedup(t, v[0], v[1], metric)
                row.append(f_x(ours) + (f" ({f_paper(p)})" if p is not None else ""))
            body.append(row)
        lines += [f"{label} speedups:", ""]
        lines += table(["technique"] + [f"{s} {w}" for s, w in views], body)

    def ours(t, pred, sp=rsp):
        return [sp[v].get(t) for v in views if pred(v) and sp[v].get(t) is not None]

    def theirs(t, pred, metric="resolve"):
        return [p for p in (paper.speedup(t, v[0], v[1], metric) for v in views if pred(v)) if p is not None]

    rev = lambda v: v[1] == "rev"  # noqa: E731
    fwd = lambda v: v[1] == "fwd"  # noqa: E731
    model = lambda v: v[0] in PAPER_SCENE  # noqa: E731
    every = lambda v: True  # noqa: E731
    for v in [v for v in views if rev(v)]:
        lines.append(f"- {v[0]} {v[1]}: BASE-RBS-L's resolve {f_x(rsp[v].get('BASE-RBS-L'))}x (paper "
                     f"{f_paper(paper.speedup('BASE-RBS-L', v[0], v[1], 'resolve'))}x), "
                     f"BMA-RBS-L {f_x(rsp[v].get('BMA-RBS-L'))}x (paper "
                     f"{f_paper(paper.speedup('BMA-RBS-L', v[0], v[1], 'resolve'))}x).")
    rbs_fwd = ours("BASE-RBS-L", fwd) + ours("BMA-RBS-L", fwd)
    lines.append(f"- On the sorted `fwd` views the RBS resolves (BASE-RBS-L, BMA-RBS-L) reach {span(rbs_fwd)}x "
                 f"(paper {span(theirs('BASE-RBS-L', fwd) + theirs('BMA-RBS-L', fwd), f_paper)}x): against "
                 f"BASE-IS, {verdict([1 / x for x in rbs_fwd if x])}.")
    lines.append(f"- On the model views BMA-RBS-L's resolve speedup is {span(ours('BMA-RBS-L', model))}x (paper "
                 f"{span(theirs('BMA-RBS-L', model), f_paper)}x).")
    bma = ours("BMA-IS", every)
    lines.append(f"- BMA-IS's resolve speedup is {span(bma)}x (paper {span(theirs('BMA-IS', every), f_paper)}x): "
                 f"against BASE-IS, {verdict([1 / x for x in bma if x], 'views')}.")
    cpu_best = [v for v in views if rsp[v].get("CPU-NATIVE") is not None and
                rsp[v]["CPU-NATIVE"] >= max(x for x in rsp[v].values() if x is not None)]
    others = [v for v in views if v not in cpu_best]
    text = f"- CPU-NATIVE's resolve is the fastest on {len(cpu_best)} of {len(views)} views"
    if others:
        text += " (elsewhere: " + "; ".join(
            f"{v[0]} {v[1]}, {max((t for t in rsp[v] if rsp[v][t]), key=lambda t: rsp[v][t])} "
            f"{f_x(max(x for x in rsp[v].values() if x))}x against CPU-NATIVE's {f_x(rsp[v].get('CPU-NATIVE'))}x"
            for v in others) + ")"
    lines.append(text + f"; {span(ours('CPU-NATIVE', rev))}x on the `rev` views, "
                 f"{span(ours('CPU-NATIVE', lambda v: not rev(v)))}x elsewhere.")
    p_total = paper.speedup("BMA-RBS-L", "planes", "Rev", "total")
    p_res = paper.speedup("BMA-RBS-L", "planes", "Rev", "resolve")
    if p_total is not None:
        lines.append(f"- The paper's planes Rev, BMA-RBS-L: total speedup {f_paper(p_total)}x, resolve "
                     f"{f_paper(p_res)}x.")
    lines.append("")

    body, avg = [], knowles.table1(rsp, {v: tsp[v] for v in views}, techs)
    for t, figures in avg.items():
        theirs1 = [paper.summary(t, m) for m in figures]
        body.append([t] + [f"{f_x(x)}x" for x in figures.values()] +
                    [" / ".join(f_paper(p) for p in theirs1[:2]), " / ".join(f_paper(p) for p in theirs1[2:])])
    lines += ["Table 1's layout: the mean and the best speedup over the views (ours: these views; the paper: "
              "its scenes).", ""]
    lines += table(["technique", "avg total", "avg resolve", "best total", "best resolve",
                    "paper avg total / resolve", "paper best total / resolve"], body)
    goal = {m: paper.summary("BMA-RBS-L", m) for m in ("best_resolve", "average_resolve", "average_total")}
    shader = {t: v for t, v in avg.items() if t != "CPU-NATIVE"}
    if shader and all(g is not None for g in goal.values()):
        parts = []
        for m, label in (("best_resolve", "best resolve"), ("average_resolve", "average resolve"),
                         ("average_total", "average total")):
            t = max(shader, key=lambda k: (shader[k][m], k))
            parts.append(f"{label} {f_x(shader[t][m])}x ({t}) against {f_paper(goal[m])}x: "
                         f"{'met' if shader[t][m] >= goal[m] else 'not met'}")
        lines.append("- The paper's BMA-RBS-L figures as targets for our best shader technique: " +
                     "; ".join(parts) + ".")
        if "CPU-NATIVE" in avg:
            c = avg["CPU-NATIVE"]
            lines.append(f"- CPU-NATIVE, outside the shader resolves: best resolve {f_x(c['best_resolve'])}x, "
                         f"average resolve {f_x(c['average_resolve'])}x, average total {f_x(c['average_total'])}x.")
    lines.append("")
    body = []
    for r in sorted(f.rows(name, "oit", technique="BMA-AUTO"), key=case_key):
        body.append([r["scene"], r["view"], max_frags_used(r), f"`{r.get('bma_auto_choice', '')}`",
                     r.get("bma_auto_source", "")])
    if body:
        lines += ["What BMA-AUTO chose per depth interval (interval top: sort), calibrated on this driver:", ""]
        lines += table(["scene", "view", "MAX_FRAGS", "choice", "source"], body, [False] * 5)
    body = []
    for v in views:
        rows = f.rows(name, "oit", scene=v[0], view=v[1], capture="PPLL")
        rates = [num(r, "fragments_per_s") for r in rows]
        caps = [ms(r) for r in f.rows(name, "oit", pass_="capture", scene=v[0], view=v[1], capture="PPLL")]
        r1 = rows[0]
        body.append([v[0], v[1], f_num(num(r1, "polygons")), f_num(num(r1, "total_fragments")),
                     field(r1, "peak_depth"), max_frags_used(r1), span([x / 1e6 for x in rates], f_ms),
                     span(caps, f_ms)])
    lines += ["Capture on these views (every technique's capture pass):", ""]
    lines += table(["scene", "view", "polygons", "fragments", "peak depth", "MAX_FRAGS", "M fragments/s",
                    "capture ms"], body)
    lines += ["BMA's gain on a GPU is occupancy, which a CPU rasteriser does not have, so on llvmpipe its "
              "extra passes cost more than its smaller arrays save. On the `fwd` views the lists arrive "
              "sorted and insertion sort is already optimal, while the unrolled network, masked straight-line "
              "code here, always pays its worst case.", ""]
    return lines


RESOLVE_GOAL_REV = 8.7  # the paper's best resolve speedup over BASE-IS (GTX Titan, table 3)
RESOLVE_GOAL_FWD = 1.2  # the fwd views' goal for our best exact resolve


def resolve_label(r):
    """BASE-IS, CS-IS+order-check, CS-RBS-L/bitonic, BMA-AUTO: one oit row's resolve as the preset varies it."""
    label = r["technique"]
    if r.get("block_sort"):
        label += "/" + r["block_sort"]
    if r.get("order_check") == "on":
        label += "+order-check"
    return label


def speedup_text(entry, pass_):
    """1.23x, with its 95% interval where the row's own pair gave one (not for a chained ratio)."""
    v = entry.get(pass_)
    if not v:
        return DASH
    text = tables.fmt(v, 3) + "x"
    lo, hi = entry.get(pass_ + "_ci") or (None, None)
    if lo is not None and hi is not None and not entry.get("chained_" + pass_):
        text += f" [{tables.fmt(lo, 3)}–{tables.fmt(hi, 3)}]"
    return text


def section_resolve_speedups(f):
    name = "resolve-speedups"
    lines = ["## The fastest exact resolve, paired", ""]
    if not f.run(name):
        return lines + missing(name)
    oit = f.rows(name, "oit", pass_="resolve", valid=False)
    if oit:
        r0 = oit[0]
        paired = any(r.get("speedup") for r in oit)
        lines += [f"`presets/{name}.csv` ({res(r0)}, {f.reps(name, r0)}): each candidate ran in an interleaved "
                  "group that holds its baseline, so its speedup "
                  "(baseline time / its time) is a ratio of medians taken side by side"
                  + (" (the rows' `speedup`: the median of the per-repetition ratios)" if paired else "")
                  + ". The order check's candidates are paired with BASE-IS with the order check, chained "
                  "through that one's pair with plain BASE-IS, so every speedup below is over plain BASE-IS. "
                  "`resolve` and `total` passes; blocks of 32 for CS-RBS-L. Goals: the paper's best resolve "
                  f"speedup on planes rev ({RESOLVE_GOAL_REV:g}x) and {RESOLVE_GOAL_FWD:g}x on every fwd view.", ""]
        speed, base_ms = {}, {}
        for pass_ in ("resolve", "total"):
            by_view = {}
            for r in f.rows(name, "oit", pass_=pass_, valid=False):
                by_view.setdefault((r["scene"], r["view"]), []).append(r)
            for view, rows in by_view.items():
                sp = speed.setdefault(view, {})
                if paired:
                    # Schema 4: each row carries its paired speedup over its baseline; a baseline measured in
                    # several groups has rows without one (its own), kept for its times only.
                    for r in rows:
                        label = resolve_label(r)
                        if label == "BASE-IS" and pass_ == "resolve" and ms(r) is not None:
                            base_ms.setdefault(view, []).append(ms(r))
                        entry = sp.setdefault(label, {"row": r})
                        if label == "BASE-IS":
                            entry[pass_], entry[pass_ + "_ms"] = 1.0, ms(r) if oitres.is_ok(r) else None
                            continue
                        value = num(r, "speedup") if oitres.is_ok(r) else None
                        if value is None and entry.get(pass_) is not None:
                            continue  # the same case as another pair's baseline: keep the paired row
                        entry["row"] = r
                        entry[pass_ + "_ms"] = ms(r) if oitres.is_ok(r) else None
                        entry[pass_] = value
                        entry[pass_ + "_ci"] = (num(r, "speedup_ci_lo"), num(r, "speedup_ci_hi"))
                    # Candidates with the order check were divided by BASE-IS with it: chain to plain BASE-IS.
                    link = sp.get("BASE-IS+order-check", {}).get(pass_)
                    for label, entry in sp.items():
                        if label.endswith("+order-check") and label != "BASE-IS+order-check":
                            if entry.get(pass_) is not None and entry.get("chained_" + pass_) is None:
                                entry["chained_" + pass_] = True
                                entry[pass_] = entry[pass_] * link if link else None
                    continue
                for a, b in zip(rows[0::2], rows[1::2]):  # schema 3: the run's groups of two, in the order they ran
                    la, lb = resolve_label(a), resolve_label(b)
                    if la == "BASE-IS" and pass_ == "resolve" and ms(a) is not None:
                        base_ms.setdefault(view, []).append(ms(a))
                    ok = oitres.is_ok(a) and oitres.is_ok(b) and ms(a) is not None and ms(b)
                    chain = 1.0 if la == "BASE-IS" else sp.get(la, {}).get(pass_)
                    value = ms(a) / ms(b) * chain if ok and chain else None
                    entry = sp.setdefault(lb, {"row": b})
                    entry[pass_] = value
                    entry[pass_ + "_ms"] = ms(b) if oitres.is_ok(b) else None
        body, best_rows = [], []
        for view in sorted(speed, key=lambda k: (scene_key(k[0]), view_key(k[1]))):
            cases = speed[view]
            order = sorted(cases, key=lambda l: -(cases[l].get("resolve") or 0))
            for label in order:
                c = cases[label]
                body.append([f"{view[0]} {view[1]}", label, f_ms(c.get("resolve_ms")),
                             speedup_text(c, "resolve"), speedup_text(c, "total")])
            if order and cases[order[0]].get("resolve"):
                best = cases[order[0]]
                goal = RESOLVE_GOAL_REV if view == ("planes", "rev") else RESOLVE_GOAL_FWD if view[1] == "fwd" else None
                met = DASH if goal is None else ("met" if best["resolve"] >= goal else "not met")
                b = base_ms.get(view, [])
                best_rows.append([f"{view[0]} {view[1]}", order[0], tables.fmt(best["resolve"], 3) + "x",
                                  tables.fmt(best.get("total"), 3) + "x" if best.get("total") else DASH,
                                  f"{goal:g}x" if goal else DASH, met,
                                  f"{f_ms(min(b))}–{f_ms(max(b))}" if b else DASH])
        lines += table(["view", "resolve", "resolve ms", "resolve speedup", "total speedup"], body,
                       [False, False, True, True, True])
        lines += ["The fastest per view, and how far BASE-IS itself moved between the view's groups (the "
                  "reason only paired ratios are compared):", ""]
        lines += table(["view", "fastest resolve", "resolve speedup", "total speedup", "goal", "goal met",
                        "BASE-IS resolve ms across groups"], best_rows, [False, False, True, True, True, False, True])
        lines += ["A list that arrives far-to-near needs no sort and one that arrives near-to-far only a "
                  "reversal: the order check turns both into a load and a pass, where every sort still pays for "
                  "its comparisons. The register networks sort without a branch, so on a driver that runs `if` "
                  "as masked straight-line code they cost their fixed size and no more.", ""]
    sort = f.rows(name, "sort")
    if sort:
        r0 = sort[0]
        ms_of = {(r["variant"], r["n"]): ms(r) for r in sort}
        body = []
        for n in sorted({r["n"] for r in sort}, key=int):
            rbs = ms_of.get(("rbs", n))
            for v in ("insertion-v2", "bitonic-network", "odd-even-merge-network"):
                if (v, n) in ms_of:
                    body.append([n, v, f_ms(ms_of[(v, n)]), f_ms(rbs), tables.fmt(ratio(ms_of[(v, n)], rbs), 3),
                                 word(ratio(ms_of[(v, n)], rbs))])
        lines += [f"The register networks against RS, the insertion network of the RBS block sort (`sort` "
                  f"experiment in the same preset, {res(r0)}, {r0.get('keys', '?')} keys, registers, one "
                  "interleaving group): time / RS's time.", ""]
        lines += table(["n", "sort", "ms", "RS ms", "/ RS", ""], body, [True, False, True, True, True, False])
    return lines

def section_knowles2013(f):
    name = "knowles2013"
    lines = ["## Exact OIT: Knowles 2013", "",
             "BMA against the baseline, Knowles 2013 table 2.", ""]
    if not f.run(name):
        return lines + missing(name)
    pairs = f.paper_pairs(name, "knowles2013-2")
    groups = {}
    for r in f.rows(name, "oit", pass_=None):
        groups.setdefault((r["scene"], r["view"], res(r), max_frags_used(r)), {})[(r["technique"], r["pass"])] = ms(r)
    body, auto = [], []
    for key in sorted(groups, key=lambda k: (scene_key(k[0]), int(k[3] or 0))):
        g = groups[key]
        base, bma = g.get(("BASE-IS", "total")), g.get(("BMA-IS", "total"))
        pscene = PAPER_SCENE.get(key[0], key[0])
        p = next((r["paper"] for k, r in pairs.items() if k[0] == "BMA-OIT" and k[2] == pscene and k[1] == key[3]
                  and k[4] == "total_speedup_vs_OIT"), None)
        a = ratio(base, g.get(("BMA-AUTO", "total")))
        auto.append(a)
        body.append([key[0], key[1], key[2], key[3], f_ms(base), f_ms(bma), f_x(ratio(base, bma)),
                     f"{f_paper(p)} ({pscene})" if p is not None else DASH, f_x(a),
                     f_ms(g.get(("BASE-IS", "resolve")))])
    r0 = f.rows(name, "oit")[0]
    lines += [f"`presets/{name}.csv` ({f.reps(name, r0)}): `total` ms and the speedup over BASE-IS "
              "(the paper's OIT); the paper's BMA-OIT speedup on its GPU (GTX 670, 1680x1050) for the scene "
              "our stand-in replaces.", ""]
    lines += table(["scene", "view", "resolution", "MAX_FRAGS", "BASE-IS", "BMA-IS", "BMA-IS speedup",
                    "paper", "BMA-AUTO speedup", "BASE-IS resolve"], body,
                   [False, False, False, True, True, True, True, False, True, True])
    smoke = sorted((k for k in groups if k[0] == "smoke"), key=lambda k: int(k[3] or 0))
    if len(smoke) >= 2:
        lo, hi = groups[smoke[0]], groups[smoke[-1]]
        p_lo = f.paper("knowles2013-bma", "2", "OIT", "total_time", scene="smoke", size=smoke[0][3])
        p_hi = f.paper("knowles2013-bma", "2", "OIT", "total_time", scene="smoke", size=smoke[-1][3])
        lines.append(f"- Smoke, MAX_FRAGS {smoke[0][3]} \u2192 {smoke[-1][3]}: BASE-IS total "
                     f"{f_ms(lo.get(('BASE-IS', 'total')))} \u2192 {f_ms(hi.get(('BASE-IS', 'total')))} ms, resolve "
                     f"{f_ms(lo.get(('BASE-IS', 'resolve')))} \u2192 {f_ms(hi.get(('BASE-IS', 'resolve')))} ms; the "
                     f"paper's OIT {f_ms(p_lo)} \u2192 {f_ms(p_hi)} ms.")
    lines.append(f"- BMA-AUTO's total speedup over BASE-IS: {span(auto)}x; against BASE-IS, "
                 f"{verdict([1 / a for a in auto if a])}.")
    lines += ["", "A bigger MAX_FRAGS costs the baseline little here, because no occupancy is lost to a bigger "
              "local array on a CPU; so BMA, which exists to avoid that cost, has nothing to win.", ""]
    return lines


def section_scale(f):
    name = "oit-scale"
    lines = ["## Exact OIT at scale", ""]
    if not f.run(name):
        return lines + missing(name)
    body = []
    for r in sorted(f.rows(name, "oit", valid=False), key=lambda r: (case_key(r), r.get("capture", ""),
                                                                     r["technique"])):
        status = oitres.status_of(r)
        body.append([r["scene"], r.get("detail", ""), r["view"], res(r), r.get("capture", ""), r["technique"],
                     max_frags_used(r), status, f_m(num(r, "total_fragments")), f_mb(num(r, "node_pool_bytes")),
                     f_m(num(r, "fragments_per_s")), f_ms(ms(r)) if status == "ok" else DASH])
    r0 = f.rows(name, "oit", valid=False)[0]
    lines += [f"`presets/{name}.csv` ({f.reps(name, r0)}, every case validated): fragments, the storage's "
              "memory (`node_pool_bytes`), capture rate and `total` ms. Why a case is not ok: above.", ""]
    lines += table(["scene", "detail", "view", "resolution", "capture", "technique", "MAX_FRAGS", "status",
                    "fragments", "memory", "fragments/s", "total ms"], body, [False] * 8 + [True] * 4)
    ok = [r for r in f.rows(name, "oit")]
    if ok:
        big = max(ok, key=lambda r: (num(r, "node_pool_bytes") or 0, r["technique"]))
        lines.append(f"- {len(ok)} of {len(body)} cases valid; the largest valid storage: {big['scene']} at "
                     f"{res(big)}, {f_m(num(big, 'total_fragments'))} fragments in "
                     f"{f_mb(num(big, 'node_pool_bytes'))} ({big.get('capture', '')}).")
    lines += ["", "Past llvmpipe's texel-buffer limit a case is `unsupported` with the reason; past its loop "
              "budget (a shader invocation's loops end after a fixed total number of iterations) the deep "
              "resolves go wrong and the validator marks them `invalid`.", ""]
    return lines


def approx_key(r):
    return (r["technique"], r.get("nodes", ""), r.get("storage", ""), r.get("wboit_weight", ""))


def approx_label(r):
    label = plot.oit_label(r)
    if r["technique"] in PER_PIXEL_ARRAY and r.get("storage"):
        label += f" {r['storage']}"
    return label


def section_approx(f):
    name = "bruell2018-approx"
    lines = ["## Approximate OIT", "",
             "What accuracy costs in time: Brüll 2018 chapters 5–6, Tables 5.1, 6.1–6.3.", ""]
    rows = f.rows(name, "oit")
    if not rows:
        return lines + missing(name)
    scenes = sorted({r["scene"] for r in rows}, key=scene_key)
    cases = {}
    for r in rows:
        cases.setdefault(approx_key(r), {})[r["scene"]] = r
    def order(k):
        r1 = next(iter(cases[k].values()))
        if k[0] in PER_PIXEL_ARRAY:
            return (2, PER_PIXEL_ARRAY.index(k[0]), int(r1.get("nodes") or 0), r1.get("storage", ""))
        return (0 if k[0] in BLENDS else 1, 0, 0, plot.oit_label(r1))

    keys = sorted(cases, key=order)
    body = []
    for k in keys:
        r1 = next(iter(cases[k].values()))
        body.append([approx_label(r1)] + [x for s in scenes for x in
                                          (f_ms(ms(cases[k].get(s))), f_err(num(cases[k].get(s), "rmse")))])
    r0 = rows[0]
    lines += [f"`presets/{name}.csv` ({res(r0)}, `{r0.get('detail', '')}` scenes, view {r0['view']}, "
              f"{f.reps(name, r0)}): `total` ms and rmse against the exact CPU reference; per-pixel-array "
              "techniques are TECHNIQUE/nodes and their storage.", ""]
    lines += table(["technique"] + [x for s in scenes for x in (f"{s} ms", f"{s} rmse")], body)

    def t(tech, nodes, storage, scene):
        return f.median(name, "oit", technique=tech, nodes=nodes, storage=storage, scene=scene)

    comps = [("UMLAB/MLAB (Table 5.1)", "5.1", "UMLAB", "MLAB", "interleaved", "interleaved"),
             ("UAT/AT (Table 6.1)", "6.1", "UAT", "AT", "interleaved", "interleaved"),
             ("LAAT/AT (Table 6.2)", "6.2", "LAAT", "AT", "texture3d", "interleaved"),
             ("UHAT/HAT (Table 6.3)", "6.3", "UHAT", "HAT", "interleaved", "interleaved")]
    body, found = [], {}
    for label, tab, a, b, sa, sb in comps:
        nodes = sizes_of([r for r in rows if r["technique"] == a], "nodes")
        row = [label, " / ".join(map(str, nodes))]
        for pscene in ("powerplant", "village"):
            row.append(" / ".join(f_x(ratio(f.paper("bruell2018-thesis", tab, a, "total_time", pscene, n),
                                            f.paper("bruell2018-thesis", tab, b, "total_time", pscene, n)))
                                  for n in nodes))
        for s in scenes:
            rs = [ratio(t(a, n, sa, s), t(b, n, sb, s)) for n in nodes]
            found.setdefault(a, []).extend(rs)
            row.append(" / ".join(f_x(x) for x in rs))
        body.append(row)
    lines += ["Time ratios beside the thesis's (GTX 1080, 800x800): ours with the interleaved layout, LAAT "
              "with the 3D texture, as the thesis ran them.", ""]
    lines += table(["ratio", "nodes", "thesis Powerplant", "thesis Village"] + [f"llvmpipe {s}" for s in scenes],
                   body, [False, False, True, True] + [True] * len(scenes))
    for label, tab, a, b, _, _ in comps:
        th = [ratio(f.paper("bruell2018-thesis", tab, a, "total_time", ps, n),
                    f.paper("bruell2018-thesis", tab, b, "total_time", ps, n))
              for ps in ("powerplant", "village") for n in sizes_of([r for r in rows if r["technique"] == a], "nodes")]
        lines.append(f"- {a} against {b}: {span(found.get(a, []))}x here, {verdict(found.get(a, []))}; the thesis "
                     f"{span(th)}x, {verdict(th)}.")
    tex = [ratio(t("UMLAB", n, "texture3d", s), t("MLAB", n, "texture3d", s))
           for s in scenes for n in sizes_of([r for r in rows if r["technique"] == "UMLAB"], "nodes")]
    if any(tex):
        lines.append(f"- UMLAB against MLAB in the 3D texture: {span(tex)}x, {verdict(tex)}.")
    for s in scenes:
        exact = {k[0]: ms(v[s]) for k, v in cases.items() if s in v and k[0] not in plot.OIT_APPROX}
        ppa = {approx_label(v[s]): ms(v[s]) for k, v in cases.items() if s in v and k[0] in PER_PIXEL_ARRAY}
        if exact and ppa:
            fe = min(exact, key=lambda k: (exact[k], k))
            fa = min(ppa, key=lambda k: (ppa[k], k))
            lines.append(f"- {s}: the fastest exact resolve, {fe} ({f_ms(exact[fe])} ms), against the fastest "
                         f"per-pixel-array approximation, {fa} ({f_ms(ppa[fa])} ms): "
                         f"{word(ratio(exact[fe], ppa[fa]))} for the exact one ({f_x(ratio(exact[fe], ppa[fa]))}x).")
    cheap_t, cheap_e = [], []
    for s in scenes:
        imsr = next((v[s] for k, v in cases.items() if k[0] == "BASE-IMS" and s in v), None)
        mlab = [v[s] for k, v in cases.items() if k[0] == "MLAB" and s in v]
        ref = min(mlab, key=lambda r: (int(r["nodes"]), r.get("storage", ""))) if mlab else None
        for k, v in cases.items():
            if k[0] in BLENDS and s in v and (k[0] == "unsorted" or k[3] == "eq7"):
                cheap_t.append(ratio(ms(v[s]), ms(imsr)))
                cheap_e.append(ratio(num(v[s], "rmse"), num(ref, "rmse")))
    if cheap_t:
        lines.append(f"- Unsorted blending and WBOIT (eq7) take {span(cheap_t)}x BASE-IMS's time, at "
                     f"{span(cheap_e)}x the rmse of the smallest MLAB.")
    diffs = [(num(r, "model_max_diff"), plot.oit_label(r), r["scene"]) for r in rows
             if num(r, "model_max_diff") is not None]
    if diffs:
        worst = max(diffs)
        flick = max((num(r, "flicker") or 0.0 for r in rows), default=0.0)
        capped = sum(num(r, "capped_updates") or 0.0 for r in rows)
        lines.append(f"- Against each technique's own CPU model: `model_max_diff` is 0 in "
                     f"{sum(1 for d in diffs if d[0] == 0)} of {len(diffs)} cases, at most "
                     f"{tables.fmt(worst[0], 2)} ({worst[1]} on {worst[2]}); `flicker` at most "
                     f"{tables.fmt(flick, 2)}; capped insertions {capped:.0f}.")
    lines += ["", "The unbounded variants (UMLAB, UAT, UHAT) trade memory bandwidth for compute. On a CPU "
              "rasteriser the nodes sit in cache while `if` runs as masked straight-line code, so only the "
              "extra compute shows, and every per-pixel-array technique inserts under a spinlock that is CPU "
              "work a GPU would hide.", ""]
    return lines


def section_error_vs_time(f):
    name = "error-vs-time"
    lines = ["## Error against time", "",
             "Every technique on every shipped scene.", ""]
    rows = f.rows(name, "oit")
    if not rows:
        return lines + missing(name)
    groups = {}
    for r in rows:
        groups.setdefault((r["scene"], r["view"], res(r)), []).append(r)
    body, ppa_ratio, on_front, wb = [], [], [], []
    for key in sorted(groups, key=lambda k: (scene_key(k[0]), view_key(k[1]))):
        g = groups[key]
        pts = [(ms(r), max(num(r, "rmse") or 0.0, RMSE_FLOOR), plot.oit_label(r), r) for r in g
               if num(r, "rmse") is not None]
        front = plot.pareto_front(pts)
        exact = [r for r in g if r["technique"] not in plot.OIT_APPROX]
        ppa = [r for r in g if r["technique"] in PER_PIXEL_ARRAY]
        fe = min(exact, key=lambda r: (ms(r), r["technique"])) if exact else None
        fa = min(ppa, key=lambda r: (ms(r), plot.oit_label(r))) if ppa else None
        ppa_ratio.append(ratio(ms(fa), ms(fe)))
        on_front += [p[2] for p in front if p[2].split("/")[0] in PER_PIXEL_ARRAY]
        u = next((r for r in g if r["technique"] == "unsorted"), None)
        w = next((r for r in g if r["technique"] == "WBOIT"), None)
        if u and w:
            wb.append((key, ratio(ms(w), ms(u)), num(w, "rmse"), num(u, "rmse")))
        body.append([key[0], key[1], key[2],
                     "; ".join(f"{p[2]} {f_ms(p[0])} ms / {f_err(num(p[3], 'rmse'))}" for p in front),
                     f"{plot.oit_label(fe)} {f_ms(ms(fe))}" if fe else DASH,
                     f"{plot.oit_label(fa)} {f_ms(ms(fa))}" if fa else DASH, f_x(ratio(ms(fa), ms(fe)))])
    r0 = rows[0]
    lines += [f"`presets/{name}.csv` ({f.reps(name, r0)}): the Pareto front of each scene (no technique "
              f"both faster and more exact; `total` ms / rmse, rmse floored at {tables.fmt(RMSE_FLOOR, 1)} so the "
              "exact ones tie), the fastest exact resolve and the fastest per-pixel-array approximation (ms). "
              "The figure: [report/figures/presets/error-vs-time/oit.png]"
              "(report/figures/presets/error-vs-time/oit.png).", ""]
    lines += table(["scene", "view", "resolution", "Pareto front", "fastest exact", "fastest per-pixel array",
                    "array / exact"], body, [False] * 6 + [True])
    lines.append(f"- Per-pixel-array approximations on a front: {', '.join(on_front) if on_front else 'none'}; the "
                 f"fastest of them takes {span(ppa_ratio)}x the fastest exact resolve "
                 f"(against exact, {verdict(ppa_ratio, 'scenes')}).")
    both_worse = [k for k, tr, we, ue in wb if tr and tr > 1 and we is not None and ue is not None and we > ue]
    better = [k for k, tr, we, ue in wb if we is not None and ue is not None and we < ue]
    if wb:
        lines.append(f"- WBOIT against unsorted blending: both slower and less exact on "
                     f"{', '.join(f'{k[0]} {k[1]}' for k in both_worse) or 'no scene'}; more exact on "
                     f"{', '.join(f'{k[0]} {k[1]}' for k in better) or 'no scene'}.")
    deep = [r for r in rows if r["scene"] == "planes-deep"]
    if deep:
        lines.append("- planes-deep, " + res(deep[0]) + ": " + ", ".join(
            f"{plot.oit_label(r)} {f_ms(ms(r))} ms / {f_err(num(r, 'rmse'))}" for r in sorted(deep, key=ms)) + ".")
    lines += ["", "The cheap end of each front is a blend that ignores order; the exact end is the fastest exact "
              "resolve; on this renderer the per-pixel-array approximations fall between, slower than exact "
              "and less exact than it.", ""]
    return lines


def section_lines(f):
    name = "sintorn-lines"
    lines = ["## Lines", "",
             "Hair as line primitives, the Sintorn et al. poster: the `lines` experiment.", ""]
    if not f.run(name):
        return lines + missing(name)
    poster = {int(float(r["size"])): r["paper"] for r in f.paper_pairs(name, "sintorn-poster").values()
              if r["size"] != ""}
    models = {int(float(r["size"])): r["scene"] for r in f.paper_pairs(name, "sintorn-poster").values()
              if r["size"] != ""}
    segs = sizes_of(f.rows(name, "lines"), "segments")
    body, share, rs = [], [], []
    for n in segs:
        ex = f.rows(name, "lines", technique="exact", segments=n)
        sl = {p: f.median(name, "lines", pass_=p, technique="slices", segments=n) for p in
              ("total", "keys", "sort", "blend")}
        exact = ms(ex[0]) if ex else None
        srow = f.rows(name, "lines", technique="slices", segments=n)
        rs.append(ratio(sl["total"], exact))
        share.append(ratio(sl["sort"], sl["total"]))
        body.append([f"{n:,}", f_m(num(ex[0], "total_fragments")) if ex else DASH,
                     field(ex[0], "peak_depth") if ex else DASH, f_ms(exact),
                     f"{f_ms(sl['total'])} ({f_ms(sl['keys'])} / {f_ms(sl['sort'])} / {f_ms(sl['blend'])})",
                     tables.fmt(1000 / sl["total"], 2) if sl["total"] else DASH,
                     f"{tables.fmt(poster[n], 3)} ({models[n]})" if n in poster else DASH,
                     f_err(num(srow[0], "rmse")) if srow else DASH])
    r0 = f.rows(name, "lines")[0]
    lines += [f"`presets/{name}.csv` ({res(r0)}, {f.reps(name, r0)}, {r0.get('slices', '?')} slices): "
              "per-fragment exact OIT against the per-primitive slice sort; the poster's frame rate on its GPU.", ""]
    lines += table(["segments", "fragments", "peak depth", "exact total ms", "slices total ms (keys / sort / blend)",
                    "slices fps", "poster fps", "slices rmse"], body)
    lines.append("- Slices against exact: " + ", ".join(f"{f_x(r)}x at {n:,} segments ({word(r)})"
                                                       for r, n in zip(rs, segs)) + ".")
    lines.append(f"- The sort is {span(share)} of the slices' time.")
    t_lo = f.median(name, "lines", technique="slices", segments=segs[0])
    t_hi = f.median(name, "lines", technique="slices", segments=segs[-1])
    if segs[0] in poster and segs[-1] in poster:
        lines.append(f"- From {segs[0]:,} to {segs[-1]:,} segments ({f_x(segs[-1] / segs[0])}x) the slices' time "
                     f"grows {f_x(ratio(t_hi, t_lo))}x; the poster's frame rate fell "
                     f"{f_x(ratio(poster[segs[0]], poster[segs[-1]]))}x over the same models.")
    lines += ["", "On a GPU the sort's passes are bandwidth-bound and nearly free for small models; on llvmpipe "
              "every pass is CPU work that grows with the data.", ""]
    return lines


def section_scenes(f):
    lines = ["## Scenes", "",
             "Statistics of the shipped scenes as captured (`polygons`, `total_fragments`, `peak_depth`, "
             "`mean_depth`, and the MAX_FRAGS the case used), from the first valid exact case of each scene, "
             "detail, view and resolution in these presets.", ""]
    seen = {}
    for name in ("knowles2014", "knowles2013", "error-vs-time", "capture-storage", "oit-scale"):
        for r in f.rows(name, "oit"):
            if r["technique"] in plot.OIT_APPROX:
                continue
            key = (r["scene"], r.get("detail", ""), r["view"], res(r))
            seen.setdefault(key, (name, r))
    body = []
    for key in sorted(seen, key=lambda k: (scene_key(k[0]), k[1], view_key(k[2]),
                                           [int(x) for x in k[3].split("x")])):
        name, r = seen[key]
        body.append(list(key) + [f_num(num(r, "polygons")), f_num(num(r, "total_fragments")), field(r, "peak_depth"),
                                 tables.fmt(num(r, "mean_depth"), 3), max_frags_used(r), f"`{name}`"])
    lines += table(["scene", "detail", "view", "resolution", "polygons", "fragments", "peak depth", "mean depth",
                    "MAX_FRAGS", "from"], body, [False] * 4 + [True] * 5 + [False])
    return lines


SECTIONS = [section_runs, section_not_ok, section_occupancy, section_sort, section_layout, section_spinlock,
            section_stencil, section_knowles2014, section_resolve_speedups,
            section_knowles2013, section_capture, section_targets, section_scale, section_approx,
            section_error_vs_time, section_lines, section_scenes, section_warmup]


def render(results_dir, paper_dir, shown_dir):
    f = Results(results_dir, paper_dir)
    if not f.runs:
        raise oitres.ResultsError(f"{results_dir}/presets: no oitbench summary CSV")
    lines = [f"# Findings: the reference runs in `{shown_dir}`", "",
             "<!-- Generated by scripts/findings.py from presets/*.csv; do not edit: regenerate. -->", "",
             f"Generated by `scripts/findings.py {shown_dir}` from the CSVs in [presets/](presets/) and the "
             "papers' numbers in [results/published/](../published/); do not edit it by hand. After new "
             f"reference runs: `/usr/bin/python3 scripts/findings.py {shown_dir} -o {shown_dir}/FINDINGS.md` "
             "(`tests/scripts/test_findings.py` fails while this file is stale).", "",
             "Every number is read or computed from those files: medians of the primary clock (`median_ms`) of "
             "valid rows only. Ratios are time ratios, A / B: below 1, A is faster. *Faster* and *slower* are "
             f"computed; *about even* means within {(EVEN_BAND - 1) * 100:.0f}% either way. The same configuration "
             "moves by tens of percent between runs on this shared machine, so read ratios and shapes, not "
             "single milliseconds. How it measures: [docs/measurement.md](../../docs/measurement.md); what each "
             "experiment does: [docs/experiments/](../../docs/experiments/).", ""]
    toc = []
    body = []
    for section in SECTIONS:
        part = section(f)
        title = part[0][3:]
        toc.append(f"- [{title}](#{anchor(title)})")
        body += part
    return "\n".join(lines + toc + [""] + body).rstrip("\n") + "\n"


def anchor(title):
    """GitHub's heading anchor: lower case, punctuation dropped, spaces to hyphens."""
    text = re.sub(r"[^\w\- ]", "", title.lower())
    return text.replace(" ", "-")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("results", help="a results folder with presets/NAME.csv (e.g. results/llvmpipe)")
    ap.add_argument("-o", "--out", help="write here (default: stdout)")
    ap.add_argument("--paper", default=tables.default_paper_dir(),
                    help="folder of the papers' tidy CSVs (default: the repository's results/published)")
    args = ap.parse_args(argv)
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)
    shown = report.shown_path(args.results).replace(os.sep, "/")
    try:
        text = render(args.results, args.paper, shown)
    except oitres.ResultsError as e:
        print(f"findings.py: {e}", file=sys.stderr)
        return 2
    if args.out:
        with open(args.out, "w", encoding="utf-8", newline="\n") as out:
            out.write(text)
    else:
        sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(cli.run(main))
