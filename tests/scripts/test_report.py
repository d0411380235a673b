"""report.py: one static HTML page from runs, checked in a real headless browser (Debian's chromium): the
page loads, every image decodes and the figures are all there, and a figure deleted afterwards is caught.
Also: the metadata and every failed case with its reason, the paper tables, a results folder searched by
header (summary files only), the same page from the same results, and errors that exit 2.
report.py --compare: two results folders written by the binary on llvmpipe and on zink, one page of
per-case ratios (in the browser too), its header, the cases it could not compare, the same bytes twice,
bad input, a tight 0.74x said to be inside the noise band, and a results root linking its pages."""
import csv
import html.parser
import json
import os
import random
import re
import shutil
import struct
import subprocess
import tempfile
import unittest
import zlib

import synthetic as syn
from support import PNG_MAGIC, PYTHON, TempDirTest, oitbench_exe, run_oitbench, run_script
from test_tables import MINI_PAPER

CHROMIUM = "/usr/bin/chromium"


def tiny_png(path, width, height, rgb):
    """A valid RGB PNG of one colour, written without any imaging library."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    rows = b"".join(b"\x00" + bytes(rgb) * width for _ in range(height))
    with open(path, "wb") as f:
        f.write(PNG_MAGIC + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


class PageParser(html.parser.HTMLParser):
    """The <img> tags (src, class) and the attributes of <body> of a page."""

    def __init__(self, text):
        super().__init__()
        self.images, self.body = [], {}
        self.feed(text)

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag == "img":
            self.images.append((attrs.get("src", ""), attrs.get("class", "")))
        elif tag == "body":
            self.body = attrs


def read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def browse(index_html):
    """Opens the page in headless chromium and returns the DOM after its load handler ran."""
    profile = tempfile.mkdtemp(prefix="oitbench-chromium-")
    try:
        proc = subprocess.run(
            [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
             "--disable-background-networking", "--disable-component-update", "--disable-sync",
             f"--user-data-dir={profile}", "--virtual-time-budget=10000", "--dump-dom",
             "file://" + os.path.abspath(index_html)],
            capture_output=True, text=True, timeout=180)
    finally:
        shutil.rmtree(profile, ignore_errors=True)
    if proc.returncode != 0 or "<body" not in proc.stdout:
        raise AssertionError(f"chromium exited {proc.returncode} without a page:\n{proc.stderr[-3000:]}")
    return proc.stdout


def browser_check(index_html):
    """What the page's own check wrote on <body>: images, figures and the broken ones."""
    dom = browse(index_html)
    body = PageParser(dom).body
    if body.get("data-loaded") != "1":
        raise AssertionError(f"the page's load handler did not run (body: {body})")
    return int(body["data-images"]), int(body["data-figures"]), json.loads(body["data-broken"]), dom


class ReportCase(TempDirTest):
    def write_runs(self, folder=None):
        """Two runs: occupancy and sort in one file, oit in the other: three figures. The occupancy run
        has an invalid case, the oit run a timeout."""
        folder = folder or self.dir
        a = syn.write_summary(os.path.join(folder, "micro.csv"), syn.occupancy_rows() + syn.sort_rows(),
                              syn.OCCUPANCY_METRICS, syn.OCCUPANCY_PARAMS + ["n", "keys"])
        b = syn.write_summary(os.path.join(folder, "oit.csv"), syn.oit_rows(), ["rmse", "max_abs_error"],
                              ["scene", "max_frags"])
        return a, b

    def write_paper(self):
        os.makedirs(self.path("paper"), exist_ok=True)
        with open(self.path("paper/mini.csv"), "w", encoding="utf-8") as f:
            f.write(MINI_PAPER)
        return self.path("paper")

    def write_images(self, folder):
        os.makedirs(folder, exist_ok=True)
        tiny_png(os.path.join(folder, "planes-rev-BASE-IS.png"), 16, 12, (200, 120, 40))
        tiny_png(os.path.join(folder, "planes-rev-BASE-IS-diff8.png"), 16, 12, (0, 0, 0))
        return folder

    def report(self, *inputs, out="report", check=True, extra=()):
        return run_script("report.py", *inputs, "-o", self.path(out), *extra, check=check)


class ReportInBrowser(ReportCase):
    EXPECTED_FIGURES = 3  # occupancy and sort from micro.csv, oit from oit.csv

    def setUp(self):
        super().setUp()
        if not os.access(CHROMIUM, os.X_OK):
            self.fail(f"{CHROMIUM} not found: the report is tested in headless chromium; run scripts/deps.sh "
                      "(as root it installs the chromium package)")

    def build(self):
        a, b = self.write_runs()
        self.report(a, b, extra=("--paper", self.write_paper(), "--images", self.write_images(self.path("img"))))
        return self.path("report/index.html")

    def test_page_loads_and_every_image_decodes(self):
        index = self.build()
        parsed = PageParser(read(index)).images
        figures = [src for src, cls in parsed if cls == "figure"]
        renders = [src for src, cls in parsed if cls == "render"]
        self.assertEqual(len(figures), self.EXPECTED_FIGURES, parsed)
        self.assertEqual(len(renders), 2, parsed)
        for src, _ in parsed:
            self.assertFalse(os.path.isabs(src) or src.startswith(("file:", "/")), src)  # the folder can move
            self.assertTrue(os.path.isfile(os.path.join(self.path("report"), src)), src)
        images, n_figures, broken, _ = browser_check(index)
        self.assertEqual(broken, [])
        self.assertEqual(images, len(parsed))
        self.assertEqual(n_figures, self.EXPECTED_FIGURES)

    def test_a_deleted_figure_is_reported_broken(self):
        index = self.build()
        figure = next(src for src, cls in PageParser(read(index)).images if cls == "figure")
        os.remove(os.path.join(self.path("report"), figure))
        images, n_figures, broken, dom = browser_check(index)
        self.assertEqual(broken, [figure])
        self.assertEqual(n_figures, self.EXPECTED_FIGURES)  # the tag is there, its image is not
        self.assertIn("1 image(s) did not load", dom)  # and the reader is told at the top

    def test_the_moved_folder_still_loads(self):
        index = self.build()
        moved = self.path("elsewhere/report")
        shutil.move(os.path.dirname(index), moved)
        shutil.rmtree(self.path("img"))  # the copies inside the report are what it shows
        _, _, broken, _ = browser_check(os.path.join(moved, "index.html"))
        self.assertEqual(broken, [])


class ReportContent(ReportCase):
    def test_metadata_and_every_failed_case_with_its_reason(self):
        a, b = self.write_runs()
        self.report(a, b, extra=("--paper", self.write_paper()))
        page = read(self.path("report/index.html"))
        for needle in (syn.RENDERER, "abc123", "2026-01-01T00:00:00Z", "64x64", "micro.csv", "oit.csv",
                       "42 pixels differ from the CPU reference", "watchdog: no progress for 10 s",
                       '<span class="badge invalid">invalid 1</span>', '<span class="badge timeout">timeout 1</span>',
                       "How to read this page", 'href="#tables"'):
            self.assertIn(needle, page)

    def test_the_time_account_gives_the_shares_per_preset_and_experiment(self):
        phases = {"phase_samples_s": 6, "phase_compile_s": 1, "phase_warmup_s": 0.5, "phase_readback_s": 0.25,
                  "phase_reference_s": 1, "phase_validate_s": 0.25, "phase_scene_s": 0.5, "phase_pool_s": 0.25,
                  "phase_other_s": 0.25}
        rows = [dict(r, preset="knowles2014", **(dict(phases, case_wall_s=10) if r["pass"] == "total" else {}))
                for r in syn.oit_rows() if r.get("status", "ok") == "ok"]
        path = syn.write_summary(self.path("account.csv"), rows, ["rmse", "max_abs_error"], ["scene", "max_frags"])
        self.report(path)
        page = read(self.path("report/index.html"))
        self.assertIn("Where the time went", page)
        section = page[page.index('id="time"'):]
        cells = re.findall(r"<td[^>]*>([^<]*)</td>", section[:section.index("</table>")])
        # knowles2014, oit: 32 cases of 10 s; samples 60 %, compile 10, warm-up 5, reference+validation 15,
        # scene 8 (7.5 rounded half to even), other 2 (2.5)
        self.assertEqual(cells, ["knowles2014", "oit", "32", "320.0", "60", "10", "5", "15", "8", "2"])
        # Files of older schemas have no account: no section.
        a, b = self.write_runs()
        self.report(a, b, out="old")
        self.assertNotIn("Where the time went", read(self.path("old/index.html")))

    def test_paper_tables_beside_ours_and_a_missing_paper_folder_said(self):
        a, b = self.write_runs()
        self.report(a, b, extra=("--paper", self.write_paper()))
        page = read(self.path("report/index.html"))
        self.assertIn("Brüll 2018 A.1", page)  # sort rows of micro.csv: 16 cases
        self.assertIn("Knowles 2014 table 2", page)  # oit rows of oit.csv
        self.assertIn("<th class=\"num ours\">ours speedup</th>", page)
        self.assertIn("2.6 ms", page)  # the paper's A.1 number
        self.assertNotIn("Knowles 2013 table 1", page)  # no paper rows for it in the mini table
        proc = self.report(a, out="nopaper", extra=("--paper", self.path("nowhere")))
        self.assertIn("tables are not here", read(self.path("nopaper/index.html")))
        self.assertIn(": 1 run, 2 figures, 0 paper tables, 0 images", proc.stdout)

    def test_a_results_folder_gives_summary_files_only(self):
        results = self.path("results")
        os.makedirs(os.path.join(results, "sub"))
        syn.write_summary(os.path.join(results, "run.csv"), syn.sort_rows(), params=["n", "keys"],
                          raw_path=os.path.join(results, "run_raw.csv"))
        # Names do not decide: a summary called *_raw.csv is a run, a raw file called summary.csv is not.
        syn.write_summary(os.path.join(results, "sub", "stats_raw.csv"), syn.sort_rows()[:4], params=["n", "keys"],
                          raw_path=os.path.join(results, "sub", "summary.csv"))
        with open(os.path.join(results, "notes.csv"), "w", encoding="utf-8") as f:
            f.write("a,b\n1,2\n")
        images = self.write_images(os.path.join(results, "images"))
        # `oitbench render` writes the case's row beside its image: shown with the image, not as a run.
        syn.write_summary(os.path.join(images, "planes-rev-BASE-IS.csv"),
                          [{"experiment": "oit", "variant": "", "pass": "total", "technique": "BASE-IS",
                            "scene": "planes", "view": "rev", "median_ms": 12.5, "max_abs_error": "1e-08"}],
                          metrics=["max_abs_error"], params=["technique", "scene", "view"])
        proc = self.report(results, out="results/report", extra=("--paper", self.path("nowhere")))
        self.assertIn(": 2 runs, 2 figures, 0 paper tables, 2 images, 3 CSVs left out", proc.stdout)
        page = read(self.path("results/report/index.html"))
        self.assertIn('id="run-run"', page)
        self.assertIn('id="run-sub-stats-raw"', page)
        for left_out in ("run_raw.csv</code> (raw repetitions", "sub/summary.csv</code> (raw repetitions",
                         "notes.csv</code> (not an oitbench summary CSV"):
            self.assertIn(left_out, page)
        self.assertIn("BASE-IS on planes rev, 64x64:", page)
        self.assertTrue(os.path.isfile(self.path("results/report/images/planes-rev-BASE-IS-diff8.png")))
        # Once more into the same folder: the previous report is replaced, not refused.
        proc = self.report(results, out="results/report")
        self.assertIn(": 2 runs, 2 figures", proc.stdout)

    def test_the_same_results_give_the_same_files(self):
        a, b = self.write_runs()
        paper = self.write_paper()
        self.report(a, b, out="one", extra=("--paper", paper))
        self.report(a, b, out="two", extra=("--paper", paper))
        files = []
        for root, _, names in os.walk(self.path("one")):
            files += [os.path.relpath(os.path.join(root, n), self.path("one")) for n in names]
        self.assertIn("index.html", files)
        self.assertGreaterEqual(len(files), 1 + 2 * 3)
        for rel in files:
            with open(os.path.join(self.path("one"), rel), "rb") as f1, \
                    open(os.path.join(self.path("two"), rel), "rb") as f2:
                self.assertEqual(f1.read(), f2.read(), f"{rel} differs between two reports of the same runs")

    def test_errors_exit_2_with_a_clear_message(self):
        proc = run_script("report.py", "-o", self.path("r"), check=False)
        self.assertEqual(proc.returncode, 2)
        self.assertIn("the following arguments are required", proc.stderr)
        proc = self.report(self.path("missing.csv"), check=False)
        self.assertEqual(proc.returncode, 2)
        self.assertIn("missing.csv: no such file or folder", proc.stderr)
        syn.write_summary(self.path("run.csv"), syn.sort_rows(), params=["n", "keys"], raw_path=self.path("raw.csv"))
        proc = self.report(self.path("raw.csv"), check=False)
        self.assertEqual(proc.returncode, 2)
        self.assertIn("--raw file", proc.stderr)
        with open(self.path("broken.csv"), "wb") as f:
            f.write(b"\xff\xfe not text \x00\n")
        proc = self.report(self.path("broken.csv"), check=False)
        self.assertEqual(proc.returncode, 2)
        self.assertIn("broken.csv", proc.stderr)
        os.makedirs(self.path("empty"))
        proc = self.report(self.path("empty"), check=False)
        self.assertEqual(proc.returncode, 2)
        self.assertIn("no oitbench summary CSV found", proc.stderr)
        os.makedirs(self.path("busy"))
        with open(self.path("busy/keep.txt"), "w", encoding="utf-8") as f:
            f.write("not a report\n")
        proc = self.report(self.path("run.csv"), out="busy", check=False)
        self.assertEqual(proc.returncode, 2)
        self.assertIn("not empty and not a previous report", proc.stderr)
        self.assertTrue(os.path.isfile(self.path("busy/keep.txt")))


AB_HEADER = "experiment,case,pass,ratio,ci_low,ci_high,noise_pct,verdict,flagged,pairs,pair_ratios\n"


class ReportAb(ReportCase):
    """--ab: A/B comparisons (scripts/ab.py's ab.csv; ab_bench.sh's trial folders with SUMMARY.txt)."""

    def write_ab(self, folder, ratio, flagged):
        os.makedirs(folder, exist_ok=True)
        with open(os.path.join(folder, "ab.csv"), "w", encoding="utf-8") as f:
            f.write(AB_HEADER + f"occupancy,occupancy dynamic size=8 256x256,total,{ratio},{ratio - 0.02},"
                    f"{ratio + 0.02},3.5,{'SLOWER' if flagged else 'no difference resolved'},{int(flagged)},8,"
                    + ";".join(f"{ratio + d:.3f}" for d in (-0.02, -0.01, 0, 0, 0.01, 0.01, 0.02, 0.02)) + "\n")

    def test_each_comparison_gets_its_table_or_summary_and_a_figure(self):
        self.write_runs()
        ab = self.path("ab")
        self.write_ab(os.path.join(ab, "drivers"), 1.31, True)
        for t in (1, 2, 3):
            self.write_ab(os.path.join(ab, "draws", f"trial-{t}"), 1.09, t != 2)
        with open(os.path.join(ab, "draws", "SUMMARY.txt"), "w", encoding="utf-8") as f:
            f.write("3 trial(s); 2 with a flagged case\n")
        proc = self.report(self.path("micro.csv"), extra=("--ab", ab))
        self.assertIn("2 A/B comparisons", proc.stdout)
        page = read(self.path("report/index.html"))
        self.assertIn('id="ab"', page)
        self.assertIn("3 trial(s); 2 with a flagged case", page)  # the trials' summary, not 3 tables
        self.assertIn("1.310", page)  # the lone comparison's table
        for name in ("ab-draws", "ab-drivers"):
            with open(self.path(f"report/figures/ab/{name}.png"), "rb") as f:
                self.assertEqual(f.read(8), PNG_MAGIC)

    def test_an_ab_folder_that_is_not_one_exits_2(self):
        self.write_runs()
        proc = self.report(self.path("micro.csv"), check=False, extra=("--ab", self.path("nowhere")))
        self.assertEqual(proc.returncode, 2)
        self.assertIn("--ab", proc.stderr)
        self.assertIn("not a folder", proc.stderr)

class ReportFiles(ReportCase):
    """report.py writes over no file and removes only what a previous page of its own wrote."""

    def test_o_onto_a_file_is_refused_and_the_file_kept(self):
        a, b = self.write_runs()
        with open(self.path("taken.html"), "w", encoding="utf-8") as f:
            f.write("mine\n")
        proc = self.report(a, b, out="taken.html", check=False)
        self.assertEqual(proc.returncode, 2, proc.stderr)
        self.assertIn("is a file, not a folder", proc.stderr)
        self.assertNotIn("Traceback", proc.stderr)
        with open(self.path("taken.html"), encoding="utf-8") as f:
            self.assertEqual(f.read(), "mine\n")

    def test_a_rerun_keeps_what_the_user_added_and_removes_its_own_old_files(self):
        a, b = self.write_runs()
        self.report(a, b)
        figures = self.path("report/figures")
        self.assertTrue(os.path.isdir(figures))
        with open(os.path.join(figures, "my-notes.txt"), "w", encoding="utf-8") as f:
            f.write("added by hand\n")
        with open(self.path("report/README.md"), "w", encoding="utf-8") as f:
            f.write("mine\n")
        listed = read(self.path("report/.report-files")).split()
        self.assertIn("index.html", listed)
        self.assertNotIn("figures/my-notes.txt", listed)
        old_figures = [r for r in listed if r.startswith("figures/")]
        self.assertTrue(old_figures)
        self.report(a)  # micro.csv only: oit.csv's figure is gone from the new page
        self.assertTrue(os.path.isfile(os.path.join(figures, "my-notes.txt")))
        self.assertTrue(os.path.isfile(self.path("report/README.md")))
        now = read(self.path("report/.report-files")).split()
        for rel in old_figures:
            self.assertEqual(os.path.exists(self.path("report/" + rel)), rel in now, rel)
        self.assertLess(len([r for r in now if r.startswith("figures/")]), len(old_figures))

    def test_a_file_list_pointing_outside_the_folder_is_not_followed(self):
        a, b = self.write_runs()
        self.report(a, b)
        with open(self.path("outside.txt"), "w", encoding="utf-8") as f:
            f.write("keep\n")
        with open(self.path("report/.report-files"), "a", encoding="utf-8") as f:
            f.write("../outside.txt\n" + self.path("outside.txt") + "\n")
        self.report(a, b)
        self.assertTrue(os.path.isfile(self.path("outside.txt")))


# ---------------------------------------------------------------------------------- report.py --compare

class TableParser(html.parser.HTMLParser):
    """Every <tr> of a page: its class and its cells' text (a cell's title attributes kept apart)."""

    def __init__(self, text):
        super().__init__()
        self.rows = []  # (class, [cell text], [titles])
        self._cell = None
        self.feed(text)

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag == "tr":
            self.rows.append((attrs.get("class", ""), [], []))
        elif tag in ("td", "th") and self.rows:
            self._cell = []
            self.rows[-1][1].append("")
        if attrs.get("title") and self.rows:
            self.rows[-1][2].append(attrs["title"])

    def handle_endtag(self, tag):
        if tag in ("td", "th"):
            self._cell = None

    def handle_data(self, data):
        if self._cell is not None and self.rows:
            self.rows[-1][1][-1] += data

    def ratio_rows(self):
        """The rows of the per-case ratio tables: (verdict class, cells, titles)."""
        return [r for r in self.rows if r[0] in ("none", "band", "overlap", "changed")]


RATIO = re.compile(r"^\d+(\.\d+)?x$")
INTERVAL = re.compile(r"^\[(\d+(?:\.\d+)?), (\d+(?:\.\d+)?)\]\u2020?$")


def write_side(folder, presets, raw=True, rng_seed=1, **kw):
    """A results folder: folder/presets/NAME.csv (and NAME_raw.csv) for each NAME: rows."""
    os.makedirs(os.path.join(folder, "presets"), exist_ok=True)
    for i, (name, (rows, metrics, params)) in enumerate(sorted(presets.items())):
        syn.write_summary(os.path.join(folder, "presets", f"{name}.csv"), rows, metrics, params,
                          raw_path=os.path.join(folder, "presets", f"{name}_raw.csv") if raw else None,
                          rng=random.Random(rng_seed + i), **kw)
    return folder


class ComparePageSynthetic(ReportCase):
    def compare_page(self, a, b, out="cmp", check=True, extra=()):
        return run_script("report.py", "--compare", a, b, "-o", self.path(out), *extra, check=check)

    def test_a_resolved_difference_inside_the_band_is_said_to_be_one(self):
        base = [dict(r, noise=0.01) for r in syn.occupancy_rows() if "reason" not in r]
        factor = {"dynamic": 0.74, "unrolled": 1.0}
        other = [dict(r, median_ms=r["median_ms"] * factor[r["variant"]],
                      noise=0.01 if r["variant"] == "dynamic" else 0.2) for r in base]
        a = write_side(self.path("a"), {"occ": (base, syn.OCCUPANCY_METRICS, syn.OCCUPANCY_PARAMS)})
        b = write_side(self.path("b"), {"occ": (other, syn.OCCUPANCY_METRICS, syn.OCCUPANCY_PARAMS)}, rng_seed=5)
        proc = self.compare_page(a, b)
        n = len(base) // 2
        self.assertIn(f"{n} no measurable difference, {n} inside the between-run noise band (at least 1.5x), "
                      "0 beyond it with overlapping repetitions, 0 changed (0 slower, 0 faster)", proc.stdout)
        rows = TableParser(read(self.path("cmp/index.html"))).ratio_rows()
        self.assertEqual(len(rows), len(base))
        for kind, cells, titles in rows:
            case, verdict = cells[0], cells[-1]
            lo, hi = (float(x) for x in INTERVAL.match(cells[4]).groups())
            if case.startswith("dynamic"):
                self.assertEqual(cells[3], "0.74x", cells)
                self.assertTrue(hi < 1, cells)  # tight: the interval excludes 1 ...
                self.assertEqual(kind, "band", cells)  # ... so it is no "no difference"
                self.assertNotIn("no measurable difference", verdict)
                self.assertIn("inside the between-run noise band (1.50x)", verdict)
                self.assertIn("not attributable to the driver or code from one run of each", " ".join(titles))
            else:
                self.assertTrue(lo <= 1 <= hi, cells)
                self.assertEqual((kind, verdict), ("none", "no measurable difference"), cells)

    def test_bad_input_exits_2_naming_it(self):
        sort = (syn.sort_rows(), [], ["n", "keys"])
        a = write_side(self.path("a"), {"sort": sort})
        os.makedirs(self.path("empty"))
        proc = self.compare_page(a, self.path("empty"), check=False)
        self.assertEqual(proc.returncode, 2, proc.stderr)
        self.assertIn(f"{self.path('empty')}: no oitbench summary CSV here", proc.stderr)
        b = write_side(self.path("b"), {"sort": sort})
        with open(os.path.join(b, "presets", "broken.csv"), "wb") as f:
            f.write(b"\x89PNG\r\n\x1a\n\x00\x00 not a csv \xff\n")
        proc = self.compare_page(a, b, check=False)
        self.assertEqual(proc.returncode, 2, proc.stderr)
        self.assertIn(os.path.join(b, "presets", "broken.csv") + ":1: not a text file", proc.stderr)
        with open(os.path.join(b, "presets", "broken.csv"), "w", encoding="utf-8") as f:
            f.write("name,value\nx,1\n")
        proc = self.compare_page(a, b, check=False)
        self.assertEqual(proc.returncode, 2, proc.stderr)
        self.assertIn(os.path.join(b, "presets", "broken.csv") + ":1: not an oitbench summary or --raw CSV", proc.stderr)
        proc = self.compare_page(a, os.path.join(a, "presets", "sort.csv"), check=False)
        self.assertEqual(proc.returncode, 2, proc.stderr)
        self.assertIn("sort.csv: not a folder", proc.stderr)
        proc = self.compare_page(a, self.path("nowhere"), check=False)
        self.assertEqual(proc.returncode, 2, proc.stderr)
        self.assertIn("nowhere: no such folder", proc.stderr)
        proc = run_script("report.py", "--compare", a, a, "-o", os.path.join(a, "presets"), check=False)
        self.assertEqual(proc.returncode, 2, proc.stderr)
        self.assertIn("would overwrite its own inputs", proc.stderr)
        proc = run_script("report.py", a, "--compare", a, a, "-o", self.path("x"), check=False)
        self.assertEqual(proc.returncode, 2, proc.stderr)
        self.assertIn("not both", proc.stderr)
        self.assertFalse(os.path.exists(self.path("cmp/index.html")))  # nothing written on bad input

    def test_a_figure_that_fails_exits_1_and_the_page_says_so(self):
        sort = (syn.sort_rows(), [], ["n", "keys"])
        a = write_side(self.path("a"), {"sort": sort})
        b = write_side(self.path("b"), {"sort": sort}, rng_seed=3)
        code = ("import sys; sys.path.insert(0, sys.argv[1]); import report; from oitbench import compare\n"
                "def fail(*args, **kwargs): raise ValueError('no figure today')\n"
                "compare.draw_figures = fail\n"
                "sys.exit(report.main(sys.argv[2:]))")
        proc = subprocess.run([PYTHON, "-c", code, syn.SCRIPTS, "--compare", a, b, "-o", self.path("cmp")],
                              capture_output=True, text=True, timeout=300, env=dict(os.environ, MPLBACKEND="Agg"))
        self.assertEqual(proc.returncode, 1, proc.stderr)
        self.assertIn("figure not drawn: sort: sort: ValueError: no figure today", proc.stderr)
        self.assertIn("could not be drawn: ValueError: no figure today", read(self.path("cmp/index.html")))

    def test_a_results_root_links_its_comparison_pages(self):
        sort = (syn.sort_rows(), [], ["n", "keys"])
        root = self.path("results")
        write_side(os.path.join(root, "llvmpipe"), {"sort": sort})
        write_side(os.path.join(root, "zink-lavapipe"), {"sort": sort}, rng_seed=9)
        proc = self.report(root, out="results/report", extra=("--paper", self.path("nowhere")))
        page = read(self.path("results/report/index.html"))
        self.assertIn('href="#across-drivers"', page)
        self.assertIn("No comparison page here yet", page)
        self.assertIn("--compare", page)
        self.compare_page(os.path.join(root, "llvmpipe"), os.path.join(root, "zink-lavapipe"),
                          out="results/compare-llvmpipe-zink")
        proc = self.report(root, out="results/report", extra=("--paper", self.path("nowhere")))
        self.assertIn(": 2 runs, 2 figures", proc.stdout)  # the comparison's compare.csv files are not runs
        self.assertNotIn("compare.csv", read(self.path("results/report/index.html")))
        links = [href for href in re.findall(r'href="([^"#]+)"', read(self.path("results/report/index.html")))
                 if "compare" in href]
        self.assertEqual(links, ["../compare-llvmpipe-zink/index.html"])
        self.assertTrue(os.path.isfile(os.path.join(self.path("results/report"), links[0])))
        # The comparison page, rewritten in place, is replaced like a report.
        self.compare_page(os.path.join(root, "llvmpipe"), os.path.join(root, "zink-lavapipe"),
                          out="results/compare-llvmpipe-zink")


@unittest.skipUnless(oitbench_exe(), "OITBENCH_EXE not set (ctest sets it)")
class ComparePageRealDrivers(ReportCase):
    """Two results folders written by the binary on llvmpipe and on zink (GL on Vulkan over lavapipe): the
    smoke preset and a quick oit grid on each. B then loses one oit case and has one smoke case
    unsupported, as a driver might."""

    OIT = ["run", "oit", "--quick", "--set", "scene=planes", "--set", "technique=BASE-IS,BASE-RBS-L"]
    DROPPED = {"technique": "BASE-RBS-L", "view": "rev"}  # removed from B's oit files
    UNSUPPORTED = {"variant": "unrolled", "size": "33"}  # made unsupported in B's smoke-test file

    @classmethod
    def setUpClass(cls):
        cls.root = tempfile.mkdtemp(prefix="oitbench-compare-")
        for side, driver in (("A", "llvmpipe"), ("B", "zink")):
            presets = os.path.join(cls.root, side, "presets")
            os.makedirs(presets)
            for name, args in (("smoke-test", ["run", "--preset", "smoke-test"]), ("oit-planes", cls.OIT)):
                run_oitbench(*args, "--driver", driver, "--no-progress", "--out",
                             os.path.join(presets, f"{name}.csv"), "--raw", os.path.join(presets, f"{name}_raw.csv"))
        b = os.path.join(cls.root, "B", "presets")
        for name in ("oit-planes.csv", "oit-planes_raw.csv"):
            cls.edit(os.path.join(b, name), lambda r: None if all(r[k] == v for k, v in cls.DROPPED.items()) else r)

        def unsupported(r):
            if all(r[k] == v for k, v in cls.UNSUPPORTED.items()):
                r.update(status="unsupported", valid="0", reason="test: this driver lacks it", median_ms="")
            return r
        cls.edit(os.path.join(b, "smoke-test.csv"), unsupported)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.root, ignore_errors=True)

    @staticmethod
    def edit(path, change):
        with open(path, newline="", encoding="utf-8") as f:
            reader = csv.DictReader(f)
            header, rows = reader.fieldnames, [change(dict(r)) for r in reader]
        with open(path, "w", newline="", encoding="utf-8") as f:
            w = csv.DictWriter(f, fieldnames=header, lineterminator="\n")
            w.writeheader()
            w.writerows(r for r in rows if r is not None)

    def side(self, name):
        return os.path.join(self.root, name)

    def rows(self, side, preset):
        with open(os.path.join(self.side(side), "presets", f"{preset}.csv"), newline="", encoding="utf-8") as f:
            return list(csv.DictReader(f))

    def build(self, out="cmp"):
        proc = run_script("report.py", "--compare", self.side("A"), self.side("B"), "-o", self.path(out))
        return proc, self.path(f"{out}/index.html")

    def test_the_page_loads_with_every_figure(self):
        _, index = self.build()
        parsed = PageParser(read(index)).images
        figures = [src for src, cls in parsed if cls == "figure"]
        self.assertEqual(len(figures), 2, parsed)  # occupancy (smoke-test) and oit (oit-planes)
        for src in figures:
            self.assertFalse(os.path.isabs(src) or src.startswith(("file:", "/")), src)
        images, n_figures, broken, _ = browser_check(index)
        self.assertEqual((images, n_figures, broken), (len(parsed), 2, []))

    def test_the_header_names_both_drivers_and_their_runs(self):
        _, index = self.build()
        table = {cells[0]: cells[1:] for _, cells, _ in TableParser(read(index)).rows if len(cells) == 3}
        self.assertEqual(table["driver"], ["llvmpipe", "zink-lavapipe"])
        self.assertTrue(table["GL_RENDERER"][0].startswith("llvmpipe"), table["GL_RENDERER"])
        self.assertTrue(table["GL_RENDERER"][1].startswith("zink"), table["GL_RENDERER"])
        self.assertIn("GALLIUM_DRIVER=zink", table["environment"][1])
        for field in ("GL_VERSION", "backend", "LP_NUM_THREADS", "git sha", "hostname", "CPU", "timestamps (UTC)"):
            self.assertTrue(all(table[field]) and "(not recorded)" not in table[field], (field, table.get(field)))
        self.assertIn("<title>oitbench comparison: zink-lavapipe against llvmpipe</title>", read(index))

    def test_every_shared_case_has_a_ratio_with_an_interval(self):
        proc, index = self.build()
        by_ms = {}
        for kind, cells, _ in TableParser(read(index)).ratio_rows():
            by_ms.setdefault((cells[1], cells[2]), []).append(cells)
        def case(r):  # the same binary wrote both sides: each row names the parameters its case uses
            return (r["experiment"], r["variant"], r["pass"], r["width"], r["height"]) + tuple(
                (p, r[p]) for p in r["parameters"].split(";"))

        expected = 0
        for preset in ("smoke-test", "oit-planes"):
            b_rows = {case(r): r for r in self.rows("B", preset) if r["status"] == "ok"}
            for r in self.rows("A", preset):
                other = b_rows.get(case(r))
                if other is None:
                    continue
                expected += 1
                pair = (format(float(r["median_ms"]), ".4g"), format(float(other["median_ms"]), ".4g"))
                self.assertIn(pair, by_ms, f"no ratio row for {preset} {r['variant']} {r['pass']}")
                for cells in by_ms[pair]:
                    self.assertRegex(cells[3], RATIO)
                    ratio = float(cells[3][:-1])
                    self.assertAlmostEqual(ratio, float(other["median_ms"]) / float(r["median_ms"]), delta=0.006)
                    self.assertRegex(cells[4], INTERVAL)
        self.assertEqual(sum(len(v) for v in by_ms.values()), expected)
        self.assertEqual(expected, 3 + 9)  # smoke: 4 less the unsupported one; oit: 12 less the dropped 3 passes
        self.assertIn(f"{expected} comparisons", proc.stdout)

    def test_cases_on_one_side_or_not_ok_are_listed_with_status_and_reason(self):
        _, index = self.build()
        rows = [cells for _, cells, _ in TableParser(read(index)).rows if len(cells) == 5 and cells[0] != "experiment"]
        dropped = [c for c in rows if "technique=BASE-RBS-L" in c[1] and "view=rev" in c[1]]
        self.assertEqual(len(dropped), 1, rows)
        self.assertEqual(dropped[0][2], "capture, resolve, total")
        self.assertTrue(dropped[0][3].startswith("ok "), dropped)
        self.assertEqual(dropped[0][4], "not in this run")
        unsupported = [c for c in rows if c[1].startswith("unrolled size=33")]
        self.assertEqual(len(unsupported), 1, rows)
        self.assertTrue(unsupported[0][3].startswith("ok "), unsupported)
        self.assertEqual(unsupported[0][4], "unsupported test: this driver lacks it")

    def test_the_same_inputs_give_the_same_bytes(self):
        self.build("one")
        self.build("two")
        files = []
        for root, _, names in os.walk(self.path("one")):
            files += [os.path.relpath(os.path.join(root, n), self.path("one")) for n in names]
        self.assertGreaterEqual(len(files), 1 + 2 * 3)  # the page, and per preset a PNG, an SVG and a CSV
        for rel in files:
            with open(os.path.join(self.path("one"), rel), "rb") as f1, \
                    open(os.path.join(self.path("two"), rel), "rb") as f2:
                self.assertEqual(f1.read(), f2.read(), f"{rel} differs between two pages of the same inputs")


if __name__ == "__main__":
    unittest.main()
