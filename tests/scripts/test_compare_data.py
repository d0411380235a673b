"""compare.py (issue 17): the header names each run's driver, threads and environment; --raw pairs summary
and raw rows on the parameters each case uses (a raw row may fill others); --repeat takes the noise band
from repeated runs of the first configuration instead of the fixed 1.5x."""
import csv
import random
import unittest

import synthetic as syn
from support import TempDirTest, run_script


def rows(slow=1.0, noise=0.0, seed=1, extra=None):
    rng = random.Random(seed)
    out = []
    for size in range(1, 21):
        r = {"experiment": "occupancy", "variant": "dynamic", "pass": "total", "size": size, "draws": 8,
             "median_ms": 10 * size * slow * (1 + rng.uniform(-noise, noise)), "noise": 0.01,
             "parameters": "size;draws;fault;seed", "driver": "llvmpipe", "lp_num_threads": "2"}
        r.update(extra or {})
        out.append(r)
    return out


class CompareDataTest(TempDirTest):
    def write(self, name, rs, raw=False, **kw):
        return syn.write_summary(self.path(name), rs, params=syn.OCCUPANCY_PARAMS,
                                 raw_path=self.path(name.replace(".csv", "_raw.csv")) if raw else None, reps=12, **kw)

    def test_header_names_driver_threads_and_environment(self):
        a = self.write("a.csv", rows())
        b = self.write("b.csv", rows(extra={"lp_num_threads": "1", "env": "LP_NUM_THREADS=1"}))
        out = run_script("compare.py", a, b).stdout
        self.assertIn("driver llvmpipe", out)
        self.assertIn("LP_NUM_THREADS 2, env -", out)
        self.assertIn("LP_NUM_THREADS 1, env LP_NUM_THREADS=1", out)
        self.assertIn("noise band: --min-effect 1.5x", out)

    def test_raw_files_pair_on_the_parameters_each_case_uses(self):
        a = self.write("a.csv", rows(), raw=True)
        b = self.write("b.csv", rows(slow=1.1), raw=True)
        # A raw row that fills a parameter its case does not use (model_gpu) still pairs with its summary row.
        for path in (self.path("a_raw.csv"), self.path("b_raw.csv")):
            with open(path, newline="") as f:
                data = list(csv.DictReader(f))
                header = list(data[0].keys())
            for r in data:
                r["model_gpu"] = "whatever"
            with open(path, "w", newline="") as f:
                w = csv.DictWriter(f, fieldnames=header, lineterminator="\n")
                w.writeheader()
                w.writerows(data)
        run_script("compare.py", a, b, "--raw", self.path("a_raw.csv"), self.path("b_raw.csv"), "-o", self.path("o"))
        with open(self.path("o/compare.csv"), newline="") as f:
            methods = {r["ci_method"] for r in csv.DictReader(f)}
        self.assertEqual(methods, {"bootstrap"})

    def test_repeat_runs_set_the_noise_band(self):
        a = self.write("a.csv", rows(noise=0.03, seed=1))
        a2 = self.write("a2.csv", rows(noise=0.03, seed=2))
        b = self.write("b.csv", rows(slow=1.2, noise=0.03, seed=3))
        fixed = run_script("compare.py", a, b, "-o", self.path("fixed")).stdout
        self.assertIn(", 0 changed", fixed)  # 1.2x is inside the fixed 1.5x band
        data = run_script("compare.py", a, b, "--repeat", a2, "-o", self.path("data")).stdout
        self.assertIn("noise band from --repeat", data)
        with open(self.path("data/compare.csv"), newline="") as f:
            got = list(csv.DictReader(f))
        self.assertTrue(all(float(r["noise_band"]) < 1.1 for r in got), data)
        self.assertGreaterEqual(sum(r["class"] == "changed" for r in got), 18, data)


if __name__ == "__main__":
    unittest.main()
