"""A grid of 2,000,000 cases through the binary (issue 27): without --max-cases raised it is refused with its
count before anything is built; with it raised the run starts, its resident memory stays bounded while the
first cases run (the grid is walked, never held: docs/usage.md#large-grids), and Ctrl-C keeps every finished
row (exit 130). OITBENCH_LARGE_GRID_EXE runs the same test against another binary (an eager one fails it)."""
import csv
import os
import signal
import subprocess
import time
import unittest

from support import TempDirTest, oitbench_exe

# 20 sizes x 100,000 seeds of the cheapest case: one draw of a 16x16 target, one repetition.
GRID = ["run", "occupancy", "--set", "variant=dynamic", "--set", "size=1..20", "--set", "seed=1..100000",
        "--set", "draws=1", "--resolution", "16x16", "--reps", "1", "--warmup", "0", "--min-sample-ms", "0",
        "--max-sample-ms", "0", "--no-progress"]
# What the first cases of any grid may hold resident: the process with its GL context (about 100-200 MB on
# llvmpipe). The same grid held in memory takes gigabytes (about 1 KB a case).
BOUND_KB = 600 * 1024
ROWS = 12  # finished rows to wait for before Ctrl-C


def exe():
    return os.environ.get("OITBENCH_LARGE_GRID_EXE") or oitbench_exe()


def peak_kb(pid):
    """The process's peak resident memory so far (VmHWM), or None once it is gone."""
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1])
    except OSError:
        return None
    return None


def data_rows(path):
    if not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        return [r for r in csv.DictReader(f) if r.get("pass") == "total"]


@unittest.skipUnless(exe(), "needs the binary (OITBENCH_EXE)")
class LargeGrid(TempDirTest):
    def test_refused_with_its_count_without_max_cases(self):
        r = subprocess.run([exe(), *GRID, "--out", self.path("refused.csv")], capture_output=True, text=True,
                           timeout=120)
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertIn("2000000 cases, more than 100000", r.stderr)
        self.assertIn("--max-cases", r.stderr)
        self.assertFalse(os.path.exists(self.path("refused.csv")), "a refused run wrote its --out")

    def test_runs_in_bounded_memory_and_ctrl_c_keeps_every_finished_row(self):
        out = self.path("run.csv")
        p = subprocess.Popen([exe(), *GRID, "--max-cases", "3000000", "--out", out], stdout=subprocess.DEVNULL,
                             stderr=subprocess.PIPE, text=True)
        peak = 0
        try:
            deadline = time.monotonic() + 400
            while len(data_rows(out)) < ROWS and p.poll() is None and time.monotonic() < deadline:
                peak = max(peak, peak_kb(p.pid) or 0)
                time.sleep(0.5)
            peak = max(peak, peak_kb(p.pid) or 0)
            self.assertIsNone(p.poll(), "the run ended before its first rows")
            self.assertGreaterEqual(len(data_rows(out)), ROWS, "no rows within 400 s")
            p.send_signal(signal.SIGINT)
            _, err = p.communicate(timeout=120)
        finally:
            if p.poll() is None:
                p.kill()
                p.wait()
        self.assertLess(peak, BOUND_KB, f"peak resident memory {peak} KB while the first cases ran")
        self.assertEqual(p.returncode, 130, err[-2000:])
        rows = data_rows(out)
        self.assertIn(f"interrupted; the {len(rows)} finished row(s) are in", err)
        self.assertTrue(all(r["status"] == "ok" for r in rows), [r["status"] for r in rows])
        # The first cases in grid order: size 1 with seeds 1, 2, 3, ...
        self.assertEqual([r["seed"] for r in rows], [str(k) for k in range(1, len(rows) + 1)])
        self.assertTrue(all(r["size"] == "1" for r in rows))


if __name__ == "__main__":
    unittest.main()
