"""The report page: the library behind scripts/report.py (collect() is shared with findings.py)."""
import collections
import html
import os
import re
import shutil
import string
import struct
import sys
import time
import urllib.parse

from oitbench import ab
from oitbench import compare
from oitbench import casekey
from oitbench import results as oitres
from oitbench import figures as plot
from oitbench import papers as tables
from oitbench import timeaccount

GENERATOR = "oitbench scripts/report.py"
STATUSES = oitres.STATUSES
COMPARE_META = "oitbench-compare"  # <meta name=COMPARE_META content="B against A"> marks a comparison page
# Metadata shown per run, in this order: (column, label).
META_COLUMNS = [("gl_renderer", "GL_RENDERER"), ("gl_vendor", "GL_VENDOR"), ("gl_version", "GL_VERSION"),
                ("backend", "backend"), ("device", "device"), ("lp_num_threads", "LP_NUM_THREADS"),
                ("env", "environment"), ("git_sha", "git sha"), ("hostname", "hostname"),
                ("cpu_model", "CPU"), ("preset", "preset"), ("timer", "primary clock")]
# Images written by `oitbench render --out NAME.png` beside NAME.png, and what each shows.
IMAGE_KINDS = [("", "image"), ("-diff8", "|image \u2212 exact| \u00d7 8"),
               ("-depth", "depth complexity (blue 1 \u2192 red at the peak, log)")]
LONG_REASON = 160


class Input:
    """One summary CSV and its place in the report."""

    def __init__(self, run, rel):
        self.run = run
        self.rel = rel  # path relative to the inputs' common folder, with .csv
        self.anchor = None  # set by Page.claim()


def slug(text):
    return re.sub(r"[^A-Za-z0-9]+", "-", text).strip("-").lower() or "x"


def esc(text):
    return html.escape(str(text), quote=True)


def url(path):
    """A relative path as an href/src value."""
    return esc(urllib.parse.quote(path.replace(os.sep, "/")))


def md_inline(text):
    """tables.py's notes: Markdown `code` spans, the rest plain text."""
    parts = text.split("`")
    return "".join(f"<code>{esc(p)}</code>" if i % 2 else esc(p) for i, p in enumerate(parts))


# ---------------------------------------------------------------------------------------------- inputs

def generated_page(folder):
    """None, or what a page this script wrote in `folder` is: its COMPARE_META text ("B against A") for
    a comparison page, "" for a report."""
    index = os.path.join(folder, "index.html")
    if not os.path.isfile(index):
        return None
    with open(index, encoding="utf-8", errors="replace") as f:
        head = f.read(4000)
    if f'<meta name="generator" content="{GENERATOR}">' not in head:
        return None
    m = re.search(f'<meta name="{COMPARE_META}" content="([^"]*)">', head)
    return html.unescape(m.group(1)) if m else ""


def collect(paths, out_dir, images_dir, pages=None):
    """(inputs, skipped, base): the summary CSVs named or found below the folders, the CSVs passed over
    with the reason, and the inputs' common folder. Folders below them that hold a page this script
    wrote are not searched (a comparison page keeps its ratios as CSV); they go to `pages`, when given,
    as (folder, generated_page(folder)). Raises ResultsError for a missing or unreadable input or when
    nothing is left."""
    found, skipped = [], []
    pages = [] if pages is None else pages
    keep_out = {os.path.realpath(p) for p in (out_dir, images_dir) if p}
    dirs = []
    for p in paths:
        if os.path.isdir(p):
            dirs.append(p)
            for root, subdirs, files in os.walk(p):
                keep = []
                for d in sorted(subdirs):
                    full = os.path.join(root, d)
                    if d.startswith(".") or os.path.realpath(full) in keep_out:
                        continue
                    what = generated_page(full)
                    if what is None:
                        keep.append(d)
                    else:
                        pages.append((full, what))
                subdirs[:] = keep
                found += [(os.path.join(root, f), False) for f in sorted(files) if f.endswith(".csv")]
        elif os.path.exists(p):
            found.append((p, True))
        else:
            raise oitres.ResultsError(f"{p}: no such file or folder")
    base = os.path.commonpath([os.path.abspath(d) for d in dirs] +
                              [os.path.dirname(os.path.abspath(p)) for p, named in found if named] or ["."])
    headers = {}
    for p, _ in found:
        headers[p] = oitres.read_csv(p)
    inputs, seen = [], set()
    for p, named in found:
        header, rows = headers[p]
        rel = os.path.relpath(os.path.abspath(p), base)
        try:
            oitres.check_summary_header(p, header)
        except oitres.ResultsError as e:
            if named:
                raise  # the scripts' usual message (a --raw file, or not oitbench's)
            why = "raw repetitions (--raw)" if oitres.is_raw_header(header) else "not an oitbench summary CSV" + (
                str(e).split("summary CSV", 1)[1] if oitres.is_summary_header(header) else "")
            skipped.append((rel, why))
            continue
        if os.path.realpath(p) in seen:
            continue
        seen.add(os.path.realpath(p))
        # NAME_raw.csv beside NAME.csv, when it is a raw file, makes NAME's parameter columns exact.
        sibling = p[:-len(".csv")] + "_raw.csv" if p.endswith(".csv") else None
        raw_header = headers[sibling][0] if sibling in headers else (
            oitres.read_csv(sibling)[0] if sibling and os.path.isfile(sibling) else [])
        raw_params = oitres.raw_param_columns(raw_header) if oitres.is_raw_header(raw_header) else None
        label = rel[:-len(".csv")] if rel.endswith(".csv") else rel
        inputs.append(Input(oitres.Run(p, header, rows, raw_params, label), rel))
    if not inputs:
        where = ", ".join(paths)
        raise oitres.ResultsError(f"{where}: no oitbench summary CSV found (written by `oitbench run --out`)")
    return inputs, skipped, base


def default_images_dir(paths):
    """images/ in the first folder given, else beside the first CSV; None when there is none."""
    for p in paths:
        if os.path.isdir(p):
            candidate = os.path.join(p, "images")
            return candidate if os.path.isdir(candidate) else None
    candidate = os.path.join(os.path.dirname(os.path.abspath(paths[0])), "images")
    return candidate if os.path.isdir(candidate) else None


# The files a page wrote into its folder, one relative path a line: all a later page there may remove.
WRITTEN_LIST = ".report-files"


def prepare_out_dir(out_dir):
    """An empty or new folder, or a previous report or comparison page, whose files (those it listed in
    WRITTEN_LIST) are removed first; anything else in the folder is left as it is. Returns the time the
    new page starts writing (write_file_list lists what is written after it)."""
    if os.path.exists(out_dir) and not os.path.isdir(out_dir):
        raise oitres.ResultsError(f"{out_dir}: is a file, not a folder; give -o a new or empty folder "
                                  "(report.py never writes over a file)")
    if os.path.isdir(out_dir) and os.listdir(out_dir):
        if generated_page(out_dir) is None:
            raise oitres.ResultsError(f"{out_dir}: not empty and not a previous report; give a new or empty "
                                      "folder with -o")
        remove_previous_page(out_dir)
    os.makedirs(out_dir, exist_ok=True)
    return time.time()


def remove_previous_page(out_dir):
    """Removes the files the previous page listed as its own (only its index.html when it kept no list),
    then the folders they leave empty; a file a user added stays."""
    listed = os.path.join(out_dir, WRITTEN_LIST)
    rels = ["index.html"]
    if os.path.isfile(listed):
        with open(listed, encoding="utf-8") as f:
            rels = [line.rstrip("\n") for line in f if line.strip()]
    root = os.path.realpath(out_dir)
    folders = set()
    for rel in rels:
        path = os.path.realpath(os.path.join(out_dir, rel))
        if os.path.isabs(rel) or not path.startswith(root + os.sep):
            continue  # a list edited to point outside the folder: never followed
        if os.path.isfile(path):
            os.remove(path)
            folders.add(os.path.dirname(path))
    for folder in sorted(folders, key=len, reverse=True):
        while folder.startswith(root + os.sep) and os.path.isdir(folder) and not os.listdir(folder):
            os.rmdir(folder)
            folder = os.path.dirname(folder)
    if os.path.isfile(listed):
        os.remove(listed)


def write_file_list(out_dir, since):
    """Lists every file in out_dir written since `since` (this page's) in WRITTEN_LIST."""
    rels = []
    for folder, _, files in os.walk(out_dir):
        for name in files:
            path = os.path.join(folder, name)
            rel = os.path.relpath(path, out_dir)
            if rel != WRITTEN_LIST and os.path.getmtime(path) >= since - 0.05:  # coarse file clocks
                rels.append(rel)
    with open(os.path.join(out_dir, WRITTEN_LIST), "w", encoding="utf-8", newline="\n") as f:
        f.write("".join(r + "\n" for r in sorted(rels)))


# -------------------------------------------------------------------------------------------- run facts

def case_key(row, params):
    """One case's rows, every pass together."""
    return casekey.key(row, params, with_pass=False, scoped=False)


class Facts:
    """What the page says about one run: metadata values, cases and their statuses, what failed."""

    def __init__(self, run):
        rows = run.rows
        self.meta = []
        for col, label in META_COLUMNS:
            values = distinct(r.get(col, "") for r in rows)
            if values:
                self.meta.append((label, values))
        stamps = sorted(r["timestamp_utc"] for r in rows if r.get("timestamp_utc"))
        self.time_range = (stamps[0], stamps[-1]) if stamps else None
        self.resolutions = sorted({f"{r['width']}x{r['height']}" for r in rows if r.get("width")},
                                  key=lambda s: [int(x) for x in s.split("x") if x.isdigit()])
        cases = collections.OrderedDict()
        for exp in run.experiments():
            params = run.params(exp)
            # A failed case is named by what varies in its experiment here (the rest is the same for all).
            shown = oitres.varying(run.rows_of(exp), params) or params
            for r in run.rows_of(exp):
                cases.setdefault(case_key(r, params), []).append((r, shown))
        self.experiments = collections.Counter()
        self.status = collections.Counter()
        self.failed = []  # (experiment, case, status, reason)
        self.notes = collections.Counter()  # reasons written on valid rows (timer-disagreement, ...)
        for key, members in cases.items():
            total = next((r for r, _ in members if r.get("pass") == "total"), None)
            failing = [r for r, _ in members if not oitres.is_ok(r)]
            row = total if total is not None and not oitres.is_ok(total) else (failing[0] if failing else None)
            status = oitres.status_of(row) if row is not None else "ok"
            self.experiments[key[0]] += 1
            self.status[status] += 1
            if row is not None:
                reason = row.get("reason") or next((r.get("reason") for r in failing if r.get("reason")), "")
                params = members[0][1]
                self.failed.append((key[0], oitres.describe_case(dict(row, **{"pass": "total"}), params),
                                    status, reason))
            else:
                for r, _ in members:
                    if r.get("reason"):
                        self.notes[r["reason"]] += 1
        self.cases = len(cases)


def distinct(values):
    out = []
    for v in values:
        if v and v not in out:
            out.append(v)
    return out


def status_badges(counter, always=True):
    names = STATUSES + sorted(s for s in counter if s not in STATUSES)
    return " ".join(f'<span class="badge {esc(s)}{" zero" if not counter.get(s) else ""}">{esc(s)} '
                    f"{counter.get(s, 0)}</span>" for s in names if always or counter.get(s))


def reason_html(reason):
    if not reason:
        return '<span class="muted">(no reason given)</span>'
    first = reason.strip().splitlines()[0] if reason.strip() else reason
    if len(reason) <= LONG_REASON and "\n" not in reason.strip():
        return esc(reason)
    short = first if len(first) <= LONG_REASON else first[:LONG_REASON - 1] + "\u2026"
    return f"<details><summary>{esc(short)}</summary><pre>{esc(reason.strip())}</pre></details>"


# ------------------------------------------------------------------------------------------------- html

def html_table(header, rows, numeric=(), classes=None):
    """header: text; rows: cells that are already HTML. A column whose name starts with "ours" is
    shaded, so our numbers stand apart from the paper's."""
    numeric = list(numeric) + [False] * (len(header) - len(numeric))
    col_class = []
    for h, n in zip(header, numeric):
        names = (["num"] if n else []) + (["ours"] if h.startswith("ours") else [])
        col_class.append(f' class="{" ".join(names)}"' if names else "")
    out = ['<div class="scroll"><table class="data"><thead><tr>']
    out += [f"<th{c}>{esc(h)}</th>" for h, c in zip(header, col_class)]
    out.append("</tr></thead><tbody>")
    for i, row in enumerate(rows):
        c = classes[i] if classes else ""
        out.append(f'<tr{f" class={c}" if c else ""}>' +
                   "".join(f"<td{k}>{cell}</td>" for cell, k in zip(row, col_class)) + "</tr>")
    out.append("</tbody></table></div>")
    return "".join(out)


def png_size(path):
    """(width, height) from a PNG's IHDR, or None."""
    try:
        with open(path, "rb") as f:
            head = f.read(24)
    except OSError:
        return None
    if len(head) < 24 or head[:8] != b"\x89PNG\r\n\x1a\n":
        return None
    return struct.unpack(">II", head[16:24])


def img_tag(src_rel, abs_path, alt, kind):
    size = png_size(abs_path)
    dims = f' width="{size[0]}" height="{size[1]}"' if size else ""
    return f'<img class="{kind}" src="{url(src_rel)}" alt="{esc(alt)}"{dims}>'


class Page:
    def __init__(self, title, meta=None):
        self.title = title
        self.meta = meta or {}  # more <meta name content> tags
        self.toc = []  # (level, anchor, text)
        self.body = []
        self.anchors = {"broken-images"}

    def claim(self, anchor):
        """`anchor`, or `anchor`-2, -3, ... when it is taken: every id on the page is unique."""
        name, n = anchor, 1
        while name in self.anchors:
            n += 1
            name = f"{anchor}-{n}"
        self.anchors.add(name)
        return name

    def section(self, level, anchor, text, claimed=False):
        anchor = anchor if claimed else self.claim(anchor)
        self.toc.append((level, anchor, text))
        self.body.append(f'<h{level} id="{esc(anchor)}">{esc(text)}</h{level}>')

    def add(self, text):
        self.body.append(text)

    def render(self):
        toc = ['<nav class="toc"><div class="toc-title">Contents</div><ul>']
        for level, anchor, text in self.toc:
            toc.append(f'<li class="l{level}"><a href="#{esc(anchor)}">{esc(text)}</a></li>')
        toc.append("</ul></nav>")
        meta = "".join(f'<meta name="{esc(k)}" content="{esc(v)}">\n' for k, v in sorted(self.meta.items()))
        return string.Template(template("page.html")).substitute(
            generator=GENERATOR, meta=meta, title=esc(self.title), css=template("report.css"), toc="\n".join(toc),
            body="\n".join(self.body), script=template("check.js"))


# The page's skeleton, style and script are files in templates/: page.html (a string.Template), report.css,
# check.js. The script checks the page once everything has loaded: how many images, how many figures,
# which did not decode. The counts go on <body> (the headless-browser test reads them) and a broken image
# is named in a banner at the top, so a reader sees it too.
TEMPLATES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "templates")


def template(name):
    with open(os.path.join(TEMPLATES, name), encoding="utf-8") as f:
        return f.read()


# ------------------------------------------------------------------------------------------- sections

def howto_section(page, have_tables, have_images):
    page.section(2, "how-to-read", "How to read this page")
    items = [
        ("Runs", "one block per CSV file: the driver (GL_RENDERER, vendor, version), backend and device, the "
         "environment that changes a driver's speed, the commit (a sha ending in <code>-dirty</code> was "
         "built from uncommitted code), the machine, when it ran, the preset and resolutions. A case is one "
         "configuration (experiment, variant, resolution, parameters), written as a row per pass; its status "
         "is <span class='badge ok'>ok</span> (matches the CPU reference), <span class='badge invalid'>"
         "invalid</span> (ran, but its result differs from the reference: it carries no time), "
         "<span class='badge unsupported'>unsupported</span> (the driver lacks something), "
         "<span class='badge error'>error</span> or <span class='badge timeout'>timeout</span>. Every case "
         "that is not ok is listed with its reason."),
        ("Figures", "drawn by <code>scripts/plot.py</code> from the valid rows only: medians of the primary "
         "clock with MAD (median absolute deviation) bars; cases left out are named in a note on the figure. "
         "Every valid row is drawn, or named in the figure's note with the reason; bars and points are keyed on "
         "every parameter that tells cases apart, and each pass has one colour in every figure. "
         "Click a figure for its SVG. On a shared 2-core machine the same case moves 20&ndash;30% between "
         "runs: read shapes and ratios, and use <code>scripts/compare.py</code> for differences."),
    ]
    if have_tables:
        items.append(("Paper tables", "<code>scripts/tables.py</code>: each paper table that any run has "
                      "rows for, the paper's numbers and ours side by side. Hardware differs by orders of "
                      "magnitude, so compare the <em>speedup</em> columns (time of the table's baseline / "
                      "time, computed alike for paper and ours), not milliseconds. Each run is matched on its "
                      "own; the paper's rows that run has nothing for are folded away below its table. The run "
                      "opened by default is the one at the table's own preset; beside the table, its figure: "
                      "the paper's speedup (hatched) and ours (solid) per case and technique."))
        items.append(("Fastest technique", "per view and driver, the exact techniques ranked by their resolve "
                      "pass and their total, each as its time over the view's fastest."))
    if have_images:
        items.append(("Rendered images", "<code>oitbench render</code> output: the image, its difference "
                      "to the exact CPU reference amplified 8 times (black is exact) and the depth "
                      "complexity in false colour."))
    page.add('<dl class="howto">' + "".join(f"<dt>{k}</dt><dd>{v}</dd>" for k, v in items) + "</dl>")


def overview_section(page, inputs, facts, skipped):
    """The table of every file, and the metadata every file shares; returns the labels shared."""
    page.section(2, "runs", "Runs")
    total = collections.Counter()
    for f in facts:
        total.update(f.status)
    page.add(f'<p class="lead">{len(inputs)} file(s), {sum(f.cases for f in facts)} cases: '
             f"{status_badges(total)}</p>")
    rows = []
    for inp, f in zip(inputs, facts):
        preset = "; ".join(dict(f.meta).get("preset", [])) or "\u2014"
        rows.append([f'<a href="#{esc(inp.anchor)}">{esc(inp.rel)}</a>',
                     esc(", ".join(sorted(f.experiments))), esc(preset), esc(", ".join(f.resolutions)),
                     str(f.cases), status_badges(f.status, always=False)])
    page.add(html_table(["file", "experiments", "preset", "resolution", "cases", "status"], rows,
                        numeric=[False, False, False, False, True, False]))
    if skipped:
        page.add("<p class='muted'>Not summary CSVs, left out: " +
                 "; ".join(f"<code>{esc(rel)}</code> ({esc(why)})" for rel, why in skipped) + "</p>")
    shared = []
    if len(facts) > 1:
        first = dict(facts[0].meta)
        shared = [label for label, values in facts[0].meta
                  if label != "preset" and all(dict(f.meta).get(label) == values for f in facts[1:])]
        if shared:
            page.add("<h4>The same in every file</h4>" +
                     meta_grid([(label, "; ".join(first[label])) for label in shared]))
    return shared


def meta_grid(pairs):
    return '<dl class="meta">' + "".join(f"<dt>{esc(k)}</dt><dd>{v if isinstance(v, Html) else esc(v)}</dd>"
                                         for k, v in pairs) + "</dl>"


class Html(str):
    """Text that is already HTML (meta_grid does not escape it)."""


def run_block(page, inp, f, shared, out_dir, failures):
    """One file: its metadata (what is not the same in every file), what was not ok, and its figures."""
    page.section(3, inp.anchor, inp.rel, claimed=True)
    meta = [(label, "; ".join(values)) for label, values in f.meta if label not in shared]
    if f.time_range:
        a, b = f.time_range
        meta.append(("timestamp (UTC)", a if a == b else f"{a} \u2013 {b}"))
    meta.append(("resolution", ", ".join(f.resolutions) or "\u2014"))
    meta.append(("cases", f"{f.cases} ({', '.join(f'{e} {n}' for e, n in sorted(f.experiments.items()))})"))
    meta.append(("status", Html(status_badges(f.status, always=False))))
    page.add('<div class="card">' + meta_grid(meta) +
             ("<p class='muted small'>and the values the same in every file (above)</p>" if shared else ""))
    if f.failed:
        page.add(f"<h4>Not ok: {len(f.failed)} case(s)</h4>")
        page.add(html_table(["experiment", "case", "status", "reason"],
                            [[esc(e), esc(c), status_badges({s: 1}, always=False), reason_html(r)]
                             for e, c, s, r in f.failed]))
    if f.notes:
        page.add("<p class='muted'>Notes on valid rows: " +
                 "; ".join(f"{esc(n)} ({k} row(s))" for n, k in sorted(f.notes.items())) + "</p>")
    page.add("</div>")
    return figures_of(page, inp, out_dir, failures)


def figures_of(page, inp, out_dir, failures):
    """Every experiment of one run through plot.py into out_dir/figures/LABEL/; returns how many."""
    count = 0
    for exp in inp.run.experiments():
        rel = os.path.join("figures", *inp.run.label.split("/"), exp)
        stem = os.path.join(out_dir, rel)
        os.makedirs(os.path.dirname(stem), exist_ok=True)
        print(f"report.py: figure: {inp.rel}: {exp}", flush=True)
        try:
            data, fig, lines = plot.draw(inp.run, exp)
            plot.save(fig, stem, ("png", "svg"))
        except Exception as e:  # a plot bug on odd data must not cost the rest of the page
            plot.plt.close("all")
            failures.append(f"{inp.rel}: {exp}: {type(e).__name__}: {e}")
            page.add(f'<p class="note">Figure <code>{esc(exp)}</code> could not be drawn: '
                     f"{esc(type(e).__name__)}: {esc(e)}</p>")
            continue
        count += 1
        drawn, noted = data.counts()
        caption = f"{exp}: {len(data.valid)} valid row(s), {drawn} drawn" + (
            f", {noted} named in the figure's note" if noted else "") + (
            f", {len(lines)} case(s) not plotted (listed above)" if lines else "")
        page.add(f'<figure><a href="{url(rel + ".svg")}">'
                 f"{img_tag(rel + '.png', stem + '.png', f'{exp} figure of {inp.rel}', 'figure')}</a>"
                 f'<figcaption>{esc(caption)} &middot; <a href="{url(rel + ".svg")}">SVG</a></figcaption>'
                 "</figure>")
    return count


def figure_block(page, out_dir, rel, make, alt, kind, caption, failure, failures):
    """Draws `make()` into out_dir/rel.png and .svg and adds it to the page, linked to the SVG, with
    `caption` (HTML). A figure that fails costs nothing else: `failure` (a name, and the HTML of what could
    not be drawn) goes to `failures` and into a note on the page. Returns whether it was drawn."""
    name, what_html = failure
    stem = os.path.join(out_dir, rel)
    os.makedirs(os.path.dirname(stem), exist_ok=True)
    print(f"report.py: figure: {name}", flush=True)
    try:
        plot.save(make(), stem)
    except Exception as e:  # a figure bug on odd data must not cost the rest of the page
        plot.plt.close("all")
        failures.append(f"{name}: {type(e).__name__}: {e}")
        page.add(f'<p class="note">{what_html} could not be drawn: {esc(type(e).__name__)}: {esc(e)}</p>')
        return False
    page.add(f'<figure><a href="{url(rel + ".svg")}">{img_tag(rel + ".png", stem + ".png", alt, kind)}</a>'
             f'<figcaption>{caption} &middot; <a href="{url(rel + ".svg")}">SVG</a></figcaption></figure>')
    return True


def paper_figure(page, table, inp, paper_rows, out_dir, failures):
    """Beside a paper table: its speedups against ours from the run opened by default (plot.py's
    paper_figure), in out_dir/figures/tables/NAME.png and .svg; nothing where no row has both."""
    ours = tables.Ours([inp.run])
    pairs = tables.figure_pairs(table, tables.build_rows(table, paper_rows, ours))
    if not pairs:
        return
    figure_block(page, out_dir, os.path.join("figures", "tables", slug(table.name)),
                 lambda: plot.paper_figure(f"{table.title} [ours: {inp.run.label}]", pairs,
                                           *tables.figure_hardware(table, ours, paper_rows)),
                 f"{table.name}: the paper against ours", "paper-figure",
                 f"{esc(table.name)}: the paper's speedup (hatched) beside ours (solid) over the same baseline, "
                 f"{len(pairs)} pair(s) from <code>{esc(inp.rel)}</code>",
                 (f"{table.name} against {inp.rel}", f"The figure of <code>{esc(table.name)}</code>"), failures)


def time_section(page, inputs):
    """Where the runs' time went (schema 6's time account): one line per file, preset and experiment with
    the cases' wall time and the shares of timed samples, compile, warm-up, reference and validation,
    scene and other. Nothing where no file has the account (older schemas)."""
    rows = []
    for inp in inputs:
        for (preset, exp), acc in timeaccount.accounts(inp.run.rows).items():
            rows.append([f'<a href="#{esc(inp.anchor)}">{esc(inp.rel)}</a>', esc(preset or "\u2014"), esc(exp),
                         str(acc.cases), f"{acc.wall:.1f}"] +
                        [f"{acc.share(name):.0f}" for name, _ in timeaccount.GROUPS])
    if not rows:
        return 0
    page.section(2, "time", "Where the time went")
    page.add("<p>Each case's wall time (<code>case_wall_s</code>, on its total row) split into phases "
             "(<code>phase_*_s</code>; docs/measurement.md): the shares below are % of the cases' wall time. "
             "The run's own start and the writing of rows are in oitbench's closing line on stderr, not here.</p>")
    page.add(html_table(["file", "preset", "experiment", "cases", "wall s"] +
                        [f"{name} %" for name, _ in timeaccount.GROUPS], rows,
                        numeric=[False, False, False, True, True] + [True] * len(timeaccount.GROUPS)))
    return len(rows)


def fastest_section(page, inputs, out_dir, failures):
    """The fastest exact technique per view and driver: for each driver the run with the most views that
    rank two or more exact techniques (then the most cases): its figure and its table. Returns 1 when
    drawn, else 0."""
    best = {}
    for inp in inputs:
        entries = plot.fastest_table([inp.run])
        if not entries:
            continue
        driver = entries[0]["driver"]
        score = (len(entries), sum(len(e["ranked"]["total"]) for e in entries))
        if driver not in best or score > best[driver][0]:
            best[driver] = (score, inp, entries)
    if not best:
        return 0
    page.section(2, "fastest", "Fastest technique per view")
    chosen = [best[d] for d in sorted(best)]
    entries = [e for _, _, es in chosen for e in es]
    page.add("<p>Per driver, the run with the most views that rank two or more exact techniques (" +
             ", ".join(f"<code>{esc(inp.rel)}</code>" for _, inp, _ in chosen) + "): every exact technique of each "
             "view, by the median of its resolve pass and of its total. Approximate techniques (an error above "
             "the floor, or an approximate family) are left out; see each run's figure for error against time."
             "</p>")
    figure_block(page, out_dir, os.path.join("figures", "fastest"), lambda: plot.fastest_figure(entries),
                 "fastest exact technique per view", "summary-figure",
                 "time / the view's fastest exact technique, per pass and driver",
                 ("fastest technique per view", "The fastest-technique figure"), failures)
    page.add(html_table(plot.FASTEST_HEADER, [[esc(c) for c in line] for line in plot.fastest_lines(entries)],
                        numeric=[False, False, False, False, True, False, True]))
    return 1


def ab_comparisons(dirs):
    """(label, folder, [ab.csv paths], SUMMARY.txt or None) for each A/B comparison under `dirs` (scripts/ab.py
    out folders): a folder of trials (trial-*/ab.csv, with ab.py --summarize's SUMMARY.txt) is one comparison,
    as is a lone ab.csv."""
    found = []
    for top in dirs:
        for root, subdirs, files in os.walk(top):
            subdirs.sort()
            trials = sorted((os.path.join(root, d, "ab.csv") for d in subdirs
                             if d.startswith("trial-") and os.path.isfile(os.path.join(root, d, "ab.csv"))),
                            key=lambda q: [int(t) if t.isdigit() else t for t in re.split(r"(\d+)", q)])
            if trials:
                summary = os.path.join(root, "SUMMARY.txt")
                found.append((os.path.relpath(root, os.path.dirname(os.path.normpath(top))), root, trials,
                              summary if os.path.isfile(summary) else None))
                subdirs[:] = [d for d in subdirs if not d.startswith("trial-")]
            elif "ab.csv" in files:
                found.append((os.path.relpath(root, os.path.dirname(os.path.normpath(top))), root,
                              [os.path.join(root, "ab.csv")], None))
    return found


def ab_section(page, dirs, out_dir, failures):
    """The A/B comparisons (scripts/ab.py, scripts/ab_bench.sh) under `dirs`: each one's summary or table
    and a figure of its paired ratios. Returns how many comparisons were shown."""
    comparisons = ab_comparisons(dirs)
    if not comparisons:
        return 0
    page.section(2, "ab", "A/B comparisons")
    page.add("<p>Whole runs of two configurations alternated in rounds A B B A &hellip; "
             "(<code>scripts/ab.py</code>; repeated trials by <code>scripts/ab_bench.sh</code>), compared round "
             "pair by round pair: the ratio is the median of B/A over the pairs, its interval the order statistics "
             "of those ratios, a case is flagged when the interval lies wholly beyond &plusmn;1%. See "
             "docs/ab-measurements.md for what each comparison ran.</p>")
    for label, folder, paths, summary in comparisons:
        page.section(3, "ab-" + slug(label), label)
        entries, rows_html = [], []
        for path in paths:
            rows = ab.read_table(path)
            trial = os.path.basename(os.path.dirname(path)) if len(paths) > 1 else ""
            for r in rows:
                ratios, lo, hi = r["pair_ratios"], r["ci_low"], r["ci_high"]
                name = f"{r['case']} {r['pass']}" + (f" ({trial})" if trial else "")
                entries.append((name, ratios, lo, hi, r["ratio"], r.get("flagged") == "1"))
                if not trial:
                    rows_html.append([esc(r["case"]), esc(r["pass"]), f"{r['ratio']:.3f}",
                                      f"{lo:.3f}&ndash;{hi:.3f}" if lo is not None and hi is not None else "&mdash;",
                                      esc(r.get("noise_pct", "")), esc(r.get("verdict", "")), esc(r.get("pairs", ""))])
        if summary:
            page.add(f"<pre>{esc(oitres.read_text(summary).strip())}</pre>")
        if rows_html:
            page.add(html_table(["case", "pass", "B / A", "interval", "noise %", "verdict", "round pairs"],
                                rows_html, numeric=[False, False, True, False, True, False, True]))
        flagged = sum(e[5] for e in entries)
        figure_block(page, out_dir, os.path.join("figures", "ab", slug(label)),
                     lambda: ab.figure(plot.plt, entries, f"{label}: {flagged} of {len(entries)} flagged",
                                       "B / A: paired ratio per round pair (|), median (o) and interval (line; "
                                       "red: flagged)"),
                     "A/B " + label, "summary-figure", esc(label),
                     (f"A/B {label}", f"The A/B figure of <code>{esc(label)}</code>"), failures)
    return len(comparisons)


def tables_section(page, inputs, paper_dir, shown_paper_dir, out_dir=None, failures=None):
    """The paper tables with any of our rows, one per (table, run) with rows, and beside each the figure
    of the paper's speedups against ours (the run opened by default); returns how many tables."""
    failures = [] if failures is None else failures
    page.section(2, "tables", "Paper tables")
    if not os.path.isdir(paper_dir):
        page.add(f'<p class="note">The papers\' tables are not here: no folder <code>{esc(shown_paper_dir)}'
                 "</code>. Give <code>--paper DIR</code> (the tidy paper CSVs, as for "
                 "<code>scripts/tables.py</code>).</p>")
        return 0
    try:
        paper_rows = tables.load_paper(paper_dir)
    except oitres.ResultsError as e:
        page.add(f'<p class="note">The papers\' tables could not be read: {esc(e)}</p>')
        return 0
    page.add(f"<p class='muted'>Paper tables from <code>{esc(shown_paper_dir)}</code>.</p>")
    ours = [(inp, tables.Ours([inp.run])) for inp in inputs]
    count = 0
    for table in tables.TABLES:
        found = []
        for inp, o in ours:
            rows = tables.build_rows(table, paper_rows, o)
            matched = sum(1 for r in rows if r["ours_cases"])
            if matched:
                found.append((matched, inp, tables.table_layout(table, rows, o, paper_rows)))
        if not found:
            continue
        count += 1
        page.section(3, "table-" + slug(table.name), table.title)
        # Open by default: the run of the preset that reruns the paper's table (knowles2014, not its quick
        # variant), else the one with most rows matched.
        def rank(item):
            matched, inp, _ = item
            presets = {r.get("preset", "") for r in inp.run.rows}
            return (bool(presets & set(table.presets)), matched)
        default = max(found, key=rank)
        for matched, inp, layout in found:
            is_open = (matched, inp) == default[:2]
            notes = "".join(f"<p class='muted'>{md_inline(n)}</p>" for n in layout.notes)
            # The rows with ours first; the paper's other rows stay one click away, in the paper's order.
            mine = [[esc(c) for c in row] for row, ok in zip(layout.cells, layout.ours_found) if ok]
            rest = [[esc(c) for c in row] for row, ok in zip(layout.cells, layout.ours_found) if not ok]
            others = (f"<details><summary>the paper's {len(rest)} other row(s), with none of ours</summary>"
                      f"{html_table(layout.header, rest, layout.numeric, ['unmatched'] * len(rest))}</details>"
                      if rest else "")
            page.add(f'<details class="table-run"{" open" if is_open else ""}><summary>ours from '
                     f"<code>{esc(inp.rel)}</code>: {matched} of {len(layout.cells)} rows matched</summary>"
                     f"{notes}{html_table(layout.header, mine, layout.numeric)}{others}</details>")
        paper_figure(page, table, default[1], paper_rows, out_dir, failures)
    if not count:
        page.add("<p class='muted'>No run has rows that a paper table compares with.</p>")
    return count


def gallery_section(page, images_dir, out_dir):
    """Every PNG below images_dir, grouped by name (NAME.png, NAME-diff8.png, NAME-depth.png), copied
    into out_dir/images; NAME.csv (the case's row) gives the caption. Returns how many images."""
    pngs = []
    for root, subdirs, files in os.walk(images_dir):
        subdirs[:] = sorted(d for d in subdirs if not d.startswith("."))
        pngs += [os.path.relpath(os.path.join(root, f), images_dir) for f in sorted(files) if f.endswith(".png")]
    page.section(2, "images", "Rendered images")
    if not pngs:
        page.add("<p class='muted'>The images folder holds no PNG.</p>")
        return 0
    groups = collections.OrderedDict()
    for rel in pngs:
        stem = rel[:-len(".png")]
        base, kind = stem, ""
        for suffix, _ in IMAGE_KINDS[1:]:
            if stem.endswith(suffix):
                base, kind = stem[:-len(suffix)], suffix
        groups.setdefault(base, []).append((kind, rel))
    order = {k: i for i, (k, _) in enumerate(IMAGE_KINDS)}
    for base in sorted(groups):
        page.section(3, "img-" + slug(base), base)
        caption = render_caption(os.path.join(images_dir, base + ".csv"))
        if caption:
            page.add(f"<p class='muted'>{caption}</p>")
        cells = []
        for kind, rel in sorted(groups[base], key=lambda kr: (order.get(kr[0], 9), kr[1])):
            dest = os.path.join(out_dir, "images", rel)
            os.makedirs(os.path.dirname(dest), exist_ok=True)
            shutil.copyfile(os.path.join(images_dir, rel), dest)
            what = dict(IMAGE_KINDS).get(kind, "")
            src = os.path.join("images", rel)
            cells.append(f'<figure><a href="{url(src)}">{img_tag(src, dest, rel, "render")}</a>'
                         f"<figcaption>{esc(what)}<br><code>{esc(os.path.basename(rel))}</code></figcaption>"
                         "</figure>")
        page.add('<div class="gallery">' + "".join(cells) + "</div>")
    return len(pngs)


def render_caption(csv_path):
    """'BASE-IS on hairball rev, 256x256: ok, total 812 ms, max error 2e-08' from render's CSV row."""
    if not os.path.isfile(csv_path):
        return ""
    try:
        header, rows = oitres.read_csv(csv_path)
    except oitres.ResultsError:
        return ""
    if not rows or not oitres.is_summary_header(header):
        return ""
    row = next((r for r in rows if r.get("pass") == "total"), rows[0])
    what = row.get("technique") or row.get("variant") or "?"
    where = " ".join(x for x in (row.get("scene"), row.get("view")) if x)
    parts = [f"{esc(what)}" + (f" on {esc(where)}" if where else "") +
             (f", {esc(row['width'])}x{esc(row['height'])}" if row.get("width") else "") + ":",
             status_badges({oitres.status_of(row): 1}, always=False)]
    facts = []
    for col, label, unit in (("median_ms", "total", " ms"), ("max_abs_error", "max error", ""),
                             ("rmse", "RMSE", ""), ("peak_depth", "peak depth", "")):
        x = oitres.to_float(row.get(col))
        if x is not None:
            facts.append(f"{label} {tables.fmt(x, 4) if unit else f'{x:.3g}'}{unit}")
    if row.get("reason"):
        facts.append(esc(row["reason"].strip().splitlines()[0][:LONG_REASON]))
    return " ".join(parts) + " " + esc(", ".join(facts)) if facts else " ".join(parts)


def across_section(page, paths, pages, out_dir):
    """A results root holding several driver folders (RESULTS/DRIVER/presets/): links to the comparison
    pages found below it, or the command that writes one."""
    drivers = []
    for p in paths:
        if os.path.isdir(p):
            drivers += [os.path.join(p, d) for d in sorted(os.listdir(p))
                        if os.path.isdir(os.path.join(p, d, "presets")) and generated_page(os.path.join(p, d)) is None]
    comparisons = [(folder, what) for folder, what in pages if what]
    if len(drivers) < 2 and not comparisons:
        return
    page.section(2, "across-drivers", "Across drivers")
    if len(drivers) >= 2:
        page.add(f"<p>{len(drivers)} driver folders: " +
                 ", ".join(f"<code>{esc(os.path.basename(d))}/</code>" for d in drivers) + ".</p>")
    if comparisons:
        page.add("<ul>" + "".join(
            f'<li><a href="{url(os.path.relpath(os.path.join(folder, "index.html"), out_dir))}">{esc(what)}</a>'
            f" (<code>{esc(os.path.basename(folder))}/</code>): per-case ratios with intervals</li>"
            for folder, what in comparisons) + "</ul>")
    else:
        a = drivers[0]
        cmds = [f"/usr/bin/python3 scripts/report.py --compare {shown_path(a)} {shown_path(b)} -o "
                f"{shown_path(os.path.join(os.path.dirname(a), 'compare-' + os.path.basename(a) + '-' + os.path.basename(b)))}"
                for b in drivers[1:]]
        page.add("<p class='muted'>No comparison page here yet. Per-case ratios with intervals, one page per pair: "
                 + "".join(f"<br><code>{esc(c)}</code>" for c in cmds) + "</p>")


# --------------------------------------------------------------------------------- cross-run comparison
# scripts/report.py --compare A B -o DIR: the presets both folders ran, case by case, through compare.py.

# How each verdict class reads in the tables; compare.py's full sentence is the cell's tooltip.
KIND_LABELS = {compare.NO_DIFFERENCE: "no measurable difference", compare.IN_BAND: "inside the noise band",
               compare.OVERLAP: "repetitions overlap", compare.CHANGED: "changed"}
# Run columns the header does not show as a row of their own.
SHOWN_ELSEWHERE = {"preset": "each preset is a section", "timestamp_utc": "shown as a range"}


class Side:
    """One results folder: its presets, RESULTS/presets/NAME.csv (or NAME.csv in the folder itself) with
    NAME_raw.csv when there is one. Raises ResultsError naming the folder or file that is not right."""

    def __init__(self, path):
        self.path = path
        if not os.path.exists(path):
            raise oitres.ResultsError(f"{path}: no such folder")
        if not os.path.isdir(path):
            raise oitres.ResultsError(f"{path}: not a folder; --compare takes two results folders, each with "
                                      "presets/NAME.csv (and NAME_raw.csv), as scripts/reference_runs.sh writes them")
        sub = os.path.join(path, "presets")
        self.folder = sub if os.path.isdir(sub) else path
        summaries, raws = {}, {}
        for f in sorted(os.listdir(self.folder)):
            p = os.path.join(self.folder, f)
            if not f.endswith(".csv") or not os.path.isfile(p):
                continue
            header = oitres.read_header(p)
            if oitres.is_summary_header(header):
                summaries[f[:-len(".csv")]] = p
            elif oitres.is_raw_header(header):
                raws[f[:-len(".csv")]] = p
            else:
                raise oitres.ResultsError(f"{p}:1: not an oitbench summary or --raw CSV (no experiment and "
                                          "median_ms columns, nor rep and cpu_ms)")
        if not summaries:
            raise oitres.ResultsError(f"{self.folder}: no oitbench summary CSV here (presets/NAME.csv, "
                                      "written by `oitbench run --out`)")
        self.presets, self.raw = {}, {}  # NAME: oitres.Run; NAME: its raw file or None
        for name, p in summaries.items():
            raw = raws.get(name + "_raw")
            header, rows = oitres.read_csv(p)
            oitres.check_summary_header(p, header)
            raw_params = oitres.raw_param_columns(oitres.read_header(raw)) if raw else None
            self.presets[name] = oitres.Run(p, header, rows, raw_params)
            self.raw[name] = raw
        self.orphans = [os.path.basename(p) for n, p in raws.items()
                        if not (n.endswith("_raw") and n[:-len("_raw")] in summaries)]
        self.rows = [r for name in sorted(self.presets) for r in self.presets[name].rows]
        self.name = self.label = None  # set by name_sides()

    def values(self, column):
        return distinct(r.get(column, "") for r in self.rows)


def name_sides(sides, labels):
    """Each side's folder name (its own name, or its path from the two folders' common parent when the
    names are the same) and label: --labels, else each side's driver where it ran one (schema 1 files
    do not record it) or its folder name; the folder names when those are the same; else A and B."""
    folders = [os.path.abspath(s.path) for s in sides]
    names = [os.path.basename(f) for f in folders]
    if names[0] == names[1]:
        common = os.path.commonpath(folders)
        names = [os.path.relpath(f, common) if f != common else os.path.basename(f) for f in folders]
    for s, name in zip(sides, names):
        s.name = name
    if not labels:
        drivers = [s.values("driver") for s in sides]
        labels = [d[0] if len(d) == 1 else s.name for d, s in zip(drivers, sides)]
        if labels[0] == labels[1]:
            labels = names if names[0] != names[1] else ["A", "B"]
    names = labels
    for s, name in zip(sides, names):
        s.label = name
        for run in s.presets.values():
            run.label = name


class Paired:
    """One preset both sides ran: compare.py's comparisons, and the cases it could not compare."""

    def __init__(self, name, sides, stats):
        self.name = name
        self.runs = [s.presets[name] for s in sides]
        self.comparisons, _, self.params_of, self.notes = compare.compare(self.runs, [s.raw[name] for s in sides],
                                                                          stats)
        self.counts = compare.tally(self.comparisons)
        self.pass_rank = {}
        for run in self.runs:
            for r in run.rows:
                self.pass_rank.setdefault((r["experiment"], r["pass"]), len(self.pass_rank))
        self.experiments = distinct(e for run in self.runs for e in run.experiments())
        # Cases some pass of which was not compared: on one side only, or not ok on one side (or both).
        compared = {c.key for c in self.comparisons}
        self.by_side = [collections.OrderedDict() for _ in self.runs]  # {case (key less pass): [rows]}
        self.missing = collections.OrderedDict()  # {case: [passes not compared]}
        for cases, run in zip(self.by_side, self.runs):
            for r in run.rows:
                key = compare.case_key(r, self.params_of[r["experiment"]])
                case = key[:2] + key[3:]
                cases.setdefault(case, []).append(r)
                if key not in compared:
                    passes = self.missing.setdefault(case, [])
                    if key[2] not in passes:
                        passes.append(key[2])

    def order(self, key):
        """A case's passes together, in the order the runs wrote them: variant, parameters, resolution, pass."""
        return ([oitres.sort_key(v) for v in (key[1],) + key[5:] + (key[3], key[4])],
                self.pass_rank.get((key[0], key[2]), 0))

    def differing(self, exp):
        """[(field, [A's values, B's values])] for the key fields of `exp` whose values differ between the
        sides (a parameter scoped away from a row counts as empty), each side's values as text."""
        fields = [("variant", lambda r: r.get("variant", "")),
                  ("resolution", lambda r: f"{r.get('width', '')}x{r.get('height', '')}")]
        fields += [(p, lambda r, p=p: r.get(p, "") if oitres.applies(p, r) else "") for p in self.params_of[exp]]
        out = []
        for name, get in fields:
            values = [sorted({get(r) for r in run.rows_of(exp)}, key=oitres.sort_key) for run in self.runs]
            if values[0] != values[1]:
                shown = ["; ".join(v or "(empty)" for v in vs[:8]) + ("; \u2026" if len(vs) > 8 else "") for vs in values]
                out.append((name, shown))
        return out


def fmt_ratio(x):
    return f"{x:.2f}" if abs(x) < 10 else f"{x:.3g}"


def badge(status):
    return f'<span class="badge {esc(status)}">{esc(status)}</span>'


def verdict_html(c):
    if c.kind == compare.CHANGED:
        label = c.verdict.lower()
    elif c.kind == compare.IN_BAND:
        label = f"inside the between-run noise band ({c.band:.2f}x)"
    elif c.kind == compare.OVERLAP:
        label = f"beyond the band ({c.band:.2f}x), repetitions overlap"
    else:
        label = KIND_LABELS[c.kind]
    extra = f" {c.verdict.lower()}" if c.kind == compare.CHANGED else ""
    return f'<span class="verdict {c.kind}{extra}" title="{esc(c.verdict)}">{esc(label)}</span>'


def side_cell(rows):
    """What one side has for a case that was not compared: nothing, ok, or its status and reason."""
    if not rows:
        return '<span class="muted">not in this run</span>'
    bad = [r for r in rows if not oitres.is_ok(r)]
    if not bad:
        total = next((r for r in rows if r.get("pass") == "total"), rows[0])
        ms = oitres.to_float(total.get("median_ms"))
        return f'<span class="case">{badge("ok")}' + (f" {esc(compare.fmt_ms(ms))} ms" if ms is not None
                                                       else " (no median)") + "</span>"
    row = next((r for r in bad if r.get("pass") == "total"), bad[0])
    return badge(oitres.status_of(row)) + " " + reason_html(row.get("reason", ""))


def counts_cells(n):
    return [str(n[compare.NO_DIFFERENCE]), str(n[compare.IN_BAND]), str(n[compare.OVERLAP]),
            str(n["slower"]), str(n["faster"])]


def sides_section(page, sides):
    """The header: for each side, the driver and everything else that identifies the run."""
    a, b = sides
    columns = ["driver"] + [c for c in oitres.RUN_COLUMNS if c != "driver" and c not in SHOWN_ELSEWHERE]
    columns.append("timer")  # a ratio of two rows is of their primary clocks
    labels = dict(META_COLUMNS)
    described = {c["name"]: c["description"] for c in oitres.SCHEMA["summary_columns"]}
    rows, classes = [], []

    def add(label, values, title=""):
        cells = [v if isinstance(v, Html) else esc(v) for v in values]
        rows.append([f'<span title="{esc(title)}">{esc(label)}</span>' if title else esc(label)] + cells)
        classes.append("differs" if values[0] != values[1] else "")

    add("folder", [f"{s.name}/" + ("presets/" if s.folder != s.path else "") for s in sides])
    for col in columns:
        add(labels.get(col, col), ["; ".join(s.values(col)) or "(not recorded)" for s in sides], described.get(col, ""))
    ranges, cases = [], []
    for s in sides:
        stamps = sorted(s.values("timestamp_utc"))
        ranges.append(f"{stamps[0]} \u2013 {stamps[-1]}" if stamps else "(not recorded)")
        facts = [Facts(run) for run in s.presets.values()]
        status = sum((f.status for f in facts), collections.Counter())
        cases.append(Html(f"{sum(f.cases for f in facts)} " + status_badges(status, always=False)))
    add("timestamps (UTC)", ranges)
    add("presets", [f"{len(s.presets)}: " + ", ".join(sorted(s.presets)) for s in sides])
    add("cases", cases)
    page.section(2, "runs", "The two runs")
    page.add(html_table(["", f"A: {a.label}", f"B: {b.label}"], rows, classes=classes))
    page.add("<p class='muted small'>Highlighted rows differ between the two sides. Hover a name for its "
             "meaning (docs/csv-schema.md).</p>")
    for s in sides:
        if s.orphans:
            page.add(f"<p class='muted'>{esc(s.label)}: raw files without their summary, left out: " +
                     ", ".join(f"<code>{esc(o)}</code>" for o in s.orphans) + "</p>")


def compare_howto(page, stats, sides):
    a, b = (s.label for s in sides)
    page.section(2, "how-to-read", "How to read this page")
    items = [
        ("Ratio", f"per case, the median time on <b>{esc(b)}</b> over the median on <b>{esc(a)}</b> (each row's "
         "primary clock): below 1, B is faster. A case is the same experiment, variant, pass, resolution and "
         "every parameter the case uses; the run columns above (driver, commit, machine) are not part of it."),
        ("95% CI", "a bootstrap over the repetitions where both sides have their raw files "
         f"(NAME_raw.csv; {stats.bootstrap} resamples, seed {stats.seed}), else from each median's MAD."),
        ("Verdict", "<b>no measurable difference</b>: the interval includes 1. <b>inside the between-run noise "
         "band</b>: the interval excludes 1, so the two runs differ, but by less than identical code moves "
         f"between runs (at least {stats.min_effect:g}x, wider for cases with noisy repetitions): not "
         "attributable to the driver or the code from one run of each. <b>beyond the band, repetitions "
         "overlap</b>: not attributable either. <span class='verdict changed slower'>slower</span> / "
         "<span class='verdict changed faster'>faster</span>: changed (interval clear of 1, ratio beyond the "
         "band, repetitions apart). Hover a verdict for compare.py's sentence."),
        ("Figures", "<code>scripts/compare.py</code>'s: each case's ratio with its interval on a log axis, the "
         "noise band in grey, changed cases ringed in red. Click one for its SVG."),
        ("Not compared", "cases on one side only, or not ok on one side, with each side's status and reason. "
         "Where cases of an experiment do not join, the key fields whose values differ are named."),
    ]
    page.add('<dl class="howto">' + "".join(f"<dt>{k}</dt><dd>{v}</dd>" for k, v in items) + "</dl>")


def summary_section(page, pairs, sides, only, stats):
    page.section(2, "summary", "Summary")
    every = [c for p in pairs for c in p.comparisons]
    page.add(f'<p class="lead">{len(pairs)} preset(s) in both folders. '
             f"{esc(compare.summary_text(every, stats.min_effect))}.</p>")
    rows = []
    for p in pairs:
        rows.append([f'<a class="case" href="#{esc(p.anchor)}">{esc(p.name)}</a>', str(len(p.comparisons))] + counts_cells(p.counts)
                    + [str(len(p.missing))])
    for s, names in zip(sides, only):
        for name in names:
            rows.append([f'<span class="case">{esc(name)}</span>', f'<span class="muted">only in {esc(s.label)}</span>'] + [""] * 5 +
                        [str(Facts(s.presets[name]).cases)])
    page.add(html_table(["preset", "compared", "no measurable difference", "inside the noise band",
                         "repetitions overlap", "slower", "faster", "cases not compared"], rows,
                        numeric=[False] + [True] * 7))


def preset_block(page, p, sides, out_dir, stats, failures):
    """One preset: per experiment its ratio table and figures, then the cases not compared."""
    a, b = sides
    page.section(3, p.anchor, p.name, claimed=True)
    page.add(f"<p>{esc(compare.summary_text(p.comparisons, stats.min_effect))}.</p>")
    fig_rel = os.path.join("figures", p.name)
    fig_dir = os.path.join(out_dir, fig_rel)
    os.makedirs(fig_dir, exist_ok=True)
    if p.comparisons:
        compare.write_csv(os.path.join(fig_dir, "compare.csv"), p.comparisons, p.params_of)
        page.add(f"<p class='muted small'>The ratios as CSV: <a href=\"{url(os.path.join(fig_rel, 'compare.csv'))}\">"
                 f"{esc(os.path.join(fig_rel, 'compare.csv'))}</a></p>")
    n_figures = 0
    for exp in p.experiments:
        comps = sorted((c for c in p.comparisons if c.key[0] == exp), key=lambda c: p.order(c.key))
        if not comps:
            continue
        params = p.params_of[exp]
        constant = compare.constant_fields([c.key for c in comps], params)
        shared = compare.shared_text(comps[0].key, params, constant)
        page.section(4, f"{p.anchor}-{slug(exp)}", exp)
        mad = sum(1 for c in comps if c.ci_method != "bootstrap")
        how = ("intervals from a bootstrap over the repetitions" if not mad else "intervals from the MADs"
               if mad == len(comps) else "intervals from a bootstrap over the repetitions (\u2020: from the MADs)")
        page.add(f"<p class='muted'>{len(comps)} comparison(s), {how}" +
                 (f"; every case: <code>{esc(shared)}</code>" if shared else "") + "</p>")
        rows, classes = [], []
        for c in comps:
            rows.append([f'<span class="case">{esc(compare.describe_key(c.key, params, constant))}</span>',
                         esc(compare.fmt_ms(c.base.median)),
                         esc(compare.fmt_ms(c.other.median)), f"{fmt_ratio(c.ratio)}x",
                         f"[{fmt_ratio(c.ci[0])}, {fmt_ratio(c.ci[1])}]" +
                         ("\u2020" if c.ci_method != "bootstrap" and mad < len(comps) else ""),
                         f"{c.band:.2f}x", verdict_html(c)])
            classes.append(c.kind)
        page.add(html_table(["case", f"A ms ({a.label})", f"B ms ({b.label})", "B / A", "95% CI", "noise band",
                             "verdict"], rows, numeric=[False, True, True, True, True, True, False], classes=classes))
        print(f"report.py: figure: {p.name}: {exp}", flush=True)
        try:
            written = compare.draw_figures(fig_dir, p.runs, comps, p.params_of, stats, order=p.order)
        except Exception as e:  # a figure bug on odd data must not cost the rest of the page
            plot.plt.close("all")
            failures.append(f"{p.name}: {exp}: {type(e).__name__}: {e}")
            page.add(f'<p class="note">Figure <code>{esc(exp)}</code> could not be drawn: '
                     f"{esc(type(e).__name__)}: {esc(e)}</p>")
            continue
        for path in written:
            if not path.endswith(".png"):
                continue
            rel = os.path.join(fig_rel, os.path.basename(path))
            svg = rel[:-len(".png")] + ".svg"
            n_figures += 1
            page.add(f'<figure><a href="{url(svg)}">{img_tag(rel, path, f"{exp} ratios of {p.name}", "figure")}</a>'
                     f'<figcaption>{esc(exp)}: {esc(b.label)} / {esc(a.label)} per case, 95% CI, noise band '
                     f'&middot; <a href="{url(svg)}">SVG</a></figcaption></figure>')
    if p.missing:
        page.section(4, f"{p.anchor}-not-compared", "not compared")
        rows = []
        for case, passes in p.missing.items():
            exp = case[0]
            key = case[:2] + ("total",) + case[2:]
            rows.append([esc(exp), esc(compare.describe_key(key, p.params_of[exp])), esc(", ".join(passes))] +
                        [side_cell(cases.get(case, [])) for cases in p.by_side])
        page.add(f"<p>{len(p.missing)} case(s) on one side only or not ok on one side.</p>")
        for exp in distinct(case[0] for case in p.missing):
            one_side = any(not cases.get(case) for case in p.missing if case[0] == exp for cases in p.by_side)
            differing = p.differing(exp) if one_side else []
            if differing:
                page.add(f"<p class='note'>{esc(exp)}: cases on one side only. The key values that differ between "
                         "the sides: " + "; ".join(
                             f"<code>{esc(name)}</code> ({esc(a.label)}: {esc(va)} | {esc(b.label)}: {esc(vb)})"
                             for name, (va, vb) in differing) + "</p>")
        page.add(html_table(["experiment", "case", "passes", a.label, b.label], rows))
    for n in p.notes:
        page.add(f"<p class='muted'>Note: {esc(n)}</p>")
    return n_figures


def build_compare(args):
    sides = [Side(path) for path in args.compare]
    name_sides(sides, args.labels.split(",") if args.labels else None)
    out = os.path.realpath(args.out_dir)
    for s in sides:
        for inside in (os.path.realpath(s.path), os.path.realpath(s.folder)):
            if out == inside or inside.startswith(out + os.sep):
                raise oitres.ResultsError(f"{args.out_dir}: the page would overwrite its own inputs ({s.path}); "
                                          "give -o a folder of its own (e.g. RESULTS/compare-A-B)")
    a, b = sides
    pairs = [Paired(name, sides, args) for name in sorted(set(a.presets) & set(b.presets))]
    only = [sorted(set(s.presets) - set(o.presets)) for s, o in ((a, b), (b, a))]
    since = prepare_out_dir(args.out_dir)
    page = Page(args.title or f"oitbench comparison: {b.label} against {a.label}",
                meta={COMPARE_META: f"{b.label} against {a.label}"})
    for p in pairs:
        p.anchor = page.claim("preset-" + slug(p.name))
    page.add(f'<p class="lead">Generated by <code>scripts/report.py --compare</code>: every preset both folders '
             f"ran, case by case; ratio = time on <b>{esc(b.label)}</b> / time on <b>{esc(a.label)}</b>, below 1 "
             f"is faster. Regenerate: <code>/usr/bin/python3 scripts/report.py --compare {esc(shown_path(a.path))} "
             f"{esc(shown_path(b.path))} -o DIR</code>.</p>")
    sides_section(page, sides)
    summary_section(page, pairs, sides, only, args)
    compare_howto(page, args, sides)
    page.section(2, "presets", "Presets")
    failures = []
    n_figures = sum(preset_block(page, p, sides, args.out_dir, args, failures) for p in pairs)
    if not pairs:
        page.add("<p class='note'>The two folders have no preset in common: nothing to compare.</p>")
    for s, names in zip(sides, only):
        if names:
            page.add(f"<p class='muted'>Only in {esc(s.label)} (not compared): " +
                     ", ".join(f"<code>{esc(n)}</code>" for n in names) + "</p>")
    with open(os.path.join(args.out_dir, "index.html"), "w", encoding="utf-8", newline="\n") as f:
        f.write(page.render())
    write_file_list(args.out_dir, since)
    every = [c for p in pairs for c in p.comparisons]
    counts = [plural(len(pairs), "preset") + " compared", plural(len(every), "comparison"), plural(n_figures, "figure")]
    counts += [f"{len(n)} only in {s.label}" for s, n in zip(sides, only) if n]
    print(f"report.py: {os.path.join(args.out_dir, 'index.html')}: {', '.join(counts)}")
    print(f"report.py: {compare.summary_text(every, args.min_effect)} ({b.label} against {a.label})")
    for fail in failures:
        print(f"report.py: figure not drawn: {fail}", file=sys.stderr)
    return 1 if failures else 0


# -------------------------------------------------------------------------------------------------- main

def plural(n, word):
    return f"{n} {word}" + ("" if n == 1 else "s")


def shown_path(path):
    """A folder as the page names it: relative to the repository, so the page does not depend on where
    the checkout lives."""
    repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    return os.path.relpath(os.path.abspath(path), repo)


def build(args):
    images_dir = args.images if args.images else default_images_dir(args.inputs)
    if args.images and not os.path.isdir(args.images):
        raise oitres.ResultsError(f"{args.images}: no such images folder (--images)")
    pages = []
    inputs, skipped, base = collect(args.inputs, args.out_dir, images_dir, pages)
    for d in args.ab or []:
        if not os.path.isdir(d):
            raise oitres.ResultsError(f"--ab {d}: not a folder (give scripts/ab.py's or ab_bench.sh's out folder)")
    for p in [base] + ([images_dir] if images_dir else []) + list(args.ab or []):
        out, inside = os.path.realpath(args.out_dir), os.path.realpath(p)
        if out == inside or inside.startswith(out + os.sep):
            raise oitres.ResultsError(f"{args.out_dir}: the report would overwrite its own inputs ({p}); "
                                      "give -o a folder of its own (e.g. RESULTS/report)")
    since = prepare_out_dir(args.out_dir)
    title = args.title or f"oitbench report: {os.path.basename(base) or 'results'}"
    page = Page(title)
    facts = [Facts(inp.run) for inp in inputs]
    for inp in inputs:
        inp.anchor = page.claim("run-" + slug(inp.run.label))
    page.add(f'<p class="lead">Generated by <code>scripts/report.py</code> from {len(inputs)} summary CSV(s)'
             f" in <code>{esc(os.path.basename(base) or '.')}/</code>. Regenerate: "
             "<code>/usr/bin/python3 scripts/report.py RESULTS -o DIR</code>.</p>")
    paper_dir = args.paper or tables.default_paper_dir()
    howto_section(page, os.path.isdir(paper_dir), bool(images_dir))
    shared = overview_section(page, inputs, facts, skipped)
    across_section(page, args.inputs, pages, args.out_dir)
    page.section(2, "files", "Results by file")
    failures = []
    n_figures = sum(run_block(page, inp, f, shared, args.out_dir, failures) for inp, f in zip(inputs, facts))
    n_fastest = fastest_section(page, inputs, args.out_dir, failures)
    time_section(page, inputs)
    n_tables = tables_section(page, inputs, paper_dir, args.paper or shown_path(paper_dir), args.out_dir, failures)
    n_ab = ab_section(page, args.ab, args.out_dir, failures) if args.ab else 0
    n_images = gallery_section(page, images_dir, args.out_dir) if images_dir else 0
    with open(os.path.join(args.out_dir, "index.html"), "w", encoding="utf-8", newline="\n") as f:
        f.write(page.render())
    write_file_list(args.out_dir, since)
    counts = [plural(len(inputs), "run"), plural(n_figures, "figure"), plural(n_tables, "paper table"),
              "a fastest-technique summary" if n_fastest else None, plural(n_ab, "A/B comparison") if n_ab else None,
              plural(n_images, "image")] + ([plural(len(skipped), "CSV") + " left out"] if skipped else [])
    print(f"report.py: {os.path.join(args.out_dir, 'index.html')}: {', '.join(c for c in counts if c)}")
    for fail in failures:
        print(f"report.py: figure not drawn: {fail}", file=sys.stderr)
    return 1 if failures else 0
