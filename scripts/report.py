#!/usr/bin/python3
"""One static HTML page from oitbench runs: what ran where, what failed and why, every figure, the
papers' tables beside ours, and the rendered images.

    scripts/report.py RUN.csv [RUN2.csv ...] -o DIR
    scripts/report.py RESULTS_DIR -o DIR [--paper PAPER_DIR] [--images IMAGES_DIR]

A folder argument stands for every summary CSV below it, found by its header (oitcsv.is_summary_header);
--raw files are left out (a NAME_raw.csv beside NAME.csv makes NAME's parameter columns exact), and so are
the output folder and the images folder. DIR gets index.html, figures/ (plot.py's figures, PNG and SVG)
and images/ (copies of the rendered PNGs); every link is relative, so DIR can be moved or committed.
The page depends only on its inputs: the same results give the same files, byte for byte.
Exit codes: 0 written; 1 written, but a figure could not be drawn (the page says which); 2 no or
unreadable input, or an output folder that holds something else.
"""
import argparse
import collections
import html
import os
import re
import shutil
import signal
import struct
import sys
import urllib.parse

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import oitcsv  # noqa: E402
import plot  # noqa: E402
import tables  # noqa: E402

GENERATOR = "oitbench scripts/report.py"
STATUSES = ["ok", "invalid", "unsupported", "error", "timeout"]
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

def collect(paths, out_dir, images_dir):
    """(inputs, skipped): the summary CSVs named or found below the folders, and the CSVs passed over
    with the reason. Raises ResultsError for a missing or unreadable input or when nothing is left."""
    found, skipped = [], []
    keep_out = {os.path.realpath(p) for p in (out_dir, images_dir) if p}
    dirs = []
    for p in paths:
        if os.path.isdir(p):
            dirs.append(p)
            for root, subdirs, files in os.walk(p):
                subdirs[:] = sorted(d for d in subdirs if not d.startswith(".")
                                    and os.path.realpath(os.path.join(root, d)) not in keep_out)
                found += [(os.path.join(root, f), False) for f in sorted(files) if f.endswith(".csv")]
        elif os.path.exists(p):
            found.append((p, True))
        else:
            raise oitcsv.ResultsError(f"{p}: no such file or folder")
    base = os.path.commonpath([os.path.abspath(d) for d in dirs] +
                              [os.path.dirname(os.path.abspath(p)) for p, named in found if named] or ["."])
    headers = {}
    for p, _ in found:
        headers[p] = oitcsv.read_csv(p)
    inputs, seen = [], set()
    for p, named in found:
        header, rows = headers[p]
        rel = os.path.relpath(os.path.abspath(p), base)
        if not oitcsv.is_summary_header(header):
            if named:
                oitcsv.Run.load(p)  # raises the scripts' usual message (a --raw file, or not oitbench's)
            why = "raw repetitions (--raw)" if oitcsv.is_raw_header(header) else "not an oitbench summary CSV"
            skipped.append((rel, why))
            continue
        if os.path.realpath(p) in seen:
            continue
        seen.add(os.path.realpath(p))
        # NAME_raw.csv beside NAME.csv, when it is a raw file, makes NAME's parameter columns exact.
        sibling = p[:-len(".csv")] + "_raw.csv" if p.endswith(".csv") else None
        raw_header = headers[sibling][0] if sibling in headers else (
            oitcsv.read_csv(sibling)[0] if sibling and os.path.isfile(sibling) else [])
        raw_params = oitcsv.raw_param_columns(raw_header) if oitcsv.is_raw_header(raw_header) else None
        label = rel[:-len(".csv")] if rel.endswith(".csv") else rel
        inputs.append(Input(oitcsv.Run(p, header, rows, raw_params, label), rel))
    if not inputs:
        where = ", ".join(paths)
        raise oitcsv.ResultsError(f"{where}: no oitbench summary CSV found (written by `oitbench run --out`)")
    return inputs, skipped, base


def default_images_dir(paths):
    """images/ in the first folder given, else beside the first CSV; None when there is none."""
    for p in paths:
        if os.path.isdir(p):
            candidate = os.path.join(p, "images")
            return candidate if os.path.isdir(candidate) else None
    candidate = os.path.join(os.path.dirname(os.path.abspath(paths[0])), "images")
    return candidate if os.path.isdir(candidate) else None


def prepare_out_dir(out_dir):
    """An empty or new folder, or a previous report (whose generated parts are removed first)."""
    index = os.path.join(out_dir, "index.html")
    if os.path.isdir(out_dir) and os.listdir(out_dir):
        previous = False
        if os.path.isfile(index):
            with open(index, encoding="utf-8", errors="replace") as f:
                previous = f'<meta name="generator" content="{GENERATOR}">' in f.read(4000)
        if not previous:
            raise oitcsv.ResultsError(f"{out_dir}: not empty and not a previous report; give a new or empty "
                                      "folder with -o")
        for sub in ("figures", "images"):
            shutil.rmtree(os.path.join(out_dir, sub), ignore_errors=True)
        os.remove(index)
    os.makedirs(out_dir, exist_ok=True)


# -------------------------------------------------------------------------------------------- run facts

def case_key(row, params):
    return (row["experiment"], row.get("variant", ""), row.get("width", ""), row.get("height", "")) + \
        tuple(row.get(p, "") for p in params)


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
            shown = oitcsv.varying(run.rows_of(exp), params) or params
            for r in run.rows_of(exp):
                cases.setdefault(case_key(r, params), []).append((r, shown))
        self.experiments = collections.Counter()
        self.status = collections.Counter()
        self.failed = []  # (experiment, case, status, reason)
        self.notes = collections.Counter()  # reasons written on valid rows (timer-disagreement, ...)
        for key, members in cases.items():
            total = next((r for r, _ in members if r.get("pass") == "total"), None)
            failing = [r for r, _ in members if not oitcsv.is_ok(r)]
            row = total if total is not None and not oitcsv.is_ok(total) else (failing[0] if failing else None)
            status = oitcsv.status_of(row) if row is not None else "ok"
            self.experiments[key[0]] += 1
            self.status[status] += 1
            if row is not None:
                reason = row.get("reason") or next((r.get("reason") for r in failing if r.get("reason")), "")
                params = members[0][1]
                self.failed.append((key[0], oitcsv.describe_case(dict(row, **{"pass": "total"}), params),
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
    def __init__(self, title):
        self.title = title
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
        return "\n".join([
            "<!DOCTYPE html>", '<html lang="en">', "<head>", '<meta charset="utf-8">',
            f'<meta name="generator" content="{GENERATOR}">',
            '<meta name="viewport" content="width=device-width, initial-scale=1">',
            f"<title>{esc(self.title)}</title>", f"<style>{CSS}</style>", "</head>",
            '<body data-loaded="0">', '<div id="broken-images" class="alert" hidden></div>',
            '<div class="layout">', "\n".join(toc), '<main>', f"<h1>{esc(self.title)}</h1>",
            "\n".join(self.body), "</main>", "</div>", f"<script>{CHECK_SCRIPT}</script>", "</body>", "</html>", ""])


# The page checks itself once everything has loaded: how many images, how many figures, which did not
# decode. The counts go on <body> (the headless-browser test reads them) and a broken image is named in
# a banner at the top, so a reader sees it too.
CHECK_SCRIPT = """
window.addEventListener("load", function () {
  var imgs = Array.prototype.slice.call(document.images);
  var broken = imgs.filter(function (i) { return !i.complete || i.naturalWidth === 0; })
                   .map(function (i) { return i.getAttribute("src"); });
  var figures = imgs.filter(function (i) { return i.classList.contains("figure"); }).length;
  document.body.setAttribute("data-images", String(imgs.length));
  document.body.setAttribute("data-figures", String(figures));
  document.body.setAttribute("data-broken", JSON.stringify(broken));
  document.body.setAttribute("data-loaded", "1");
  if (broken.length) {
    var box = document.getElementById("broken-images");
    box.textContent = broken.length + " image(s) did not load: " + broken.join(", ");
    box.hidden = false;
  }
});
"""

CSS = """
:root { --fg: #1f2328; --muted: #656d76; --line: #d8dee4; --bg: #ffffff; --soft: #f6f8fa; --accent: #0969da; }
* { box-sizing: border-box; }
body { margin: 0; color: var(--fg); background: var(--bg); font: 15px/1.5 system-ui, -apple-system, "Segoe UI",
       Roboto, "Helvetica Neue", Arial, sans-serif; }
.layout { display: flex; align-items: flex-start; }
nav.toc { position: sticky; top: 0; flex: 0 0 250px; max-height: 100vh; overflow-y: auto; padding: 20px 14px;
          border-right: 1px solid var(--line); background: var(--soft); font-size: 13px; }
nav.toc ul { list-style: none; margin: 0; padding: 0; }
nav.toc li { margin: 2px 0; }
nav.toc li.l3 { padding-left: 14px; }
nav.toc li.l4 { padding-left: 28px; font-size: 12px; }
nav.toc a { color: var(--fg); text-decoration: none; }
nav.toc a:hover { color: var(--accent); }
.toc-title { font-weight: 600; margin-bottom: 8px; text-transform: uppercase; letter-spacing: .05em;
             color: var(--muted); font-size: 11px; }
main { flex: 1 1 auto; min-width: 0; max-width: 1280px; padding: 8px 36px 60px; }
h1 { font-size: 28px; margin: 18px 0 4px; }
h2 { font-size: 22px; margin: 40px 0 10px; padding-bottom: 6px; border-bottom: 1px solid var(--line); }
h3 { font-size: 17px; margin: 28px 0 8px; }
h4 { font-size: 15px; margin: 20px 0 6px; }
a { color: var(--accent); }
code { font: 13px ui-monospace, SFMono-Regular, Menlo, Consolas, monospace; background: var(--soft);
       padding: 1px 4px; border-radius: 4px; }
pre { font: 12px/1.4 ui-monospace, SFMono-Regular, Menlo, Consolas, monospace; background: var(--soft);
      padding: 8px; border-radius: 6px; white-space: pre-wrap; max-height: 320px; overflow: auto; }
.muted { color: var(--muted); }
.lead { color: var(--muted); margin-top: 0; }
.scroll { overflow-x: auto; margin: 8px 0 16px; }
table.data { border-collapse: collapse; font-size: 13px; }
table.data th, table.data td { border-bottom: 1px solid var(--line); padding: 4px 10px; text-align: left;
                               vertical-align: top; }
table.data th { background: var(--soft); font-weight: 600; position: sticky; top: 0; }
table.data td.num, table.data th.num { text-align: right; font-variant-numeric: tabular-nums;
                                       white-space: nowrap; }
table.data tbody tr:hover { background: #f0f6ff; }
table.data tr.unmatched td { color: var(--muted); }
table.data td.ours { background: #f0f6ff; }
table.data th.ours { background: #ddeeff; }
details.table-run p { margin: 4px 0; }
table.data td details summary { cursor: pointer; }
dl.meta { display: grid; grid-template-columns: max-content minmax(0, 1fr) max-content minmax(0, 1fr);
          gap: 2px 14px; margin: 0; font-size: 14px; }
dl.meta dt { color: var(--muted); white-space: nowrap; }
dl.meta dd { margin: 0; overflow-wrap: anywhere; }
.small { font-size: 12px; margin: 6px 0 0; }
.badge { display: inline-block; padding: 0 7px; border-radius: 10px; font-size: 12px; font-weight: 600;
         margin-right: 3px; white-space: nowrap; }
.badge.ok { background: #dafbe1; color: #116329; }
.badge.invalid { background: #fff1c2; color: #7d4e00; }
.badge.unsupported { background: #eaeef2; color: #424a53; }
.badge.error { background: #ffebe9; color: #a40e26; }
.badge.timeout { background: #fbefff; color: #6e40c9; }
.badge.zero { opacity: .35; }
.card { border: 1px solid var(--line); border-radius: 8px; padding: 12px 16px; margin: 14px 0; }
.alert { background: #ffebe9; color: #a40e26; border-bottom: 1px solid #ffc1ba; padding: 10px 20px;
         font-weight: 600; }
.note { background: #fff8c5; border: 1px solid #eac54f; border-radius: 6px; padding: 8px 12px; }
figure { margin: 16px 0 28px; }
figure img.figure { display: block; max-width: 100%; height: auto; border: 1px solid var(--line);
                    border-radius: 6px; background: #fff; }
figcaption { font-size: 13px; color: var(--muted); margin-top: 4px; }
.gallery { display: grid; grid-template-columns: repeat(auto-fill, minmax(250px, 1fr)); gap: 14px; }
.gallery figure { margin: 0; }
.gallery img { display: block; width: 100%; height: auto; image-rendering: pixelated;
               border: 1px solid var(--line); border-radius: 4px; background: #000; }
details.table-run { margin: 6px 0 14px; }
details.table-run > summary { cursor: pointer; font-weight: 600; }
details.table-run details > summary { cursor: pointer; color: var(--muted); font-size: 13px; }
dl.howto dt { font-weight: 600; margin-top: 8px; }
dl.howto dd { margin-left: 16px; }
"""


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
         "Click a figure for its SVG. On a shared 2-core machine the same case moves 20&ndash;30% between "
         "runs: read shapes and ratios, and use <code>scripts/compare.py</code> for differences."),
    ]
    if have_tables:
        items.append(("Paper tables", "<code>scripts/tables.py</code>: each paper table that any run has "
                      "rows for, the paper's numbers and ours side by side. Hardware differs by orders of "
                      "magnitude, so compare the <em>speedup</em> columns (time of the table's baseline / "
                      "time, computed alike for paper and ours), not milliseconds. Each run is matched on its "
                      "own; the paper's rows that run has nothing for are folded away below its table."))
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
        caption = f"{exp}: {len(data.ok)} valid row(s)" + (
            f", {len(lines)} case(s) not plotted (listed above)" if lines else "")
        page.add(f'<figure><a href="{url(rel + ".svg")}">'
                 f"{img_tag(rel + '.png', stem + '.png', f'{exp} figure of {inp.rel}', 'figure')}</a>"
                 f'<figcaption>{esc(caption)} &middot; <a href="{url(rel + ".svg")}">SVG</a></figcaption>'
                 "</figure>")
    return count


def tables_section(page, inputs, paper_dir, shown_paper_dir):
    """The paper tables with any of our rows, one per (table, run) with rows; returns how many."""
    page.section(2, "tables", "Paper tables")
    if not os.path.isdir(paper_dir):
        page.add(f'<p class="note">The papers\' tables are not here: no folder <code>{esc(shown_paper_dir)}'
                 "</code>. Give <code>--paper DIR</code> (the tidy paper CSVs, as for "
                 "<code>scripts/tables.py</code>).</p>")
        return 0
    try:
        paper_rows = tables.load_paper(paper_dir)
    except oitcsv.ResultsError as e:
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
        best = max(m for m, _, _ in found)
        opened = False
        for matched, inp, layout in found:
            is_open = matched == best and not opened
            opened = opened or is_open
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
        header, rows = oitcsv.read_csv(csv_path)
    except oitcsv.ResultsError:
        return ""
    if not rows or not oitcsv.is_summary_header(header):
        return ""
    row = next((r for r in rows if r.get("pass") == "total"), rows[0])
    what = row.get("technique") or row.get("variant") or "?"
    where = " ".join(x for x in (row.get("scene"), row.get("view")) if x)
    parts = [f"{esc(what)}" + (f" on {esc(where)}" if where else "") +
             (f", {esc(row['width'])}x{esc(row['height'])}" if row.get("width") else "") + ":",
             status_badges({oitcsv.status_of(row): 1}, always=False)]
    facts = []
    for col, label, unit in (("median_ms", "total", " ms"), ("max_abs_error", "max error", ""),
                             ("rmse", "RMSE", ""), ("peak_depth", "peak depth", "")):
        x = oitcsv.to_float(row.get(col))
        if x is not None:
            facts.append(f"{label} {tables.fmt(x, 4) if unit else f'{x:.3g}'}{unit}")
    if row.get("reason"):
        facts.append(esc(row["reason"].strip().splitlines()[0][:LONG_REASON]))
    return " ".join(parts) + " " + esc(", ".join(facts)) if facts else " ".join(parts)


# -------------------------------------------------------------------------------------------------- main

def plural(n, word):
    return f"{n} {word}" + ("" if n == 1 else "s")


def shown_path(path):
    """A folder as the page names it: relative to the repository, so the page does not depend on where
    the checkout lives."""
    repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    return os.path.relpath(os.path.abspath(path), repo)


def build(args):
    images_dir = args.images if args.images else default_images_dir(args.inputs)
    if args.images and not os.path.isdir(args.images):
        raise oitcsv.ResultsError(f"{args.images}: no such images folder (--images)")
    inputs, skipped, base = collect(args.inputs, args.out_dir, images_dir)
    for p in [base] + ([images_dir] if images_dir else []):
        out, inside = os.path.realpath(args.out_dir), os.path.realpath(p)
        if out == inside or inside.startswith(out + os.sep):
            raise oitcsv.ResultsError(f"{args.out_dir}: the report would overwrite its own inputs ({p}); "
                                      "give -o a folder of its own (e.g. RESULTS/report)")
    prepare_out_dir(args.out_dir)
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
    page.section(2, "files", "Results by file")
    failures = []
    n_figures = sum(run_block(page, inp, f, shared, args.out_dir, failures) for inp, f in zip(inputs, facts))
    n_tables = tables_section(page, inputs, paper_dir, args.paper or shown_path(paper_dir))
    n_images = gallery_section(page, images_dir, args.out_dir) if images_dir else 0
    with open(os.path.join(args.out_dir, "index.html"), "w", encoding="utf-8", newline="\n") as f:
        f.write(page.render())
    counts = [plural(len(inputs), "run"), plural(n_figures, "figure"), plural(n_tables, "paper table"),
              plural(n_images, "image")] + ([plural(len(skipped), "CSV") + " left out"] if skipped else [])
    print(f"report.py: {os.path.join(args.out_dir, 'index.html')}: {', '.join(counts)}")
    for fail in failures:
        print(f"report.py: figure not drawn: {fail}", file=sys.stderr)
    return 1 if failures else 0


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("inputs", nargs="+", metavar="CSV_OR_DIR",
                    help="summary CSVs (`oitbench run --out`) or folders to search for them")
    ap.add_argument("-o", "--out-dir", required=True, help="the report's folder (index.html, figures/, images/)")
    ap.add_argument("--paper", help="folder of the papers' tidy CSVs (default: tables.py's, "
                                    "the repository's results/published)")
    ap.add_argument("--images", help="folder of `oitbench render` PNGs (default: images/ in the results folder, "
                                     "or beside the first CSV, when there is one)")
    ap.add_argument("--title", help="the page's title (default: oitbench report: FOLDER)")
    args = ap.parse_args(argv)
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)
    try:
        return build(args)
    except oitcsv.ResultsError as e:
        print(f"report.py: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
