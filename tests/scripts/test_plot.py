"""plot.py: a figure per experiment, valid rows only, invalid ones named; the registry's figures and the
generic fallback on synthetic runs, and the occupancy staircase on a real quick run when OITBENCH_EXE is set.
(The committed reference CSVs: test_reference_figures.py.)"""
import os
import re
import unittest

import synthetic as syn
from support import TempDirTest, oitbench_exe, run_oitbench, run_script

COUNT_LINE = re.compile(r"^(?P<label>\S+): (?P<exp>\S+): (?P<valid>\d+) valid rows, (?P<bad>\d+) not plotted; "
                        r"(?P<drawn>\d+) drawn, (?P<noted>\d+) named in the note -> ", re.M)


class PlotSynthetic(TempDirTest):
    def write_all(self):
        rows = (syn.occupancy_rows() + syn.sort_rows() + syn.oit_rows()
                + syn.simple_rows("layout", ["texture3d", "ssbo", "interleaved"], "size", [4, 8])
                + syn.simple_rows("spinlock", ["naive", "ordered"], "contention", ["low", "high"])
                + syn.simple_rows("stencil", ["stencil", "no-stencil"], "coverage", [0.1, 0.5, 1.0])
                + syn.simple_rows("newthing", ["a", "b"], "blocks", [1, 2, 4, 8]))
        return syn.write_summary(self.path("run.csv"), rows, metrics=syn.OCCUPANCY_METRICS + ["rmse", "max_abs_error"],
                                 params=syn.OCCUPANCY_PARAMS + ["n", "keys", "scene", "max_frags", "contention",
                                                                "coverage", "blocks"])

    def test_every_experiment_gets_a_png_and_an_svg(self):
        csv_path = self.write_all()
        out = self.path("fig")
        proc = run_script("plot.py", csv_path, "-o", out)
        for exp in ("occupancy", "sort", "oit", "layout", "spinlock", "stencil", "newthing"):
            self.assertPng(os.path.join(out, f"{exp}.png"))
            self.assertGreater(os.path.getsize(os.path.join(out, f"{exp}.svg")), 1000)
            self.assertIn(f"{exp}:", proc.stdout)

    def test_measured_occupancy_is_drawn_beside_the_model(self):
        rows = [dict(r, measured_occupancy="0.4375") for r in syn.occupancy_rows()]
        path = syn.write_summary(self.path("m.csv"), rows, syn.OCCUPANCY_METRICS + ["measured_occupancy"],
                                 syn.OCCUPANCY_PARAMS)
        run_script("plot.py", path, "-o", self.path("mfig"))
        with open(self.path("mfig/occupancy.svg"), encoding="utf-8") as f:
            svg = f.read()
        self.assertIn("measured occupancy (dynamic)", svg)
        self.assertIn("measured occupancy (unrolled)", svg)
        self.assertIn("predicted occupancy", svg)

    def test_invalid_rows_are_listed_not_plotted(self):
        proc = run_script("plot.py", self.write_all(), "-o", self.path("fig"))
        self.assertIn("occupancy: not plotted: unrolled size=128", proc.stdout)
        self.assertIn("42 pixels differ", proc.stdout)
        self.assertIn("spinlock-naive scene=planes max_frags=64: timeout", proc.stdout)
        self.assertIn("occupancy: 16 valid rows, 1 not plotted", proc.stdout)
        # The note is on the figure too (SVG keeps text as text).
        with open(self.path("fig/occupancy.svg"), encoding="utf-8") as f:
            svg = f.read()
        self.assertIn("not plotted", svg)

    def test_oit_error_is_drawn_against_memory_where_rows_carry_bytes_per_pixel(self):
        memory = {"base-is": 48, "weighted-blend": 20, "k-buffer": 100}
        rows = [dict(r, bytes_per_pixel=str(memory.get(r["variant"], 64))) for r in syn.oit_rows()
                if r.get("status") != "timeout"]
        path = syn.write_summary(self.path("mem.csv"), rows, metrics=["rmse", "max_abs_error", "bytes_per_pixel"],
                                 params=["scene", "max_frags"])
        run_script("plot.py", path, "-o", self.path("memfig"))
        with open(self.path("memfig/oit.svg"), encoding="utf-8") as f:
            svg = f.read()
        self.assertIn("rmse against memory", svg)
        self.assertIn("bytes per pixel", svg)
        self.assertIn("marker area: bytes/pixel, largest 100", svg)
        # Without the column the figure keeps its two rows and says nothing about memory.
        plain = syn.write_summary(self.path("plain.csv"), [{k: v for k, v in r.items() if k != "bytes_per_pixel"}
                                                            for r in rows], metrics=["rmse", "max_abs_error"],
                                  params=["scene", "max_frags"])
        run_script("plot.py", plain, "-o", self.path("plainfig"))
        with open(self.path("plainfig/oit.svg"), encoding="utf-8") as f:
            self.assertNotIn("against memory", f.read())

    def test_an_experiment_in_two_files_gets_two_figures(self):
        a = syn.write_summary(self.path("a.csv"), syn.occupancy_rows(), syn.OCCUPANCY_METRICS, syn.OCCUPANCY_PARAMS)
        b = syn.write_summary(self.path("b.csv"), syn.occupancy_rows(draws=32), syn.OCCUPANCY_METRICS,
                              syn.OCCUPANCY_PARAMS)
        run_script("plot.py", a, b, "-o", self.path("fig"))
        self.assertPng(self.path("fig/occupancy-a.png"))
        self.assertPng(self.path("fig/occupancy-b.png"))

    def test_a_raw_file_is_refused_with_a_clear_message(self):
        syn.write_summary(self.path("run.csv"), syn.sort_rows(), params=["n", "keys"], raw_path=self.path("raw.csv"))
        proc = run_script("plot.py", self.path("raw.csv"), "-o", self.path("fig"), check=False)
        self.assertEqual(proc.returncode, 2)
        self.assertIn("--raw file", proc.stderr)

    def test_a_run_with_nothing_valid_still_gives_a_figure(self):
        rows = [dict(r, status="error", reason="link failed") for r in syn.sort_rows()[:3]]
        csv_path = syn.write_summary(self.path("bad.csv"), rows, params=["n", "keys"])
        proc = run_script("plot.py", csv_path, "-o", self.path("fig"))
        self.assertPng(self.path("fig/sort.png"))
        self.assertIn("link failed", proc.stdout)


    def test_a_valid_row_no_panel_draws_is_named_and_counted(self):
        rows = [r for r in syn.oit_rows() if r.get("status") != "timeout"]
        # A pass of a case whose total row is missing: no bar can carry it.
        rows.append({"experiment": "oit", "variant": "orphan", "pass": "capture", "scene": "planes", "max_frags": 64,
                     "median_ms": 3.0})
        path = syn.write_summary(self.path("orphan.csv"), rows, metrics=["rmse", "max_abs_error"],
                                 params=["scene", "max_frags"])
        proc = run_script("plot.py", path, "-o", self.path("fig"))
        m = COUNT_LINE.search(proc.stdout)
        self.assertEqual((m["exp"], m["valid"], m["drawn"], m["noted"]), ("oit", str(len(rows)), str(len(rows) - 1), "1"),
                         proc.stdout)
        self.assertIn("orphan scene=planes max_frags=64 pass=capture: valid, not drawn", proc.stdout)
        with open(self.path("fig/oit.svg"), encoding="utf-8") as f:
            self.assertIn("valid rows not drawn", f.read())

    def test_cases_that_differ_only_in_capture_get_bars_of_their_own(self):
        rows = []
        for capture, ms in (("PPLL", 10.0), ("PPPA", 20.0)):
            for p, share in (("capture", 0.4), ("resolve", 0.6), ("total", 1.0)):
                rows.append({"experiment": "oit", "variant": "", "technique": "BASE-IMS", "capture": capture,
                             "scene": "planes", "view": "fwd", "pass": p, "median_ms": ms * share})
        path = syn.write_summary(self.path("cap.csv"), rows, params=["technique", "capture", "scene", "view"])
        proc = run_script("plot.py", path, "-o", self.path("fig"))
        self.assertRegex(proc.stdout, r"oit: 6 valid rows, 0 not plotted; 6 drawn, 0 named")
        with open(self.path("fig/oit.svg"), encoding="utf-8") as f:
            svg = f.read()
        self.assertIn("BASE-IMS capture=PPLL", svg)
        self.assertIn("BASE-IMS capture=PPPA", svg)

    def test_the_sort_figure_splits_by_family_with_at_most_eight_curves_a_panel(self):
        rows = []
        variants = ["insertion-a", "insertion-b", "insertion-c", "insertion-d", "insertion-e", "bubble", "bubble-early",
                    "bitonic", "odd-even-merge", "shell", "rbs", "newsort-x"]
        for v in variants:
            for memory in ("local", "registers"):
                for n in (4, 8, 16):
                    rows.append({"experiment": "sort", "variant": v, "pass": "total", "n": n, "memory": memory,
                                 "median_ms": n * (1 + len(v) / 10)})
        path = syn.write_summary(self.path("s.csv"), rows, params=["n", "memory"])
        run_script("plot.py", path, "-o", self.path("fig"))
        with open(self.path("fig/sort.svg"), encoding="utf-8") as f:
            svg = f.read()
        for title in ("insertion, part 1/2", "insertion, part 2/2", "bubble", "merge networks", "shell", "rbs",
                      "newsort", "n (fragments per pixel)"):
            self.assertIn(title, svg)


@unittest.skipUnless(oitbench_exe(), "OITBENCH_EXE not set (ctest sets it)")
class PlotRealRun(TempDirTest):
    def test_occupancy_quick_run(self):
        csv_path = self.path("occ.csv")
        run_oitbench("run", "occupancy", "--quick", "--set", "size=1,8,32,33", "--set", "draws=2",
                     "--resolution", "64x64", "--out", csv_path)
        proc = run_script("plot.py", csv_path, "-o", self.path("fig"))
        self.assertPng(self.path("fig/occupancy.png"))
        self.assertIn("occupancy: 8 valid rows, 0 not plotted", proc.stdout)


if __name__ == "__main__":
    unittest.main()
