"""The recipes in deploy/, validated offline (issue 26): the Kubernetes Indexed Job manifest and the GitLab CI
job are parsed and their fields checked, and their index arithmetic is run through the binary with each
worker's variables set by hand: --shard auto must give shard index+1 of completions (Kubernetes) and
CI_NODE_INDEX of CI_NODE_TOTAL (GitLab), every shard once. The Slurm job script runs for real in
fleet.SlurmArrayRunsEveryCaseOnce."""
import os
import subprocess
import unittest

import yaml

from support import oitbench_exe
from synthetic import SCRIPTS

DEPLOY = os.path.join(os.path.dirname(SCRIPTS), "deploy")
GRID = ["run", "occupancy", "--quick", "--reps", "1", "--set", "size=1,2,3,4,5", "--set", "variant=dynamic", "--no-interleave", "--no-progress",
        "--out", "-"]


def load(*path):
    with open(os.path.join(DEPLOY, *path)) as f:
        return yaml.safe_load(f)


def shard_of(env):
    """The shard --shard auto takes from these variables (and none of the machine's)."""
    clean = {k: v for k, v in os.environ.items() if not k.startswith(("SLURM_", "CI_NODE", "JOB_COMPLETION"))}
    proc = subprocess.run([oitbench_exe(), *GRID, "--shard", "auto"], env={**clean, **env}, capture_output=True,
                          text=True, timeout=300)
    if proc.returncode != 0:
        raise AssertionError(proc.stderr)
    line = next(l for l in proc.stderr.splitlines() if "--shard auto: shard" in l)
    return line.split("shard ")[2].split(" ")[0], line, proc.stdout


class Kubernetes(unittest.TestCase):
    def setUp(self):
        self.job = load("kubernetes", "oitbench-indexed-job.yaml")

    def test_an_indexed_job_with_graphics_and_the_shard_count(self):
        self.assertEqual((self.job["apiVersion"], self.job["kind"]), ("batch/v1", "Job"))
        spec = self.job["spec"]
        self.assertEqual(spec["completionMode"], "Indexed")
        container = spec["template"]["spec"]["containers"][0]
        env = {e["name"]: e["value"] for e in container["env"]}
        self.assertIn("graphics", env["NVIDIA_DRIVER_CAPABILITIES"].split(","))
        self.assertEqual(int(env["OITBENCH_SHARD_COUNT"]), spec["completions"])
        command = " ".join(container["command"] + container["args"])
        self.assertIn("--shard auto", command)
        self.assertIn("$JOB_COMPLETION_INDEX", command)
        mounts = {m["mountPath"] for m in container["volumeMounts"]}
        self.assertIn("/results", mounts)

    @unittest.skipUnless(oitbench_exe(), "needs the binary (OITBENCH_EXE)")
    def test_every_pod_runs_its_own_shard(self):
        n = self.job["spec"]["completions"]
        env = {e["name"]: e["value"] for e in self.job["spec"]["template"]["spec"]["containers"][0]["env"]}
        seen = []
        for index in range(n):
            shard, line, _ = shard_of({"JOB_COMPLETION_INDEX": str(index),
                                       "OITBENCH_SHARD_COUNT": env["OITBENCH_SHARD_COUNT"]})
            self.assertIn("Kubernetes Indexed Job", line)
            seen.append(shard)
        self.assertEqual(seen, [f"{i}/{n}" for i in range(1, n + 1)])


class GitLab(unittest.TestCase):
    def setUp(self):
        self.ci = load("gitlab", "oitbench.gitlab-ci.yml")
        self.job = self.ci["oitbench"]

    def test_parallel_junit_and_csv_artifacts_gated_on_the_baseline(self):
        self.assertIsInstance(self.job["parallel"], int)
        self.assertGreaterEqual(self.job["parallel"], 2)
        script = " ".join(self.job["script"])
        for needed in ("--shard auto", "--expect", "--junit", "--out"):
            self.assertIn(needed, script)
        artifacts = self.job["artifacts"]
        self.assertEqual(artifacts["when"], "always")  # the reports of a failing (gated) job too
        self.assertIn("results/", artifacts["paths"])
        self.assertEqual(artifacts["reports"]["junit"], "results/shard-*.xml")
        self.assertIn("results/shard-$CI_NODE_INDEX.xml", script)
        self.assertIn("graphics", self.job["variables"]["NVIDIA_DRIVER_CAPABILITIES"])

    @unittest.skipUnless(oitbench_exe(), "needs the binary (OITBENCH_EXE)")
    def test_every_node_runs_its_own_shard_and_together_the_grid(self):
        n = self.job["parallel"]
        seen, rows = [], []
        for index in range(1, n + 1):  # CI_NODE_INDEX is 1-based
            shard, line, out = shard_of({"CI_NODE_INDEX": str(index), "CI_NODE_TOTAL": str(n)})
            self.assertIn("GitLab parallel:", line)
            seen.append(shard)
            rows += [l for l in out.splitlines()[1:] if ",total," in l]
        self.assertEqual(seen, [f"{i}/{n}" for i in range(1, n + 1)])
        self.assertEqual(len(rows), 5)  # size=1..5, each once


if __name__ == "__main__":
    unittest.main()
