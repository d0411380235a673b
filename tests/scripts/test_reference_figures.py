"""The committed reference runs under results/ through the scripts, as a user regenerates the pages:
every valid row of every summary CSV drawn by plot.py or named in its figure's note (drawn + noted =
valid rows), the knowles2014 figure with all nine views, and the report of the papers' presets with the
figures of ours against the paper and the fastest-technique summary, checked in headless chromium.
Minutes of drawing on a busy machine: its own ctest entry (scripts.reference_figures) with a longer timeout."""
import csv
import os
import re
import shutil
import unittest

import synthetic as syn
import test_report
from support import TempDirTest, run_script
from test_plot import COUNT_LINE

RESULTS = os.path.join(os.path.dirname(syn.SCRIPTS), "results")


class PlotReferenceCsvs(TempDirTest):
    """Every committed summary CSV under results/ (the reference runs, the effects, techniques and
    self-shadowing runs, the rendered images' rows): drawn rows + rows named in the note = valid rows."""

    def reference_csvs(self):
        found = []
        for root, dirs, files in os.walk(RESULTS):
            dirs[:] = sorted(d for d in dirs if not os.path.isfile(os.path.join(root, d, "index.html")))
            for f in sorted(files):
                path = os.path.join(root, f)
                if f.endswith(".csv") and not f.endswith("_raw.csv"):
                    with open(path, newline="", encoding="utf-8") as fh:
                        header = next(csv.reader(fh), [])
                    if "experiment" in header and "median_ms" in header:
                        found.append(path)
        return found

    @staticmethod
    def valid_rows(path):
        with open(path, newline="", encoding="utf-8") as f:
            rows = list(csv.DictReader(f))
        out = {}
        for r in rows:
            if r["status"] == "ok" and r["valid"] == "1":
                out[r["experiment"]] = out.get(r["experiment"], 0) + 1
        return out

    def test_every_valid_row_is_drawn_or_named_in_the_note(self):
        csvs = self.reference_csvs()
        self.assertGreater(len(csvs), 15, csvs)
        # --format none: every figure drawn and counted, no file written (the files cost minutes here).
        proc = run_script("plot.py", *csvs, "-o", self.path("fig"), "--format", "none", timeout=1500)
        counted = {}
        for m in COUNT_LINE.finditer(proc.stdout):
            self.assertEqual(int(m["drawn"]) + int(m["noted"]), int(m["valid"]), m.group(0))
            counted.setdefault(m["exp"], []).append(int(m["valid"]))
        expected = {}
        for path in csvs:
            for exp, n in self.valid_rows(path).items():
                expected.setdefault(exp, []).append(n)
        self.assertEqual({k: sorted(v) for k, v in counted.items()}, {k: sorted(v) for k, v in expected.items()})
        # The committed runs need no note: every valid row of them is in a panel.
        self.assertNotIn("valid, not drawn", proc.stdout)

    def test_the_knowles2014_figure_shows_all_nine_views(self):
        path = os.path.join(RESULTS, "llvmpipe", "presets", "knowles2014.csv")
        proc = run_script("plot.py", path, "-o", self.path("k"), "--format", "svg", timeout=900)
        self.assertRegex(proc.stdout, r"oit: 405 valid rows, 0 not plotted; 405 drawn, 0 named in the note")
        with open(self.path("k/oit.svg"), encoding="utf-8") as f:
            svg = f.read()
        for view in ("scene=planes, view=fwd", "scene=planes, view=rev", "scene=hairball, view=fwd",
                     "scene=hairball, view=rev", "scene=engine-grid, view=V1", "scene=engine-grid, view=V2",
                     "scene=engine-grid, view=V3", "scene=house, view=V1", "scene=house, view=V2"):
            self.assertIn(view, svg)
        self.assertIn("every technique exact: no error panels", svg)
        self.assertNotIn("against time", svg)



class ReportPaperFigures(test_report.ReportCase):
    """The committed reference runs at the papers' presets (and Knowles 2014's quick variant beside them):
    the figure of ours against the paper beside each paper table, the fastest-technique summary, all
    decoding in headless chromium, and each table opened on the run at its paper's preset."""
    PRESETS = ("knowles2014", "knowles2014-quick", "knowles2013", "bruell2018-sorting", "bruell2018-approx",
               "bruell2018-stencil", "bruell2018-storage")
    # Knowles 2014 tables 1 to 3, Knowles 2013 tables 1 and 2, Brüll's tables with our rows.
    PAPER_FIGURES = ("knowles2014-1", "knowles2014-2", "knowles2014-3", "knowles2013-1", "knowles2013-2",
                     "bruell-a-1", "bruell-a-2", "bruell-a-3", "bruell-a-4", "bruell-4-1", "bruell-5-1", "bruell-6-1")

    def setUp(self):
        super().setUp()
        if not os.access(test_report.CHROMIUM, os.X_OK):
            self.fail(f"{test_report.CHROMIUM} not found: run scripts/deps.sh")

    def test_ours_against_the_paper_and_the_fastest_technique_load(self):
        results = os.path.join(os.path.dirname(syn.SCRIPTS), "results", "llvmpipe", "presets")
        os.makedirs(self.path("runs/presets"))
        for name in self.PRESETS:
            for suffix in (".csv", "_raw.csv"):
                if os.path.isfile(os.path.join(results, name + suffix)):
                    shutil.copy(os.path.join(results, name + suffix), self.path("runs/presets"))
        proc = run_script("report.py", self.path("runs"), "-o", self.path("report"), timeout=1500)
        self.assertIn("a fastest-technique summary", proc.stdout)
        index = self.path("report/index.html")
        parsed = test_report.PageParser(test_report.read(index)).images
        paper = [src for src, cls in parsed if cls == "paper-figure"]
        for name in self.PAPER_FIGURES:
            self.assertIn(f"figures/tables/{name}.png", paper)
        self.assertEqual([src for src, cls in parsed if cls == "summary-figure"], ["figures/fastest.png"])
        images, _, broken, dom = test_report.browser_check(index)
        body = test_report.PageParser(dom).body
        self.assertEqual(broken, [])
        self.assertEqual(images, len(parsed))
        self.assertEqual(int(body["data-paper-figures"]), len(paper))
        self.assertEqual(int(body["data-summary-figures"]), 1)
        # The table of Knowles 2014 opens on the run at its preset, not the quick one beside it.
        page = test_report.read(index)
        section = page[page.index('id="table-knowles2014-1"'):page.index('id="table-knowles2014-2"')]
        opened = re.search(r'<details class="table-run" open><summary>ours from <code>([^<]*)</code>', section)
        self.assertEqual(opened.group(1), "presets/knowles2014.csv")
        self.assertIn("paper: NVIDIA GTX Titan", test_report.read(self.path("report/figures/tables/knowles2014-3.svg")))


if __name__ == "__main__":
    unittest.main()
