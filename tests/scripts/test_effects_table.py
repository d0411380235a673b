"""effects_table.py: docs/effects.md's table of what the opaque effect saves is what the script makes
of the committed measurement (results/effects/), and a CSV without two effect sets per case exits 2."""
import csv
import os
import unittest

from support import TempDirTest, run_script

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MEASURED = os.path.join(REPO, "results", "effects", "house-opaque-128.csv")
DOC = os.path.join(REPO, "docs", "effects.md")


class EffectsTable(TempDirTest):
    def test_the_docs_table_is_generated_from_the_committed_csv(self):
        table = run_script("effects_table.py", MEASURED).stdout
        with open(DOC, encoding="utf-8") as f:
            doc = f.read()
        begin = doc.index("-->\n", doc.index("<!-- generated: scripts/effects_table.py")) + len("-->\n")
        end = doc.index("<!-- end of effects table -->")
        self.assertEqual(doc[begin:end], table, "docs/effects.md's effects table is stale; regenerate it with\n"
                         "  scripts/effects_table.py results/effects/house-opaque-128.csv")

    def test_the_opaque_effect_captures_fewer_fragments_in_every_case(self):
        lines = run_script("effects_table.py", MEASURED).stdout.splitlines()[2:]
        by_case = {}
        for line in lines:
            cells = [c.strip() for c in line.strip("|").split("|")]
            by_case.setdefault(tuple(cells[:3]), {})[cells[3]] = float(cells[4].replace(",", ""))
        self.assertTrue(by_case)
        for case, sets in by_case.items():
            self.assertLess(sets["opaque+transparency"], sets["transparency"], case)

    def test_one_effect_set_per_case_exits_2(self):
        with open(MEASURED, newline="", encoding="utf-8") as f:
            reader = csv.DictReader(f)
            header, rows = reader.fieldnames, [r for r in reader if r["effects"] == "transparency"]
        path = self.path("one.csv")
        with open(path, "w", newline="", encoding="utf-8") as f:
            w = csv.DictWriter(f, fieldnames=header)
            w.writeheader()
            w.writerows(rows)
        proc = run_script("effects_table.py", path, check=False)
        self.assertEqual(proc.returncode, 2, proc.stderr)
        self.assertIn("more than one effect set", proc.stderr)


if __name__ == "__main__":
    unittest.main()
