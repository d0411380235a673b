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


def container_env(job):
    """The container's env as a dict that writes through to the manifest."""
    container = job["spec"]["template"]["spec"]["containers"][0]
    env = {e["name"]: e["value"] for e in container["env"]}

    class Through(dict):
        def update(self, **kw):
            super().update(**kw)
            container["env"] = [{"name": k, "value": v} for k, v in self.items()]
    return Through(env)


def kubernetes_problems(job):
    """What is wrong with an Indexed Job manifest for oitbench (empty: nothing)."""
    problems = []
    if (job.get("apiVersion"), job.get("kind")) != ("batch/v1", "Job"):
        problems.append("not a batch/v1 Job")
    spec = job["spec"]
    if spec.get("completionMode") != "Indexed":
        problems.append("completionMode is not Indexed")
    container = spec["template"]["spec"]["containers"][0]
    env = container_env(job)
    if "graphics" not in env.get("NVIDIA_DRIVER_CAPABILITIES", "").split(","):
        problems.append("NVIDIA_DRIVER_CAPABILITIES lacks graphics")
    if int(env.get("OITBENCH_SHARD_COUNT", -1)) != spec.get("completions"):
        problems.append("OITBENCH_SHARD_COUNT is not completions")
    command = " ".join(container.get("command", []) + container.get("args", []))
    if "--shard auto" not in command or "$JOB_COMPLETION_INDEX" not in command:
        problems.append("the command does not run --shard auto into a file per index")
    if "/results" not in {m["mountPath"] for m in container.get("volumeMounts", [])}:
        problems.append("no /results volume")
    return problems


class Kubernetes(unittest.TestCase):
    def setUp(self):
        self.job = load("kubernetes", "oitbench-indexed-job.yaml")

    def test_an_indexed_job_with_graphics_and_the_shard_count(self):
        self.assertEqual(kubernetes_problems(self.job), [])

    def test_the_check_fails_on_broken_manifests(self):
        import copy
        for break_it in (lambda j: j["spec"].update(completions=5),
                         lambda j: j["spec"].update(completionMode="NonIndexed"),
                         lambda j: container_env(j).update(NVIDIA_DRIVER_CAPABILITIES="compute,utility"),
                         lambda j: j["spec"]["template"]["spec"]["containers"][0].update(args=["oitbench run"])):
            broken = copy.deepcopy(self.job)
            break_it(broken)
            self.assertNotEqual(kubernetes_problems(broken), [])

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


def gitlab_problems(job):
    """What is wrong with the GitLab job for oitbench (empty: nothing)."""
    problems = []
    if not isinstance(job.get("parallel"), int) or job["parallel"] < 2:
        problems.append("no parallel: N")
    script = " ".join(job.get("script", []))
    for needed in ("--shard auto", "--expect", "--junit results/shard-$CI_NODE_INDEX.xml", "--out"):
        if needed not in script.replace('"', ""):
            problems.append(f"the script lacks {needed}")
    artifacts = job.get("artifacts", {})
    if artifacts.get("when") != "always":
        problems.append("artifacts not kept when the gate fails (when: always)")
    if "results/" not in artifacts.get("paths", []):
        problems.append("the CSVs are not artifacts")
    if artifacts.get("reports", {}).get("junit") != "results/shard-*.xml":
        problems.append("the JUnit reports are not artifacts:reports:junit")
    if "graphics" not in job.get("variables", {}).get("NVIDIA_DRIVER_CAPABILITIES", ""):
        problems.append("NVIDIA_DRIVER_CAPABILITIES lacks graphics")
    return problems


class GitLab(unittest.TestCase):
    def setUp(self):
        self.ci = load("gitlab", "oitbench.gitlab-ci.yml")
        self.job = self.ci["oitbench"]

    def test_parallel_junit_and_csv_artifacts_gated_on_the_baseline(self):
        self.assertEqual(gitlab_problems(self.job), [])

    def test_the_check_fails_on_broken_jobs(self):
        import copy
        for break_it in (lambda j: j.pop("parallel"),
                         lambda j: j["script"].__setitem__(-1, "build/oitbench run --preset default --shard auto"),
                         lambda j: j["artifacts"].pop("when"),
                         lambda j: j["artifacts"]["reports"].update(junit="report.xml"),
                         lambda j: j["variables"].update(NVIDIA_DRIVER_CAPABILITIES="compute,utility")):
            broken = copy.deepcopy(self.job)
            break_it(broken)
            self.assertNotEqual(gitlab_problems(broken), [])

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
