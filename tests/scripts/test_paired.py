"""tables.py's paired speedups (issue 17): rows whose case ran beside its baseline carry `speedup` and its
interval; paired_speedups() reads them, best_paired_speedups() takes the best resolve per view, and
`tables.py --paired` prints both."""
import sys
import unittest

from support import TempDirTest, run_script
from synthetic import SCRIPTS

sys.path.insert(0, SCRIPTS)
from oitbench import papers as tables  # noqa: E402


def row(tech, view, pas, speedup, status="ok"):
    return {"experiment": "oit", "technique": tech, "scene": "planes", "view": view, "pass": pas, "status": status,
            "valid": "1" if status == "ok" else "0", "width": "128", "height": "128", "baseline": "technique=BASE-IS",
            "speedup": speedup, "speedup_ci_lo": "1" if speedup else "", "speedup_ci_hi": "9" if speedup else ""}


class PairedTest(TempDirTest):
    ROWS = [row("BASE-IS", "rev", "resolve", ""), row("BMA-IS", "rev", "resolve", "2.5"),
            row("BASE-IMS", "rev", "resolve", "4.0"), row("BASE-IMS", "rev", "total", "3.0"),
            row("RBS-G", "rev", "resolve", "9.0", status="invalid"), row("BMA-IS", "fwd", "resolve", "1.5")]

    def test_only_ok_rows_with_a_speedup(self):
        got = tables.paired_speedups(self.ROWS)
        self.assertEqual([(p["technique"], p["view"], p["pass"]) for p in got],
                         [("BMA-IS", "rev", "resolve"), ("BASE-IMS", "rev", "resolve"), ("BASE-IMS", "rev", "total"),
                          ("BMA-IS", "fwd", "resolve")])
        self.assertEqual(got[0]["ci_lo"], 1.0)

    def test_the_best_resolve_per_view(self):
        best = tables.best_paired_speedups(self.ROWS)
        self.assertEqual(best[("planes", "rev", "128x128")]["technique"], "BASE-IMS")  # the invalid 9x is out
        self.assertEqual(best[("planes", "fwd", "128x128")]["speedup"], 1.5)

    def test_the_command_prints_them(self):
        import os
        csv_path = os.path.join(os.path.dirname(SCRIPTS), "results", "ab-llvmpipe", "knowles", "run-1.csv")
        out = run_script("tables.py", "--paired", csv_path).stdout
        self.assertIn("Best resolve speedup per view", out)
        self.assertIn("| planes | rev | 128x128 |", out)


if __name__ == "__main__":
    unittest.main()
