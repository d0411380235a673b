"""shadow_plot.py: the self-shadowing figure from the committed measurement (results/self-shadowing/),
invalid rows left out, exit 2 when no row has the effect, and docs/effects.md's table is what the
script makes of the committed CSV (regenerate it with --table after a new measurement)."""
import csv
import os
import unittest

from support import TempDirTest, run_script

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MEASURED = os.path.join(REPO, "results", "self-shadowing", "hairball-lit-128.csv")
HAIR = os.path.join(REPO, "results", "self-shadowing", "hair-128.csv")
DOC = os.path.join(REPO, "docs", "effects.md")


class ShadowPlot(TempDirTest):
    def test_the_committed_measurement_gives_a_figure(self):
        out = self.path("shadow.png")
        run_script("shadow_plot.py", MEASURED, "--out", out)
        self.assertPng(out)

    def test_the_docs_table_is_generated_from_the_committed_csv(self):
        table = run_script("shadow_plot.py", MEASURED, HAIR, "--table").stdout
        with open(DOC, encoding="utf-8") as f:
            doc = f.read()
        begin = doc.index("-->\n", doc.index("<!-- generated: scripts/shadow_plot.py")) + len("-->\n")
        end = doc.index("<!-- end of generated table -->")
        self.assertEqual(doc[begin:end], table, "docs/effects.md's table is stale; regenerate it with\n"
                         "  scripts/shadow_plot.py results/self-shadowing/hairball-lit-128.csv "
                         "results/self-shadowing/hair-128.csv --table")

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
