"""scripts/oitbench/timeaccount.py's account of scripts/reference_runs.sh (list_lines): one line per preset
with its wall time and its cases' shares, one per list with the list's total and shares, the rest of the
list's wall time, and a CSV without an account (an older schema) or one that cannot be read named, never
a traceback. Read from a committed reference CSV (resolve-speedups) and a copy of default.csv without the
account's columns (the schema before them), so the test holds whatever run the committed files came from."""
import os
import re
import shutil
import unittest

from support import TempDirTest, edit_csv
from synthetic import SCRIPTS
from oitbench import timeaccount

PRESETS = os.path.join(os.path.dirname(SCRIPTS), "results", "llvmpipe", "presets")


class ReferenceRunsAccount(TempDirTest):
    def test_each_preset_and_each_list(self):
        # default.csv as the schema before the account wrote it: no case_wall_s, no phase_*_s.
        older = shutil.copy(os.path.join(PRESETS, "default.csv"), self.path("default.csv"))
        def account(k):
            return k == "case_wall_s" or k.startswith("phase_")
        edit_csv(older, lambda header, rows: ([k for k in header if not account(k)],
                                              [{k: v for k, v in r.items() if not account(k)} for r in rows]))
        with_account = os.path.join(PRESETS, "resolve-speedups.csv")
        acc = timeaccount.accounts_of_file(with_account)
        self.assertGreater(acc.cases, 0)
        lines = timeaccount.list_lines([("default", "resolve-speedups", acc.wall + 30, with_account),
                                        ("default", "default", 17, older),
                                        ("opt-in", "missing", 5, os.path.join(PRESETS, "nosuch.csv"))])
        text = "\n".join(lines)
        self.assertIn(f"resolve-speedups (default): {timeaccount.minutes(acc.wall + 30)}; {acc.cases} cases: "
                      "timed samples ", text)
        self.assertIn("default (default): 0m17s; no time account in its rows", text)
        self.assertRegex(text, r"missing: .*nosuch\.csv")
        default = [line for line in lines if "the default list:" in line]
        self.assertEqual(len(default), 1)
        self.assertIn(f"2 preset(s), {timeaccount.minutes(acc.wall + 47)}; its {acc.cases} cases", default[0])
        # The shares of the list's cases add up to their wall time (the account's own rule: within 5%).
        shares = [float(s) for s in re.findall(r" ([0-9.]+) s \(\d+%\)", default[0].split("; the rest")[0])]
        self.assertAlmostEqual(sum(shares), acc.wall, delta=0.05 * acc.wall)
        self.assertRegex(default[0], r"the rest of its wall time 4[67] s")
        self.assertIn("the opt-in list: 1 preset(s), 0m05s", text)

    def test_minutes(self):
        self.assertEqual(timeaccount.minutes(0), "0m00s")
        self.assertEqual(timeaccount.minutes(725.4), "12m05s")


if __name__ == "__main__":
    unittest.main()
