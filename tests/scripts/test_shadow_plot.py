"""shadow_plot.py: the self-shadowing figure from the committed measurement (results/self-shadowing/),
invalid rows left out, and exit 2 when no row has the effect."""
import csv
import os
import unittest

from support import TempDirTest, run_script

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MEASURED = os.path.join(REPO, "results", "self-shadowing", "hairball-lit-128.csv")


class ShadowPlot(TempDirTest):
    def test_the_committed_measurement_gives_a_figure(self):
        out = self.path("shadow.png")
        run_script("shadow_plot.py", MEASURED, "--out", out)
        self.assertPng(out)

    def test_rows_without_the_effect_or_invalid_exit_2(self):
        with open(MEASURED, newline="", encoding="utf-8") as f:
            reader = csv.DictReader(f)
            header, rows = reader.fieldnames, list(reader)
        for r in rows:
            r["valid"] = "0"
        path = self.path("invalid.csv")
        with open(path, "w", newline="", encoding="utf-8") as f:
            w = csv.DictWriter(f, fieldnames=header)
            w.writeheader()
            w.writerows(rows)
        proc = run_script("shadow_plot.py", path, "--out", self.path("none.png"), check=False)
        self.assertEqual(proc.returncode, 2, proc.stderr)
        self.assertIn("no valid oit rows", proc.stderr)
        self.assertFalse(os.path.exists(self.path("none.png")))


if __name__ == "__main__":
    unittest.main()
