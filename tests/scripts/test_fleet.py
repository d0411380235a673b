"""Runs over a fleet and in CI through the binary (issue 26): --shard parts that together are the whole grid,
--expect's exit codes (0 when every outcome is expected, 4 naming a case that is not; a run's own list
expects it), --write-expect, the JUnit report in the shape GitLab reads, and the bad input of each."""
import csv
import json
import os
import subprocess
import unittest
import xml.etree.ElementTree as ET

from support import TempDirTest, oitbench_exe

# Two cheap cases; the "-fault" preset is the same two with the fault injected into the second.
TWO = {"description": "two cases", "runs": [
    {"experiment": "occupancy", "quick": True, "reps": 1, "set": {"variant": ["dynamic"], "size": [1, 2]}}]}
TWO_FAULT = {"description": "the same two, the second broken", "runs": [
    {"experiment": "occupancy", "quick": True, "reps": 1, "set": {"variant": ["dynamic"], "size": [1]}},
    {"experiment": "occupancy", "quick": True, "reps": 1,
     "set": {"variant": ["dynamic"], "size": [2], "fault": ["wrong-result"]}}]}
SECOND = "occupancy/200x150/variant=dynamic/size=2/draws=8/model_gpu=auto/seed=1"


@unittest.skipUnless(oitbench_exe(), "needs the binary (OITBENCH_EXE)")
class Fleet(TempDirTest):
    def setUp(self):
        super().setUp()
        os.mkdir(self.path("presets"))
        for name, preset in {"two": TWO, "two-fault": TWO_FAULT}.items():
            with open(self.path(f"presets/{name}.json"), "w") as f:
                json.dump(preset, f)

    def oitbench(self, *args, env=None):
        return subprocess.run([oitbench_exe(), *map(str, args)], capture_output=True, text=True, timeout=300,
                              env=env, cwd=self.dir)

    def run_preset(self, preset, *args):
        return self.oitbench("run", "--presets-dir", self.path("presets"), "--preset", preset, "--no-progress",
                             *args)

    def test_a_runs_own_list_expects_it_and_a_fault_fails_naming_the_case(self):
        first = self.run_preset("two", "--out", "a.csv", "--write-expect", "E")
        self.assertEqual(first.returncode, 0, first.stderr)
        again = self.run_preset("two", "--out", "b.csv", "--expect", "E")
        self.assertEqual(again.returncode, 0, again.stderr)
        self.assertIn("0 unexpected", again.stderr)
        broken = self.run_preset("two-fault", "--out", "c.csv", "--expect", "E")
        self.assertEqual(broken.returncode, 4, broken.stderr)
        self.assertIn(f"unexpected: {SECOND}: new invalid", broken.stderr)
        # Its list (beside the CSV) expects the broken case: with it, the broken run passes; the fixed one
        # fails, saying "fixed".
        with open(self.path("c.csv.expect")) as f:
            listed = f.read()
        self.assertIn(f"{SECOND} invalid  # ", listed)
        self.assertEqual(self.run_preset("two-fault", "--out", "d.csv", "--expect", "c.csv.expect").returncode, 0)
        fixed = self.run_preset("two", "--out", "e.csv", "--expect", "c.csv.expect")
        self.assertEqual(fixed.returncode, 4, fixed.stderr)
        self.assertIn(f"unexpected: {SECOND}: fixed: expected invalid (c.csv.expect:3), now ok", fixed.stderr)

    def test_bad_baselines_are_usage_errors_and_unmatched_patterns_warnings(self):
        with open(self.path("bad"), "w") as f:
            f.write("occupancy/* invalid\noccupancy/* passing\n")
        r = self.run_preset("two", "--out", "a.csv", "--expect", "bad")
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertIn("bad:2: unknown status 'passing'", r.stderr)
        self.assertFalse(os.path.exists(self.path("a.csv")), "a bad baseline must stop the run before any work")
        with open(self.path("bad"), "w") as f:
            f.write("occupancy/*\n")
        r = self.run_preset("two", "--out", "a.csv", "--expect", "bad")
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertIn("bad:1: expected 'PATTERN STATUS'", r.stderr)
        with open(self.path("unused"), "w") as f:
            f.write("sort/* error\n")
        r = self.run_preset("two", "--out", "a.csv", "--expect", "unused")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("warning: --expect unused:1: 'sort/*' matches no case of this run", r.stderr)
        r = self.run_preset("two", "--out", "a.csv", "--expect", "none")
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertIn("none", r.stderr)

    def test_junit_has_the_shape_gitlab_reads(self):
        r = self.run_preset("two-fault", "--out", "a.csv", "--junit", "j.xml", "--shard", "1/1")
        self.assertEqual(r.returncode, 0, r.stderr)
        root = ET.parse(self.path("j.xml")).getroot()
        self.assertEqual(root.tag, "testsuites")
        suites = list(root)
        self.assertEqual([s.tag for s in suites], ["testsuite"])
        suite = suites[0]
        for node in (root, suite):
            self.assertEqual((node.get("tests"), node.get("failures"), node.get("errors"), node.get("skipped")),
                             ("2", "1", "0", "0"))
            float(node.get("time"))
        props = {p.get("name"): p.get("value") for p in suite.find("properties")}
        self.assertEqual(props["driver"], "llvmpipe")
        self.assertIn("llvmpipe", props["renderer"])
        self.assertTrue(props["commit"])
        self.assertEqual(props["shard"], "1/1")
        cases = suite.findall("testcase")
        self.assertEqual(len(cases), 2)
        with open(self.path("a.csv"), newline="") as f:
            rows = [r for r in csv.DictReader(f) if r["pass"] == "total"]
        for case, row in zip(cases, rows):
            self.assertEqual(case.get("classname"), "oitbench.occupancy")
            self.assertAlmostEqual(float(case.get("time")), float(row["median_ms"] or 0) / 1000, places=5)
            self.assertTrue(set(child.tag for child in case) <= {"failure", "error", "skipped"})
        self.assertEqual(cases[1].get("name"), SECOND)
        failure = cases[1].find("failure")
        self.assertEqual(failure.get("message"), rows[1]["reason"])
        self.assertIsNone(cases[0].find("failure"))

    def test_outputs_that_are_not_files_are_refused(self):
        for option in ("--junit", "--write-expect"):
            for path in (self.dir, "/dev/null"):
                r = self.run_preset("two", "--out", "a.csv", option, path)
                self.assertEqual(r.returncode, 2, r.stderr)
                self.assertIn(option, r.stderr)

    def test_shards_together_are_the_whole_grid_each_case_once(self):
        def cases(name):
            with open(self.path(name), newline="") as f:
                return [(r["variant"], r["size"], r["status"], r["shard"]) for r in csv.DictReader(f)
                        if r["pass"] == "total"]
        grid = ["occupancy", "--quick", "--reps", "1", "--set", "size=1,2,3", "--no-interleave", "--no-progress"]
        self.assertEqual(self.oitbench("run", *grid, "--out", "all.csv").returncode, 0)
        union = []
        env = dict(os.environ)
        for index in (1, 2, 3):  # GitLab's parallel: 3, CI_NODE_INDEX 1-based
            env.update(CI_NODE_INDEX=str(index), CI_NODE_TOTAL="3")
            r = self.oitbench("run", *grid, "--shard", "auto", "--out", f"s{index}.csv", env=env)
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertIn(f"--shard auto: shard {index}/3 from GitLab parallel:", r.stderr)
            part = cases(f"s{index}.csv")
            self.assertTrue(part)
            self.assertEqual({c[3] for c in part}, {f"{index}/3"})
            union += [c[:3] for c in part]
        self.assertEqual(sorted(union), sorted(c[:3] for c in cases("all.csv")))
        for bad in ("0/4", "5/4", "a/b"):
            r = self.oitbench("run", *grid, "--shard", bad, "--out", "x.csv")
            self.assertEqual(r.returncode, 2, r.stderr)
            self.assertIn(f"--shard '{bad}'", r.stderr)
        env = {k: v for k, v in os.environ.items() if not k.startswith(("SLURM_", "CI_NODE", "JOB_COMPLETION"))}
        r = self.oitbench("run", *grid, "--shard", "auto", "--out", "x.csv", env=env)
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertIn("--shard auto: no scheduler's variables", r.stderr)


if __name__ == "__main__":
    unittest.main()
