"""findings.py: results/llvmpipe/FINDINGS.md is what the generator makes of the committed CSVs (regenerate
it when they change), its numbers follow the CSVs, it reads schema 2's column names as well as schema 1's,
and a folder without runs is a clear error."""
import difflib
import os
import shutil
import subprocess
import sys
import unittest

from support import PYTHON, TempDirTest, edit_csv
from synthetic import SCRIPTS

sys.path.insert(0, SCRIPTS)
from oitbench.findings import common as findings  # noqa: E402  (the wording findings.py uses)

REPO = os.path.dirname(SCRIPTS)
RESULTS = os.path.join(REPO, "results", "llvmpipe")
COMMITTED = os.path.join(RESULTS, "FINDINGS.md")


def generate(results_dir, cwd):
    """findings.py's output for a results folder, run from `cwd` the way a user runs it."""
    proc = subprocess.run([PYTHON, os.path.join(SCRIPTS, "findings.py"), results_dir], cwd=cwd,
                          capture_output=True, text=True, timeout=300, env=dict(os.environ, MPLBACKEND="Agg"))
    if proc.returncode != 0:
        raise AssertionError(f"findings.py {results_dir} exited {proc.returncode}:\n{proc.stderr}")
    return proc.stdout


def sections(text):
    """{heading: its text} of a FINDINGS page."""
    out, title = {}, ""
    for line in text.splitlines():
        if line.startswith("## "):
            title = line
        out[title] = out.get(title, "") + line + "\n"
    return out


def same_place(text, src, dst):
    """The text as if generated from folder `dst` instead of `src` (the page names its folder)."""
    return text.replace(os.path.relpath(src, REPO), os.path.relpath(dst, REPO))


class FindingsTest(TempDirTest):
    def copy_results(self, name):
        """The committed runs (presets/*.csv) in a folder of our own."""
        dest = self.path(name)
        shutil.copytree(os.path.join(RESULTS, "presets"), os.path.join(dest, "presets"))
        return dest

    def test_the_blends_are_the_mesh_blends_and_the_baseline_is_not_a_tie(self):
        """The no-OIT baseline is the blend reading the fewest parameters: a tie would make it the table's order's
        choice (GLOBAL-SORT, a splat order, once read as 'unsorted blending' this way), and a splat-only order
        is no blend of a mesh scene."""
        from oitbench import techniques
        fewest = min(len(techniques.params(b)) for b in findings.BLENDS)
        self.assertEqual([b for b in findings.BLENDS if len(techniques.params(b)) == fewest], [findings.UNSORTED])
        self.assertTrue(all(techniques.primitives(b) == "any" for b in findings.BLENDS), findings.BLENDS)
        self.assertIn(findings.WEIGHTED_BLEND, findings.BLENDS)

    def test_the_committed_findings_are_what_the_committed_csvs_give(self):
        got = generate(os.path.relpath(RESULTS, REPO), cwd=REPO)
        # From another working directory the same file comes out: paths are found from the script.
        self.assertEqual(generate(RESULTS, cwd=self.dir), got)
        with open(COMMITTED, encoding="utf-8") as f:
            committed = f.read()
        if got != committed:
            diff = "".join(list(difflib.unified_diff(committed.splitlines(True), got.splitlines(True),
                                                     "results/llvmpipe/FINDINGS.md (committed)",
                                                     "findings.py results/llvmpipe (now)"))[:200])
            self.fail("results/llvmpipe/FINDINGS.md is stale; regenerate it with\n"
                      "  /usr/bin/python3 scripts/findings.py results/llvmpipe -o results/llvmpipe/FINDINGS.md\n"
                      "and read what changed:\n" + diff)

    def test_a_changed_median_changes_its_numbers(self):
        original = self.copy_results("original")
        before = generate(original, cwd=self.dir)
        changed = self.copy_results("changed")
        doubled = {}

        def double_unrolled_33(header, rows):
            for r in rows:
                if r["variant"] == "unrolled" and r["size"] == "33" and r["pass"] == "total":
                    doubled["dynamic"] = next(float(x["median_ms"]) for x in rows if x["variant"] == "dynamic"
                                              and x["size"] == "33" and x["pass"] == "total") / float(r["draws"])
                    doubled["unrolled"] = float(r["median_ms"]) / float(r["draws"])
                    r["median_ms"] = repr(2 * float(r["median_ms"]))
            return header, rows

        def double_early_out_at_4(header, rows):
            for r in rows:
                if (r["experiment"], r["variant"], r["size"], r["keys"]) == ("insert", "early-out", "4", "random"):
                    r["median_ms"] = repr(2 * float(r["median_ms"]))
            return header, rows

        edit_csv(os.path.join(changed, "presets", "occupancy-fig3.csv"), double_unrolled_33)
        edit_csv(os.path.join(changed, "presets", "bruell2018-sorting.csv"), double_early_out_at_4)
        after = same_place(generate(changed, cwd=self.dir), changed, original)
        self.assertNotEqual(before, after)
        d, u = doubled["dynamic"], doubled["unrolled"]
        old = f"| 33 | {findings.f_ms(d)} | {findings.f_ms(u)} | {findings.f_x(d / u)} |"
        new = f"| 33 | {findings.f_ms(d)} | {findings.f_ms(2 * u)} | {findings.f_x(d / (2 * u))} |"
        self.assertIn(old, before)
        self.assertNotIn(old, after)
        self.assertIn(new, after)
        # The cliff sentence follows: the step from 32 to 33 is now twice as high.
        self.assertIn("to 33 (" + findings.f_ms(2 * u) + " ms)", after)
        # A.2's ratio at size 4 (early out / without) doubles beside the thesis's unchanged one.
        a2 = [line for line in after.splitlines() if line.startswith("| A.2:")]
        a2_before = [line for line in before.splitlines() if line.startswith("| A.2:")]
        self.assertEqual(len(a2), 1)
        first_after = float(a2[0].split("|")[4].split(",")[0])
        first_before = float(a2_before[0].split("|")[4].split(",")[0])
        self.assertAlmostEqual(first_after, 2 * first_before, delta=0.011)
        self.assertEqual(a2[0].split("|")[3], a2_before[0].split("|")[3])
        # Nothing else moved: the other sections read other CSVs.
        old_parts, new_parts = sections(before), sections(after)
        self.assertEqual(old_parts.keys(), new_parts.keys())
        moved = [t for t in old_parts if old_parts[t] != new_parts[t]]
        self.assertEqual(sorted(moved), ["## Occupancy", "## Sort and insert"])

    def test_the_memory_column_follows_the_rows_and_marks_an_episode(self):
        """The resolve table's `memory ns` is each row's host_mem_ns, with its slowest chase where that reached 1.5x
        (an episode that slows a list walk); rows of a schema before the probe show a dash and no Host sentence."""
        changed = self.copy_results("memory")

        def episode(header, rows):
            for r in rows:
                if (r["technique"], r["scene"], r["view"], r["order_check"], r["capture"]) == \
                        ("BASE-IS", "planes", "rev", "on", "PPLL"):
                    r["host_mem_ns"], r["host_mem_max_ns"] = "411", "977"
            return header, rows

        edit_csv(os.path.join(changed, "presets", "resolve-speedups.csv"), episode)
        text = sections(generate(changed, cwd=self.dir))["## The fastest exact resolve, paired"]
        row = [line for line in text.splitlines() if line.startswith("| planes rev | BASE-IS+order-check |")]
        self.assertEqual(len(row), 1, text)
        self.assertTrue(row[0].endswith("| 411 (max 977) |"), row[0])
        self.assertIn("slowest 977 ns", text)

        def no_probe(header, rows):
            gone = ("host_mem_ns", "host_mem_max_ns")
            return [k for k in header if k not in gone], [{k: v for k, v in r.items() if k not in gone} for r in rows]

        edit_csv(os.path.join(changed, "presets", "resolve-speedups.csv"), no_probe)
        text = sections(generate(changed, cwd=self.dir))["## The fastest exact resolve, paired"]
        self.assertNotIn("Memory latency between rounds", text)
        row = [line for line in text.splitlines() if line.startswith("| planes rev | BASE-IS+order-check |")]
        self.assertTrue(row[0].endswith(f"| {findings.DASH} |"), row[0])

    def test_schema_2_names_give_the_same_findings(self):
        """Schema 2 renames the metric max_frags to max_frags_used, adds sort_source and leaves empty the
        parameters a case does not use; the findings must not change."""
        one = self.copy_results("schema-one")
        two = self.copy_results("schema-two")

        def to_schema_2(header, rows):
            if "max_frags_used" in header:  # written by schema 2 or later: already named so
                return header, rows
            header = header[:header.index("parameters") + 1] + ["sort_source"] + \
                header[header.index("parameters") + 1:] + ["max_frags_used"]
            for r in rows:
                r["schema"] = "2"
                r["sort_source"] = ""
                r["max_frags_used"], r["max_frags"] = r.get("max_frags", ""), ""
                if r.get("experiment") == "oit":
                    if r.get("technique") not in findings.PER_PIXEL_ARRAY:
                        r["nodes"] = r["storage"] = ""
                    if r.get("technique") != "WBOIT":
                        r["wboit_weight"] = ""
            return header, rows

        for name in sorted(os.listdir(os.path.join(two, "presets"))):
            if name.endswith(".csv") and not name.endswith("_raw.csv"):
                edit_csv(os.path.join(two, "presets", name), to_schema_2)
        a = generate(one, cwd=self.dir)
        b = same_place(generate(two, cwd=self.dir), two, one)
        if a != b:
            self.fail("schema 2 names changed the findings:\n" + "".join(
                list(difflib.unified_diff(a.splitlines(True), b.splitlines(True), "schema 1", "schema 2"))[:80]))

    def test_a_folder_without_runs_is_a_clear_error(self):
        proc = subprocess.run([PYTHON, os.path.join(SCRIPTS, "findings.py"), self.dir], capture_output=True,
                              text=True, timeout=60)
        self.assertEqual(proc.returncode, 2)
        self.assertIn("no presets/ folder", proc.stderr)
        os.makedirs(self.path("presets"))
        proc = subprocess.run([PYTHON, os.path.join(SCRIPTS, "findings.py"), self.dir], capture_output=True,
                              text=True, timeout=60)
        self.assertEqual(proc.returncode, 2)
        self.assertIn("no oitbench summary CSV", proc.stderr)

    def test_words_come_from_the_numbers(self):
        self.assertEqual(findings.word(0.5), "faster")
        self.assertEqual(findings.word(1.05), "about even")
        self.assertEqual(findings.word(1.5), "slower")
        self.assertEqual(findings.verdict([0.5, 0.6, 0.7], "views"), "faster in all 3 views")
        self.assertEqual(findings.verdict([0.5, 1.0, 2.0, 3.0]), "1 faster, 1 about even, 2 slower of 4 cases")
        self.assertEqual(findings.span([0.4, 0.31, None]), "0.31\u20130.40")
        self.assertEqual(findings.field({"max_frags": "256", "max_frags_used": ""}, "max_frags_used", "max_frags"),
                         "256")
        self.assertEqual(findings.max_frags_used({"max_frags": "", "max_frags_used": "128"}), "128")


if __name__ == "__main__":
    unittest.main()
