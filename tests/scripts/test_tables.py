"""tables.py: the papers' numbers with ours beside them (or "—"), speedups computed alike for both, the
technique mapping, the csv format, and errors that name what is wrong."""
import csv
import io
import os
import subprocess
import unittest

import synthetic as syn
from support import PYTHON, TempDirTest, oitbench_exe, run_oitbench, run_script

PAPER_HEADER = "source,table,gpu,resolution,scene,view,technique,size,metric,unit,value\n"
MINI_PAPER = PAPER_HEADER + "".join(
    f'bruell2018-thesis,A.1,NVIDIA GTX 1080,800x800,sort-bench,,"naive insertion, dynamic index assignment: {t}",'
    f"{n},total_time,ms,{v}\n"
    for n, vals in ((4, (0.0584, 0.0573, 0.0573, 0.0573)), (16, (2.5999, 0.2068, 0.241, 0.213)))
    for t, v in zip(("direct", "loop", "switch", "if-else"), vals)) + "".join(
    f"knowles2014-rbs,2,NVIDIA GTX Titan,,planes,Fwd,{t},128,{m},ms,{v}\n"
    for t, m, v in (("BASE-IS", "total_time", 77), ("BASE-IS", "resolve_time", 67), ("BMA-RBS-L", "total_time", 62),
                    ("BMA-RBS-L", "resolve_time", 49), ("CUDA-IS", "total_time", 50)))


REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PUBLISHED = os.path.join(REPO, "results", "published")


class TablesMini(TempDirTest):
    def setUp(self):
        super().setUp()
        os.makedirs(self.path("paper"))
        with open(self.path("paper/mini.csv"), "w", encoding="utf-8") as f:
            f.write(MINI_PAPER)

    def sort_run(self):
        return syn.write_summary(self.path("sort.csv"), syn.sort_rows(), params=["n", "keys"])

    def oit_run(self):
        return syn.write_summary(self.path("oit.csv"), syn.oit_rows(), metrics=["rmse", "max_abs_error"],
                                 params=["scene", "max_frags"])

    def test_paper_numbers_with_dashes_when_we_have_no_rows(self):
        proc = run_script("tables.py", "--paper", self.path("paper"), "--table", "bruell-A.1")
        self.assertIn("| 4 | naive insertion, dynamic index assignment: direct | 0.0584 ms | 1x | \u2014 | \u2014 |",
                      proc.stdout)
        self.assertIn("2.6 ms", proc.stdout)
        self.assertIn("12.6x", proc.stdout)  # paper speedup of loop over direct at 16: 2.5999 / 0.2068

    def test_ours_beside_the_paper_with_speedups_over_the_baseline(self):
        proc = run_script("tables.py", self.sort_run(), "--paper", self.path("paper"), "--table", "A.1",
                          "--format", "csv")
        rows = {(r["size"], r["technique"].split(": ")[1]): r for r in csv.DictReader(io.StringIO(proc.stdout))}
        direct, loop = rows[("16", "direct")], rows[("16", "loop")]
        # synthetic: direct costs 1.0 * n^2/16, loop 0.3 * n^2/16, averaged over the random and reverse keys
        self.assertAlmostEqual(float(direct["ours_ms"]), 20.0, places=3)
        self.assertAlmostEqual(float(loop["ours_speedup"]), 1 / 0.3, places=3)
        self.assertAlmostEqual(float(loop["paper_speedup"]), 2.5999 / 0.2068, places=3)
        self.assertEqual(loop["ours_cases"], "2")

    def test_knowles_techniques_map_onto_oit_variants(self):
        proc = run_script("tables.py", self.oit_run(), "--paper", self.path("paper"), "--table", "knowles2014-2",
                          "--format", "csv")
        rows = {(r["technique"], r["metric"]): r for r in csv.DictReader(io.StringIO(proc.stdout))}
        base, bma = rows[("BASE-IS", "total_time")], rows[("BMA-RBS-L", "total_time")]
        self.assertAlmostEqual(float(bma["paper_speedup"]), 77 / 62, places=3)
        # synthetic planes, 128: capture 4 + resolve 10*cost*2 + 0.1; base-is cost 1.0, bma-rbs 0.25
        self.assertAlmostEqual(float(base["ours_ms"]), 24.1, places=3)
        self.assertAlmostEqual(float(bma["ours_speedup"]), 24.1 / 9.1, places=3)
        self.assertAlmostEqual(float(rows[("BMA-RBS-L", "resolve_time")]["ours_ms"]), 5.0, places=3)
        self.assertEqual(rows[("CUDA-IS", "total_time")]["ours_ms"], "")  # CUDA: never ours

    def test_a_tables_own_preset_wins_and_packed_arrays_stay_out(self):
        # Two runs of BASE-IS on planes fwd at MAX_FRAGS 128: the knowles2014 preset's and another grid's
        # (other resolution); plus a PPPA row. The table must take the preset's row only.
        rows = [{"experiment": "oit", "variant": "base-is", "scene": "planes", "view": "Fwd", "max_frags": 128,
                 "pass": "total", "median_ms": ms, "preset": preset, "capture": capture}
                for ms, preset, capture in ((10.0, "knowles2014", "PPLL"), (500.0, "oit-scale", "PPLL"),
                                            (1.0, "knowles2014", "PPPA"))]
        run = syn.write_summary(self.path("mixed.csv"), rows, params=["scene", "view", "max_frags", "capture"])
        proc = run_script("tables.py", run, "--paper", self.path("paper"), "--table", "knowles2014-2",
                          "--format", "csv")
        got = {(r["technique"], r["metric"]): r for r in csv.DictReader(io.StringIO(proc.stdout))}
        self.assertAlmostEqual(float(got[("BASE-IS", "total_time")]["ours_ms"]), 10.0)
        self.assertEqual(got[("BASE-IS", "total_time")]["ours_cases"], "1")
        # Without any row of the table's preset, every PPLL row counts (the median of 10 and 500).
        for r in rows:
            r["preset"] = ""
        run = syn.write_summary(self.path("unscoped.csv"), rows, params=["scene", "view", "max_frags", "capture"])
        proc = run_script("tables.py", run, "--paper", self.path("paper"), "--table", "knowles2014-2",
                          "--format", "csv")
        got = {(r["technique"], r["metric"]): r for r in csv.DictReader(io.StringIO(proc.stdout))}
        self.assertAlmostEqual(float(got[("BASE-IS", "total_time")]["ours_ms"]), 255.0)

    def test_the_size_is_max_frags_for_exact_resolves_even_beside_a_nodes_column(self):
        # oit rows carry nodes (the approximate techniques' parameter, 8 by default) and max_frags: the
        # Knowles tables' size is MAX_FRAGS, so neither a nodes=8 row nor the other MAX_FRAGS may count.
        with open(self.path("paper/mini.csv"), "a", encoding="utf-8") as f:
            f.write("knowles2013-bma,2,NVIDIA GTX 670,1680x1050,smoke,,OIT,256,total_time,ms,167.7\n"
                    "knowles2013-bma,2,NVIDIA GTX 670,1680x1050,smoke,,BMA-OIT,256,total_time,ms,80.7\n")
        rows = [{"experiment": "oit", "variant": v, "scene": "smoke", "view": "fwd", "max_frags": mf, "nodes": 8,
                 "pass": "total", "median_ms": ms}
                for v, mf, ms in (("base-is", 256, 80.0), ("base-is", 512, 90.0), ("bma-is", 256, 100.0),
                                  ("bma-is", 512, 50.0))]
        run = syn.write_summary(self.path("k13.csv"), rows, params=["scene", "view", "max_frags", "nodes"])
        proc = run_script("tables.py", run, "--paper", self.path("paper"), "--table", "knowles2013-2",
                          "--format", "csv")
        got = {r["technique"]: r for r in csv.DictReader(io.StringIO(proc.stdout)) if r["scene"] == "smoke"}
        self.assertAlmostEqual(float(got["OIT"]["ours_ms"]), 80.0)
        self.assertAlmostEqual(float(got["BMA-OIT"]["ours_speedup"]), 0.8)

    def test_bubble_variants_fill_table_a3(self):
        with open(self.path("paper/mini.csv"), "a", encoding="utf-8") as f:
            f.write('bruell2018-thesis,A.3,NVIDIA GTX 1080,800x800,sort-bench,,"bubble sort, no early out",'
                    "32,total_time,ms,1.109\n"
                    'bruell2018-thesis,A.3,NVIDIA GTX 1080,800x800,sort-bench,,"bubble sort, early out",'
                    "32,total_time,ms,0.5507\n")
        rows = [{"experiment": "sort", "variant": v, "n": 32, "keys": "random", "pass": "total", "median_ms": ms}
                for v, ms in (("bubble", 200.0), ("bubble-early", 400.0))]
        run = syn.write_summary(self.path("bubble.csv"), rows, params=["n", "keys"])
        proc = run_script("tables.py", run, "--paper", self.path("paper"), "--table", "A.3", "--format", "csv")
        got = {r["technique"]: r for r in csv.DictReader(io.StringIO(proc.stdout))}
        self.assertAlmostEqual(float(got["bubble sort, no early out"]["ours_ms"]), 200.0)
        self.assertAlmostEqual(float(got["bubble sort, early out"]["ours_speedup"]), 0.5)

    def test_stand_in_scenes_sit_beside_the_papers_models(self):
        # The power plant's V1 has MAX_FRAGS 512 in the paper; our engine grid's V1 has its own 256.
        with open(self.path("paper/mini.csv"), "a", encoding="utf-8") as f:
            f.write("knowles2014-rbs,2,NVIDIA GTX Titan,,powerplant,V1,BASE-IS,512,total_time,ms,530\n"
                    "knowles2014-rbs,2,NVIDIA GTX Titan,,powerplant,V2,BASE-IS,256,total_time,ms,490\n")
        rows = [{"experiment": "oit", "variant": "base-is", "scene": "engine-grid", "view": "V1", "max_frags": 256,
                 "pass": "total", "median_ms": 42.0},
                {"experiment": "oit", "variant": "base-is", "scene": "planes", "view": "V2", "max_frags": 256,
                 "pass": "total", "median_ms": 7.0}]
        run = syn.write_summary(self.path("stand.csv"), rows, params=["scene", "view", "max_frags"])
        proc = run_script("tables.py", run, "--paper", self.path("paper"), "--table", "knowles2014-2",
                          "--format", "csv")
        got = {(r["scene"], r["view"]): r["ours_ms"] for r in csv.DictReader(io.StringIO(proc.stdout))
               if r["technique"] == "BASE-IS" and r["metric"] == "total_time"}
        self.assertAlmostEqual(float(got[("powerplant", "V1")]), 42.0)
        self.assertEqual(got[("powerplant", "V2")], "")  # planes never stands in for the power plant

    def test_unknown_table_and_missing_paper_dir_are_clear_errors(self):
        proc = run_script("tables.py", "--paper", self.path("paper"), "--table", "nope", check=False)
        self.assertEqual(proc.returncode, 2)
        self.assertIn("no table 'nope'", proc.stderr)
        proc = run_script("tables.py", "--paper", self.path("nowhere"), check=False)
        self.assertEqual(proc.returncode, 2)
        self.assertIn("no paper tables", proc.stderr)

    def test_list_shows_the_mapping(self):
        proc = run_script("tables.py", "--list")
        self.assertIn("BMA-RBS-L", proc.stdout)
        self.assertIn("-> oit:", proc.stdout)


class TablesPublished(TempDirTest):
    def test_every_table_prints_the_published_numbers(self):
        # The default --paper is the repository's results/published, from any working directory.
        proc = subprocess.run([PYTHON, os.path.join(REPO, "scripts", "tables.py")], cwd=self.dir,
                              capture_output=True, text=True, timeout=300)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        for needle in ("0.0584 ms",  # Brüll A.1, direct, 4
                       "145.4 ms",  # A.2 powerplant x16 no early out, 32
                       "1.109 ms",  # A.3 bubble no early out, 32
                       "0.3901 ms",  # A.4 fullscreen pass, no stencil, 32
                       "2.843 ms",  # A.5 UMLAB no stencil, 32
                       "15.22 ms",  # 4.1 powerplant interleaved, 4
                       "| BMA-RBS-L | average_total_speedup_vs_BASE-IS | 3x |",  # Knowles 2014 table 1
                       "530 ms",  # Knowles 2014 table 2, powerplant V1 BASE-IS total
                       "604 ms",  # Knowles 2013 table 2, powerplant OIT 512
                       "3.78x"):  # Knowles 2013 table 1, powerplant 32
            self.assertIn(needle, proc.stdout)
        for name in ("A.1", "A.2", "A.3", "A.4", "A.5", "4.1", "Knowles 2014 table 1", "Knowles 2014 table 3",
                     "Knowles 2013 table 1", "Knowles 2013 table 2"):
            self.assertIn(name, proc.stdout)

    def test_every_published_file_is_described(self):
        with open(os.path.join(PUBLISHED, "README.md"), encoding="utf-8") as f:
            readme = f.read()
        for name in sorted(os.listdir(PUBLISHED)):
            if name.endswith(".csv"):
                self.assertIn(f"`{name}`", readme, f"results/published/README.md does not describe {name}")


class TablesMboit(TempDirTest):
    """Münstermann 2018 figure 1 beside our MBOIT, MLAB and (where the build has it) DP rows."""

    def run_csv(self, with_dp):
        rows = []
        for scene in ("planes", "hairball"):
            for technique, extra, ms in (("MBOIT", {"moments": 6, "moment_kind": "power", "moment_bits": 16}, 30.0),
                                         ("MBOIT", {"moments": 6, "moment_kind": "trigonometric",
                                                    "moment_bits": 32}, 40.0),
                                         ("MBOIT", {"moments": 4, "moment_kind": "power", "moment_bits": 16}, 5.0),
                                         ("MLAB", {"nodes": 4}, 60.0), ("MLAB", {"nodes": 8}, 1.0),
                                         ("DP", {}, 240.0)):
                if technique == "DP" and not with_dp:
                    continue
                rows.append(dict({"experiment": "oit", "variant": "", "technique": technique, "scene": scene,
                                  "pass": "total", "median_ms": ms}, **extra))
        return syn.write_summary(self.path("mboit.csv"), rows,
                                 params=["scene", "technique", "nodes", "moments", "moment_kind", "moment_bits"])

    def table(self, with_dp):
        out = run_script("tables.py", self.run_csv(with_dp), "--table", "mboit", "--format", "csv").stdout
        return {r["technique"]: r for r in csv.DictReader(io.StringIO(out))}

    def test_paper_rows_with_our_ratios_over_mlab(self):
        t = self.table(with_dp=True)
        self.assertEqual(float(t["MBOIT power 16-bit"]["paper"]), 12)
        self.assertAlmostEqual(float(t["MBOIT power 16-bit"]["paper_speedup"]), 16 / 12, places=4)
        self.assertAlmostEqual(float(t["MBOIT power 16-bit"]["ours_ms"]), 30.0)  # 6 moments, not the 4
        self.assertAlmostEqual(float(t["MBOIT power 16-bit"]["ours_speedup"]), 2.0)  # MLAB with 4 nodes
        self.assertAlmostEqual(float(t["MBOIT trigonometric 32-bit"]["ours_speedup"]), 1.5)
        self.assertAlmostEqual(float(t["DP"]["paper_speedup"]), 16 / 123, places=4)
        self.assertAlmostEqual(float(t["DP"]["ours_speedup"]), 0.25)

    def test_without_depth_peeling_its_row_is_empty(self):
        t = self.table(with_dp=False)
        self.assertEqual(t["DP"]["ours_ms"], "")
        self.assertAlmostEqual(float(t["MBOIT power 16-bit"]["ours_speedup"]), 2.0)
        out = run_script("tables.py", self.run_csv(False), "--table", "mboit").stdout
        self.assertIn("| DP | 123 ms | 0.13x | \u2014 | \u2014 |", out)


class TablesErrorMemory(TempDirTest):
    """--error-memory: each oit case's rmse beside its bytes per pixel, sized by the parameters its technique
    reads, sorted by memory within a scene; a missing file is exit 2 naming it."""

    def run_csv(self):
        rows = []
        for technique, extra, nbytes, rmse in (("MBOIT", {"moments": 8, "moment_kind": "power", "moment_bits": 32},
                                                52, 0.02),
                                               ("WOIT", {"wavelet_coeffs": 8, "wavelet_bits": 32}, 48, 0.007),
                                               ("MBOIT", {"moments": 4, "moment_kind": "power", "moment_bits": 32},
                                                36, 0.04)):
            for p, ms in (("blend", 1.0), ("total", 3.0)):
                rows.append(dict({"experiment": "oit", "variant": "", "technique": technique, "scene": "planes",
                                  "view": "fwd", "pass": p, "median_ms": ms, "rmse": rmse,
                                  "bytes_per_pixel": nbytes}, **extra))
        return syn.write_summary(self.path("em.csv"), rows, metrics=["rmse", "bytes_per_pixel"],
                                 params=["scene", "view", "technique", "moments", "moment_kind", "moment_bits",
                                         "wavelet_coeffs", "wavelet_bits"])

    def test_rows_sorted_by_memory_with_their_sizes(self):
        out = run_script("tables.py", "--error-memory", self.run_csv(), "--format", "csv").stdout
        rows = list(csv.DictReader(io.StringIO(out)))
        self.assertEqual([r["bytes_per_pixel"] for r in rows], ["36", "48", "52"])  # one row per case
        self.assertEqual(rows[1]["technique"], "WOIT")
        self.assertEqual(rows[1]["size"], "wavelet_bits=32 wavelet_coeffs=8")
        self.assertEqual(rows[0]["size"], "moment_bits=32 moment_kind=power moments=4")
        md = run_script("tables.py", "--error-memory", self.run_csv()).stdout
        self.assertIn("| planes | fwd | 64x64 | WOIT | wavelet_bits=32 wavelet_coeffs=8 | 48 | 0.007 |", md)

    def test_a_missing_file_is_exit_2_naming_it(self):
        proc = run_script("tables.py", "--error-memory", self.path("nosuch.csv"), check=False)
        self.assertEqual(proc.returncode, 2)
        self.assertIn("nosuch.csv", proc.stderr)


class TablesSlabDoc(unittest.TestCase):
    """docs/experiments/oit.md's SLAB-beside-STOCHASTIC table is --error-memory of the committed run."""

    def test_the_docs_tables_are_generated_from_the_committed_csvs(self):
        with open(os.path.join(REPO, "docs", "experiments", "oit.md"), encoding="utf-8") as f:
            doc = f.read()
        for driver, end_marker in (("llvmpipe", "<!-- end of SLAB table -->"),
                                   ("zink", "<!-- end of SLAB zink table -->")):
            csv_path = f"results/techniques/slab-stochastic-{driver}.csv"
            table = run_script("tables.py", "--error-memory", os.path.join(REPO, csv_path)).stdout
            marker = f"<!-- generated: scripts/tables.py --error-memory {csv_path} -->"
            begin = doc.index(marker) + len(marker) + 1
            self.assertEqual(doc[begin:doc.index(end_marker)], table,
                             f"docs/experiments/oit.md's SLAB table is stale; regenerate it with\n"
                             f"  scripts/tables.py --error-memory {csv_path}")


class TablesFromReferenceRuns(unittest.TestCase):
    """The approximate-OIT and line-primitive tables on the committed llvmpipe runs."""

    def setUp(self):
        self.paper = PUBLISHED
        self.results = os.path.join(REPO, "results", "llvmpipe")

    def test_bruell_approx_tables_set_ours_beside_the_thesis(self):
        out = run_script("tables.py", os.path.join(self.results, "presets", "bruell2018-approx.csv"), "--paper", self.paper,
                         "--table", "bruell-5.1").stdout
        self.assertIn("| powerplant | 4 | MLAB | 15.22 ms | 1x |", out)
        self.assertRegex(out, r"\| powerplant \| 4 \| UMLAB \| 14.75 ms \| 1.03x \| [0-9.]+ \| [0-9.]+x \|")

    def test_sintorn_poster_beside_the_lines_experiment(self):
        out = run_script("tables.py", os.path.join(self.results, "presets", "sintorn-lines.csv"), "--paper", self.paper,
                         "--table", "sintorn").stdout
        self.assertRegex(out, r"\| dog \| 1800000 \| 25 \| [0-9.]+ \| [0-9.]+ \|")
        self.assertRegex(out, r"\| woman2 \| 320000 \| 50 \| [0-9.]+ \| [0-9.]+ \|")  # the preset runs all four


@unittest.skipUnless(oitbench_exe(), "needs the built binary (OITBENCH_EXE)")
class TablesFromAFreshLinesRun(TempDirTest):
    """The poster's table from rows the lines experiment writes now (scenes/hair.json at two of the poster's
    sizes, tiny and one repetition): ours fill the models run, the others stay empty."""

    def test_the_poster_table_reads_a_run_of_the_hair_scene(self):
        out = self.path("lines.csv")
        run_oitbench("run", "lines", "--set", "technique=exact,slices", "--set", "scene=hair",
                     "--set", "segments=90000,320000", "--resolution", "32x32", "--reps", "1", "--warmup", "0",
                     "--no-progress", "--out", out)
        table = run_script("tables.py", out, "--paper", PUBLISHED, "--table", "sintorn").stdout
        self.assertRegex(table, r"\| beard \| 90000 \| 120 \| [0-9.]+ \| [0-9.]+ \|")
        self.assertRegex(table, r"\| woman2 \| 320000 \| 50 \| [0-9.]+ \| [0-9.]+ \|")
        self.assertIn("| dog | 1800000 | 25 | — | — |", table)


if __name__ == "__main__":
    unittest.main()
