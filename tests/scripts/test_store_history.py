"""The store's questions on both backends (SQLite and a real PostgreSQL 15, pgserver.py): history finds a
+9.4% step (runs 11-20 doing 70 draws instead of 64) at run 11 in at least 9 of 10 synthetic trials with
realistic noise and no step in 10 of 10 trials of identical runs; compare, history and the Bencher export
answer the same on both backends; every Grafana panel's SQL runs against the test server and returns the
expected series; the fleet page; a filter that matches nothing exits 1."""
import csv
import json
import math
import os
import random
import shutil
import subprocess
import tempfile
import time
import unittest

from synthetic import SCRIPTS  # noqa: F401  (puts scripts/ on sys.path)
import pgserver
from oitbench.store import open_store, queries
from oitbench.store import compare as store_compare
from oitbench.store import history as store_history
from oitbench.store.sqlschema import CSV_SCHEMA, SCHEMA

REPO = os.path.dirname(SCRIPTS)
PYTHON = "/usr/bin/python3"
SERVER = None
SUMMARY = [c["name"] for c in SCHEMA["summary_columns"]]
RAW = [c["name"] for c in SCHEMA["raw_columns"]]
STEP = 70 / 64  # +9.4% work


def setUpModule():
    global SERVER
    SERVER = pgserver.PgServer.start()


def tearDownModule():
    if SERVER:
        SERVER.stop()


def order_ci(samples):
    s = sorted(samples)
    n = len(s)
    half = 1.959964 * math.sqrt(n) / 2
    return s[max(0, int(math.floor(n / 2 - half)))], s[min(n - 1, int(math.ceil(n / 2 + half)) - 1)]


def write_trial(folder, name, trial, step, runs=20, samples=15, rng=None, extra_cases=(), driver="llvmpipe",
                machine="00000000000000aa", shas=None):
    """One CSV (and its raw file) holding `runs` runs of occupancy's unrolled size=32 case (draws 64, or 70
    from run 11 on with `step`): a between-run factor (lognormal, 1.5%) and per-sample noise (lognormal, 6%,
    15 samples): ~2.4% per run's median, as the A/B pairs of identical code in results/ab-llvmpipe/identical
    (3.3-3.8% per pair ratio)."""
    rng = rng or random.Random(trial)
    summary, raw = [], []
    for i in range(runs):
        run_id = f"{trial:08x}-{i:04x}-4000-8000-{abs(hash(name)) % 10**12:012d}"
        work = STEP if step and i >= runs // 2 else 1.0
        run_factor = math.exp(rng.gauss(0, 0.015))
        stamp = f"2026-11-{1 + i:02d}T00:00:00Z"
        for case, base in [("32", 3.0)] + list(extra_cases):
            values = [base * work * run_factor * math.exp(rng.gauss(0, 0.06)) for _ in range(samples)]
            med = sorted(values)[samples // 2]
            lo, hi = order_ci(values)
            row = {c: "" for c in SUMMARY}
            row.update(schema=str(CSV_SCHEMA), experiment="occupancy", variant="unrolled", status="ok", valid="1",
                       backend="egl", driver=driver, gl_renderer="llvmpipe (LLVM 15.0.6, 256 bits)",
                       width="800", height="600", reps=str(samples), median_ms=f"{med:.6g}",
                       mean_ms=f"{sum(values) / samples:.6g}", mad_ms=f"{sorted(abs(v - med) for v in values)[samples // 2]:.6g}",
                       ci_lo_ms=f"{lo:.6g}", ci_hi_ms=f"{hi:.6g}", samples=str(samples), timestamp_utc=stamp,
                       git_sha=shas[i] if shas else f"c{i:03d}", hostname="vm", machine_id=machine, run_id=run_id,
                       tags=f"trial={name}", size=case, draws="64", parameters="size;draws")
            row["pass"] = "total"
            summary.append(row)
            for rep, v in enumerate(values):
                r = {c: "" for c in RAW}
                r.update(schema=str(CSV_SCHEMA), experiment="occupancy", variant="unrolled", rep=str(rep),
                         width="800", height="600", cpu_ms=f"{v:.6g}", backend="egl", driver=driver,
                         timestamp_utc=stamp, run_id=run_id, size=case, draws="64")
                r["pass"] = "total"
                raw.append(r)
    paths = []
    for rows, cols, suffix in ((summary, SUMMARY, ""), (raw, RAW, "_raw")):
        path = os.path.join(folder, f"{name}{suffix}.csv")
        with open(path, "w", newline="", encoding="utf-8") as f:
            w = csv.DictWriter(f, cols, lineterminator="\n")
            w.writeheader()
            w.writerows(rows)
        paths.append(path)
    return paths


def answers(url):
    """history of one trial and compare of two, as plain values."""
    with open_store(url) as s:
        hist = [(x.case_key, [r["run_id"] for r in x.rows], x.steps)
                for x in store_history.history(s, queries.RunFilter(["trial=step3"]))]
        comps, _ = store_compare.compare(s, queries.RunFilter(["trial=flat1"]), queries.RunFilter(["trial=step1"]))
    return hist, [(c.key, round(c.ratio, 12), c.kind, [round(x, 12) for x in c.ci]) for c in comps]


class Backend:
    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.mkdtemp(prefix="oitbench-history-")
        cls.url = cls.new_store()
        with open_store(cls.url) as s:
            for trial in range(10):
                for step in (True, False):
                    for p in write_trial(cls.dir, f"{'step' if step else 'flat'}{trial}", trial + 100 * step, step,
                                         extra_cases=[("8", 2.0)] if trial == 0 else ()):
                        s.ingest(p)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.dir, ignore_errors=True)

    def history(self, name):
        with open_store(self.url) as s:
            return store_history.history(s, queries.RunFilter([f"trial={name}"]), "occupancy",
                                         "occupancy/unrolled/total/800x600/draws=64;size=32")

    def test_a_step_of_9_4_percent_is_found_at_run_11(self):
        found = 0
        for trial in range(10):
            (series,) = self.history(f"step{trial}")
            self.assertEqual(len(series.rows), 20)
            starts = [i for i, _, _ in series.steps]
            found += starts == [10]
            for i, ratio, p in series.steps:
                self.assertLess(p, 0.01)
        print(f"{type(self).__name__}: step found at run 11 in {found} of 10 trials")
        self.assertGreaterEqual(found, 9)

    def test_identical_runs_have_no_step(self):
        false = sum(bool(self.history(f"flat{trial}")[0].steps) for trial in range(10))
        print(f"{type(self).__name__}: a step in {false} of 10 trials of identical runs")
        self.assertEqual(false, 0)

    def test_the_command_prints_the_step_and_draws_the_figure(self):
        png = os.path.join(self.dir, "h.png")
        proc = subprocess.run([PYTHON, os.path.join(SCRIPTS, "store.py"), "--store", self.url, "history",
                               "--tag", "trial=step0", "--case", "%size=32", "-v", "-o", png],
                              capture_output=True, text=True, timeout=300, env=dict(os.environ, MPLBACKEND="Agg"))
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertIn("1 change point(s); at run 11: x1.", proc.stdout)
        mean = subprocess.run([PYTHON, os.path.join(SCRIPTS, "store.py"), "--store", self.url, "history",
                               "--tag", "trial=step0", "--case", "%size=32", "--statistic", "mean"],
                              capture_output=True, text=True, timeout=300)
        self.assertEqual(mean.returncode, 0, mean.stderr)
        self.assertIn("1 change point(s); at run 11: x1.", mean.stdout)
        with open(png, "rb") as f:
            self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
        proc = subprocess.run([PYTHON, os.path.join(SCRIPTS, "store.py"), "--store", self.url, "history",
                               "--tag", "trial=nosuch"], capture_output=True, text=True, timeout=300)
        self.assertEqual(proc.returncode, 1)
        self.assertIn("no ok row of any run matches", proc.stderr)

    def test_order_commit_follows_the_commit_graph(self):
        """--order commit: by git ancestry (a -dirty build at its commit's place), not by the date each
        commit was first run; a commit the repository does not know orders everything by date, with a note."""
        repo = os.path.join(self.dir, "repo")
        os.makedirs(repo)

        def git(*args):
            return subprocess.run(["git", "-C", repo, "-c", "user.name=t", "-c", "user.email=t@example.org"] +
                                  list(args), check=True, capture_output=True, text=True).stdout.strip()
        git("init", "-q")
        shas = []
        for i in range(3):
            git("commit", "-q", "--allow-empty", "-m", f"commit {i}")
            shas.append(git("rev-parse", "--short=12", "HEAD"))
        run_order = [shas[2], shas[0] + "-dirty", shas[1]]  # a bisection's order: newest first
        case = "occupancy/unrolled/total/800x600/draws=64;size=32"
        with open_store(self.url) as s:
            for p in write_trial(self.dir, "graph", 7, False, runs=3, shas=run_order):
                s.ingest(p)
            for p in write_trial(self.dir, "stranger", 8, False, runs=3, shas=[shas[1], "0123456789ab", shas[0]]):
                s.ingest(p)

            def shas_of(trial, order, repo_dir, notes=None):
                (series,) = store_history.history(s, queries.RunFilter([f"trial={trial}"]), "occupancy", case,
                                                  order=order, repo=repo_dir, notes=notes)
                return [r["git_sha"] for r in series.rows]
            notes = []
            self.assertEqual(shas_of("graph", "commit", repo, notes), [shas[0] + "-dirty", shas[1], shas[2]])
            self.assertEqual(notes, [])
            self.assertEqual(shas_of("graph", "date", repo), run_order)
            for trial, repo_dir, unknown in (("stranger", repo, "0123456789ab"), ("graph", self.dir, shas[0]),
                                             ("graph", None, shas[0])):
                notes = []
                self.assertEqual(shas_of(trial, "commit", repo_dir, notes),
                                 run_order if trial == "graph" else [shas[1], "0123456789ab", shas[0]])
                self.assertEqual(len(notes), 1)
                self.assertIn("ordered by the date", notes[0])
                self.assertIn(unknown, notes[0])
        proc = subprocess.run([PYTHON, os.path.join(SCRIPTS, "store.py"), "--store", self.url, "history",
                               "--tag", "trial=graph", "--order", "commit", "--repo", repo, "-v"],
                              capture_output=True, text=True, timeout=300)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertNotIn("note:", proc.stderr)
        self.assertLess(proc.stdout.index(shas[0]), proc.stdout.index(shas[1]))
        self.assertLess(proc.stdout.index(shas[1]), proc.stdout.index(shas[2]))
        proc = subprocess.run([PYTHON, os.path.join(SCRIPTS, "store.py"), "--store", self.url, "history",
                               "--tag", "trial=stranger", "--order", "commit", "--repo", repo],
                              capture_output=True, text=True, timeout=300)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertIn("note: ordered by the date each commit was first run", proc.stderr)

    def test_compare_two_halves(self):
        with open_store(self.url) as s:
            before = queries.RunFilter(["trial=step0"], until="2026-11-11")
            after = queries.RunFilter(["trial=step0"], since="2026-11-11")
            comps, warnings = store_compare.compare(s, before, after, min_effect=1.02)
        (c,) = [c for c in comps if c.key.endswith("size=32")]
        self.assertAlmostEqual(c.ratio, STEP, delta=0.04)
        self.assertEqual(c.kind, store_compare.CHANGED)
        self.assertEqual(warnings, [])

    def test_bencher_export(self):
        proc = subprocess.run([PYTHON, os.path.join(SCRIPTS, "store.py"), "--store", self.url, "bencher",
                               "--tag", "trial=step0"], capture_output=True, text=True, timeout=300)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        bmf = json.loads(proc.stdout)
        self.assertEqual(len(bmf), 2)
        m = bmf["occupancy/unrolled/total/800x600/draws=64;size=32"]["latency"]
        self.assertLessEqual(m["lower_value"], m["value"])
        self.assertLessEqual(m["value"], m["upper_value"])

    def test_fleet_page(self):
        out = os.path.join(self.dir, "fleet.html")
        proc = subprocess.run([PYTHON, os.path.join(SCRIPTS, "store.py"), "--store", self.url, "fleet", "-o", out],
                              capture_output=True, text=True, timeout=300)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        with open(out, encoding="utf-8") as f:
            text = f.read()
        self.assertIn("llvmpipe | llvmpipe (LLVM 15.0.6, 256 bits)", text)
        self.assertIn("ok 440", text)  # 20 trials x 20 runs, + 2 x 20 rows of a second case


class SqliteTest(Backend, unittest.TestCase):
    @classmethod
    def new_store(cls):
        return os.path.join(cls.dir, "store.sqlite")


@unittest.skipIf(pgserver.available(), pgserver.available())
class PostgresTest(Backend, unittest.TestCase):
    @classmethod
    def new_store(cls):
        return SERVER.url(f"h{os.getpid()}")

    def test_same_answers_as_sqlite(self):
        sqlite = os.path.join(self.dir, "same.sqlite")
        with open_store(sqlite) as s:
            for name in ("step3", "flat1", "step1"):
                for suffix in ("", "_raw"):
                    s.ingest(os.path.join(self.dir, f"{name}{suffix}.csv"))
        self.assertEqual(answers(self.url), answers(sqlite))

    def test_every_grafana_panel_runs_and_returns_its_series(self):
        with open(os.path.join(REPO, "deploy", "grafana", "oitbench.json"), encoding="utf-8") as f:
            dash = json.load(f)
        values = {"case": "occupancy/unrolled/total/800x600/draws=64;size=32", "driver": "llvmpipe"}
        oit_csv = os.path.join(REPO, "results", "llvmpipe", "presets", "knowles2014-quick.csv")
        url = SERVER.url(f"g{os.getpid()}")
        with open_store(url) as s:
            for suffix in ("", "_raw"):
                s.ingest(os.path.join(self.dir, f"step0{suffix}.csv"))
            s.ingest(oit_csv)
            for var in dash["templating"]["list"]:
                options = [list(r.values())[0] for r in s.query(var["query"])]
                self.assertIn(values[var["name"]], options)
            results = {}
            for panel in dash["panels"]:
                sql = panel["targets"][0]["rawSql"]
                for k, v in values.items():
                    sql = sql.replace(f"${k}", v)
                cur = s.conn.cursor()
                cur.execute(sql)
                results[panel["id"]] = ([d[0] for d in cur.description], cur.fetchall())
                s.conn.rollback()
        cols, rows = results[1]
        self.assertEqual(cols, ["time", "median", "ci_lo", "ci_hi"])
        self.assertEqual(len(rows), 20)  # the trial's runs of that case, in time order
        self.assertTrue(all(lo <= m <= hi for _, m, lo, hi in rows))
        self.assertEqual([r[0] for r in rows], sorted(r[0] for r in rows))
        with open(oit_csv, newline="", encoding="utf-8") as f:
            oit = [r for r in csv.DictReader(f) if r["pass"] == "total"]
        gpu = f"{oit[0]['driver']} | {oit[0]['gl_renderer']}"
        cols, rows = results[2]
        self.assertEqual(cols, ["gpu", "preset", "ok", "invalid", "unsupported", "error", "timeout"])
        counts = {s: sum(r["status"] == s for r in oit) for s in ("ok", "invalid", "unsupported", "error", "timeout")}
        self.assertEqual(rows, sorted([("llvmpipe | llvmpipe (LLVM 15.0.6, 256 bits)", "", 40, 0, 0, 0, 0),
                                       (gpu, oit[0]["preset"]) + tuple(counts.values())]))
        cols, rows = results[3]
        self.assertEqual(cols, ["gpu", "scene", "view", "technique", "median_ms"])
        best = {}
        for r in oit:
            if r["experiment"] == "oit" and r["status"] == "ok" and r["median_ms"]:
                k = (r["scene"], r["view"])
                if k not in best or float(r["median_ms"]) < best[k][1]:
                    best[k] = (r["technique"], float(r["median_ms"]))
        self.assertGreater(len(best), 1)
        self.assertEqual({(sc, v): (t, m) for _, sc, v, t, m in rows}, best)
        SERVER.drop(f"g{os.getpid()}")


if __name__ == "__main__":
    unittest.main()
