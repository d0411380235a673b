"""report.py: one static HTML page from runs, checked in a real headless browser (Debian's chromium): the
page loads, every image decodes and the figures are all there, and a figure deleted afterwards is caught.
Also: the metadata and every failed case with its reason, the paper tables, a results folder searched by
header (summary files only), the same page from the same results, and errors that exit 2."""
import html.parser
import json
import os
import shutil
import struct
import subprocess
import tempfile
import unittest
import zlib

import synthetic as syn
from support import PNG_MAGIC, TempDirTest, run_script
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


if __name__ == "__main__":
    unittest.main()
