"""scripts/gpu-run.sh --smoke: the prepared GPU run, at tiny sizes, on both drivers this machine has
(llvmpipe and zink over lavapipe). Every step must run, every row be ok (or unsupported with a reason),
the rows name the driver and the paper preset, and the report page be written."""
import csv
import os
import shutil
import subprocess
import tempfile
import unittest

from support import oitbench_exe
from synthetic import SCRIPTS

STEPS = ["occupancy", "sort", "knowles2014", "knowles2014-engine-grid", "bruell2018-approx"]


@unittest.skipUnless(oitbench_exe(), "needs the oitbench binary (OITBENCH_EXE)")
class GpuRunSmoke(unittest.TestCase):
    def smoke(self, driver, slug):
        out = tempfile.mkdtemp(prefix=f"oitbench-gpu-run-{driver}-")
        self.addCleanup(shutil.rmtree, out, ignore_errors=True)
        env = dict(os.environ, OITBENCH=oitbench_exe(), MPLBACKEND="Agg")
        proc = subprocess.run([os.path.join(SCRIPTS, "gpu-run.sh"), "--smoke", "--driver", driver, "--out", out],
                              env=env, capture_output=True, text=True, timeout=900)
        self.assertEqual(proc.returncode, 0, proc.stdout[-3000:] + proc.stderr[-3000:])
        self.assertIn("gpu-run.sh: done", proc.stdout)
        self.assertIn("gpu-run.sh: time: all steps: ", proc.stdout)  # the time account
        self.assertIn("gpu-run.sh: time: knowles2014: ", proc.stdout)
        # The projection of the full run on a GPU (issue 28): every step's full-size cases from --dry-run.
        for step in STEPS:
            self.assertRegex(proc.stdout, rf"gpu-run.sh: projection: {step}: [1-9][0-9]* cases: outside the samples ")
        self.assertIn("gpu-run.sh: projection: all steps: about ", proc.stdout)
        for step in STEPS:
            path = os.path.join(out, "presets", step + ".csv")
            self.assertTrue(os.path.exists(path), step)
            with open(path, newline="") as f:
                rows = list(csv.DictReader(f))
            self.assertTrue(rows, step)
            for r in rows:
                self.assertIn(r["status"], ("ok", "unsupported"), f"{step}: {r['parameters']}: {r['reason']}")
                if r["status"] == "unsupported":
                    self.assertTrue(r["reason"], step)
                self.assertEqual(r["driver"], slug, step)
            self.assertTrue(any(r["status"] == "ok" for r in rows), step)
            if step.startswith("knowles2014"):
                self.assertEqual({r["preset"] for r in rows}, {"knowles2014"})
        self.assertTrue(os.path.exists(os.path.join(out, "report", "index.html")))
        with open(os.path.join(out, "info.txt")) as f:
            self.assertIn("GL_RENDERER:", f.read())
        with open(os.path.join(out, "device.txt")) as f:  # the --device auto step (docs/ci.md)
            self.assertIn("--device auto -> EGL device", f.read())

    def test_smoke_on_llvmpipe(self):
        self.smoke("llvmpipe", "llvmpipe")

    def test_smoke_on_zink(self):
        self.smoke("zink", "zink-lavapipe")

    def test_dry_run_runs_nothing(self):
        # --dry-run prints the plan at the sizes asked and opens no CSV.
        out = tempfile.mkdtemp(prefix="oitbench-dry-run-")
        self.addCleanup(shutil.rmtree, out, ignore_errors=True)
        csv_path = os.path.join(out, "never.csv")
        proc = subprocess.run([oitbench_exe(), "run", "--dry-run", "--driver", "llvmpipe", "oit", "--set",
                               "scene=planes,hairball", "--set", "view=fwd,rev", "--set", "technique=BASE-IS,BMA-IS",
                               "--resolution", "1920x1080", "--reps", "5", "--out", csv_path],
                              capture_output=True, text=True, timeout=120)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertIn("plan: oit 1920x1080 cases=8 reps=5 warmup=1", proc.stdout)
        self.assertIn("dry run: 8 case(s)", proc.stdout)
        self.assertFalse(os.path.exists(csv_path))
        from oitbench import gpuprojection
        self.assertEqual(gpuprojection.parse_plan(proc.stdout), [("oit", "1920x1080", 8, 5, 1)])
        self.assertEqual(gpuprojection.parse_plan("plan: oit 192x192 cases=6 reps=auto (6-30) warmup=1"),
                         [("oit", "192x192", 6, 30, 1)])

    def test_bad_arguments_exit_two(self):
        proc = subprocess.run([os.path.join(SCRIPTS, "gpu-run.sh"), "--nosuch"], capture_output=True, text=True)
        self.assertEqual(proc.returncode, 2)
        self.assertIn("unknown argument", proc.stderr)


if __name__ == "__main__":
    unittest.main()
