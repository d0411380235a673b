"""ab.py: the rounds alternate A B B A ..., the pairing pairs (round k of A with round k of B, a --set
parameter left out of the key), identical configurations on a drifting machine are not flagged, a 9.4 %
slower one is, and a failing run is an exit code 1 with the rest kept. A fake oitbench (a Python script)
writes each round's CSV: the whole machine drifts by up to +-40 % from run to run, so only pairing resolves
the difference."""
import csv
import os
import stat
import sys
import unittest

from support import TempDirTest, run_script
from synthetic import SCRIPTS

sys.path.insert(0, SCRIPTS)
from oitbench import ab, stats  # noqa: E402

FAKE = r'''#!/usr/bin/python3
import csv, math, os, sys
args = sys.argv[1:]
out = args[args.index("--out") + 1]
raw = args[args.index("--raw") + 1]
draws = 64
for i, a in enumerate(args):
    if a == "--set" and args[i + 1].startswith("draws="):
        draws = int(args[i + 1].split("=")[1])
counter = os.environ["FAKE_COUNTER"]
n = int(open(counter).read()) if os.path.exists(counter) else 0
open(counter, "w").write(str(n + 1))
if os.environ.get("FAKE_FAIL_CALL") == str(n):
    sys.exit(1)
with open(os.environ["FAKE_LOG"], "a") as log:
    log.write(os.environ.get("FAKE_NAME", "?") + "\n")
machine = 1 + 0.4 * math.sin(1.3 * (n // 2))   # the pair's two runs see the same machine
cols = ["experiment", "variant", "pass", "status", "valid", "reason", "width", "height", "reps", "warmup",
        "median_ms", "parameters", "size", "draws", "seed", "fault", "driver", "gl_renderer", "git_sha",
        "lp_num_threads", "env"]
with open(out, "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(cols)
    for size in (1, 33):
        jitter = 1 + 0.004 * math.sin(7.1 * n + size)
        ms = size * draws / 64 * machine * jitter
        w.writerow(["occupancy", "dynamic", "draw", "ok", 1, "", 64, 64, 10, 2, ms, "size;draws;fault;seed", size,
                    draws, 1, "none", "llvmpipe", "llvmpipe (fake)", "abc", 2, ""])
open(raw, "w").close()
'''


class AbTest(TempDirTest):
    def setUp(self):
        super().setUp()
        self.exe = self.path("fake-oitbench")
        with open(self.exe, "w") as f:
            f.write(FAKE)
        os.chmod(self.exe, os.stat(self.exe).st_mode | stat.S_IEXEC)
        os.environ["FAKE_COUNTER"] = self.path("counter")
        os.environ["FAKE_LOG"] = self.path("log")
        os.environ.pop("FAKE_FAIL_CALL", None)

    def ab(self, *extra, check=True):
        return run_script("ab.py", "--rounds", 8, "-o", self.path("out"), "--a-exe", self.exe, "--b-exe",
                          self.exe, "--a-env", "FAKE_NAME=A", "--b-env", "FAKE_NAME=B", *extra, "--",
                          "occupancy", check=check)

    def table(self):
        with open(self.path("out/ab.csv"), newline="") as f:
            return list(csv.DictReader(f))

    def test_rounds_alternate_a_b_b_a(self):
        self.assertEqual([c for c, _ in ab.round_order(3)], ["A", "B", "B", "A", "A", "B"])
        self.ab()
        with open(self.path("log")) as f:
            self.assertEqual(f.read().split(), ["A", "B", "B", "A"] * 4)

    def test_identical_configurations_are_not_flagged(self):
        proc = self.ab()
        rows = self.table()
        self.assertEqual(len(rows), 2, proc.stdout)
        for r in rows:
            self.assertEqual(r["flagged"], "0", proc.stdout)
            self.assertEqual(int(r["pairs"]), 8)
            self.assertLess(abs(float(r["ratio"]) - 1), 0.01)
            # Unpaired, the machine's drift (+-40 %) would dominate: the noise column says how much.
            self.assertGreater(float(r["noise_pct"]), 10)
        self.assertIn("0 of 2 case(s) flagged", proc.stdout)
        self.assertPng(self.path("out/ab-occupancy.png"))

    def test_a_set_difference_pairs_and_is_flagged(self):
        proc = self.ab("--a-args", "--set draws=64", "--b-args", "--set draws=70")
        rows = self.table()
        self.assertEqual(len(rows), 2, proc.stdout)  # draws is out of the key, so the cases pair
        for r in rows:
            self.assertEqual(r["verdict"], "SLOWER", proc.stdout)
            self.assertNotIn("draws=", r["case"])
            self.assertGreater(float(r["ci_low"]), 1.04)
            self.assertLess(float(r["ci_high"]), 1.15)
            self.assertAlmostEqual(float(r["ratio"]), 70 / 64, delta=0.01)

    def test_trials_are_summarized(self):
        self.ab("--a-args", "--set draws=64", "--b-args", "--set draws=70")
        out = run_script("ab.py", "--summarize", self.path("out"), self.path("out")).stdout
        self.assertIn("2 trial(s); 2 with a flagged case", out)
        self.assertIn("slower in 2/2, faster in 0/2", out)
        self.assertIn("pooled over the trials: 16 round pairs, ratio 1.09", out)

    def test_a_failed_run_is_exit_1_and_the_rest_compared(self):
        os.environ["FAKE_FAIL_CALL"] = "3"
        proc = self.ab(check=False)
        self.assertEqual(proc.returncode, 1, proc.stdout + proc.stderr)
        self.assertIn("failed runs: A round 2", proc.stderr)
        for r in self.table():
            self.assertEqual(int(r["pairs"]), 7)  # round 2 left out whole: the others stay paired
            self.assertEqual(r["flagged"], "0")

    def test_usage_errors(self):
        proc = run_script("ab.py", "-o", self.path("x"), check=False)
        self.assertEqual(proc.returncode, 2)
        proc = run_script("ab.py", "--", "occupancy", "--out", "x.csv", check=False)
        self.assertEqual(proc.returncode, 2)
        self.assertIn("--out is ab.py's to set", proc.stderr)

    def test_too_few_rounds_say_so(self):
        self.assertEqual(stats.pairs_needed(1), 6)
        self.assertEqual(stats.pairs_needed(2), 7)
        proc = run_script("ab.py", "--rounds", 6, "-o", self.path("out"), "--a-exe", self.exe, "--b-exe", self.exe,
                          "--", "occupancy")
        self.assertIn("need at least 7 round pairs", proc.stdout)

    def test_the_interval_is_the_sampling_rule_one(self):
        self.assertIsNone(ab.median_interval([1, 2, 3, 4, 5], 0.95))
        self.assertEqual(ab.median_interval(list(range(1, 10)), 0.95), (2, 8))
        self.assertEqual(ab.median_interval(list(range(1, 101)), 0.95), (40, 61))


if __name__ == "__main__":
    unittest.main()
