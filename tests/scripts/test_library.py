"""The scripts' library (scripts/oitbench/, issue 31 item 1): no script imports another script or touches
sys.path; the techniques come from scripts/techniques.json; the case key's identity comes from the
schema; the report's templates are files. The import check is shown to fail on a probe that breaks it."""
import ast
import glob
import json
import os
import unittest

from support import TempDirTest
from synthetic import SCRIPTS

from oitbench import casekey, techniques
from oitbench import results as oitres
from oitbench import report

SCRIPT_NAMES = {os.path.splitext(os.path.basename(p))[0] for p in glob.glob(os.path.join(SCRIPTS, "*.py"))}


def violations(path):
    """(line, what) for each import of another script and each sys.path change in a Python file."""
    with open(path, encoding="utf-8") as f:
        tree = ast.parse(f.read(), path)
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [(node.lineno, f"imports the script {a.name}") for a in node.names if a.name in SCRIPT_NAMES]
        elif isinstance(node, ast.ImportFrom) and node.module in SCRIPT_NAMES and node.level == 0:
            found.append((node.lineno, f"imports from the script {node.module}"))
        elif isinstance(node, ast.Attribute) and isinstance(node.value, ast.Attribute) \
                and ast.unparse(node.value) == "sys.path" and node.attr in ("insert", "append", "extend"):
            found.append((node.lineno, f"sys.path.{node.attr}"))
    return sorted(found)


class NoScriptImportsAScript(TempDirTest):
    def test_scripts_and_the_library(self):
        files = sorted(glob.glob(os.path.join(SCRIPTS, "*.py")) + glob.glob(os.path.join(SCRIPTS, "oitbench", "*.py")))
        self.assertGreater(len(files), 15)
        found = {os.path.relpath(p, SCRIPTS): violations(p) for p in files}
        self.assertEqual({p: v for p, v in found.items() if v}, {})

    def test_the_check_finds_a_script_import_and_a_path_change(self):
        probe = self.path("probe.py")
        with open(probe, "w", encoding="utf-8") as f:
            f.write("import sys\nsys.path.insert(0, '.')\nimport plot\nfrom tables import Ours\n"
                    "from oitbench import papers\n")
        self.assertEqual([w for _, w in violations(probe)],
                         ["sys.path.insert", "imports the script plot", "imports from the script tables"])


class Techniques(unittest.TestCase):
    def test_read_from_the_export(self):
        with open(os.path.join(SCRIPTS, "techniques.json"), encoding="utf-8") as f:
            table = json.load(f)["techniques"]
        self.assertEqual(techniques.names(), [t["name"] for t in table])
        exact = [t["name"] for t in table if t["family"] == "exact"]
        self.assertEqual(sorted(techniques.exact_in_paper_order()), sorted(exact))
        self.assertEqual(techniques.exact_in_paper_order()[0], "BASE-IS")
        self.assertEqual(techniques.exact_in_paper_order()[-1], "CPU-NATIVE")

    def test_roles_are_found_by_property(self):
        # The baseline is the table's first technique and the one the Knowles presets divide by.
        self.assertEqual(techniques.BASELINE, techniques.names()[0])
        for preset in ("knowles2013", "knowles2014", "knowles2014-quick"):
            with open(os.path.join(SCRIPTS, "..", "presets", preset + ".json"), encoding="utf-8") as f:
                grids = json.load(f)["runs"]
            baselines = {g["baseline"]["technique"] for g in grids if g.get("baseline")}
            self.assertEqual(baselines, {techniques.BASELINE}, preset)
        cpu = [t for t in techniques.TABLE if t["scheme"] == "CPU"]
        self.assertEqual([techniques.CPU_RESOLVE], [t["name"] for t in cpu])
        base = techniques.find(family="exact", scheme="BASE", sort="RBS-L")
        bma = techniques.twin(base, "BMA")
        self.assertEqual((techniques.scheme(bma), techniques.sort(bma)), ("BMA", "RBS-L"))
        self.assertIn("nodes", techniques.params(techniques.reading("nodes")[0]))
        self.assertFalse(techniques.reads("no such technique", "nodes"))

    def test_a_role_the_table_lacks_or_repeats_is_an_error(self):
        with self.assertRaisesRegex(oitres.ResultsError, r"techniques\.json: 0 techniques with scheme=NOSUCH"):
            techniques.find(scheme="NOSUCH")
        with self.assertRaisesRegex(oitres.ResultsError, r"techniques with family=exact, expected one"):
            techniques.find(family="exact")

    def test_the_papers_tables_are_data_and_a_broken_file_is_refused_naming_it(self):
        from oitbench import papers
        self.assertIn(techniques.BASELINE, papers.TECHNIQUES)
        self.assertEqual(papers.table("bruell-A.4").compare, [("MLAB stencil", "MLAB no stencil")])
        with self.assertRaisesRegex(oitres.ResultsError, r"nosuch\.json: cannot read"):
            papers.load_tables("nosuch.json")
        with self.assertRaisesRegex(oitres.ResultsError, r"techniques\.json: not the papers' tables"):
            papers.load_tables(os.path.join(SCRIPTS, "techniques.json"))

    def test_a_broken_export_is_refused_naming_it(self):
        with self.assertRaisesRegex(oitres.ResultsError, r"nosuch\.json: cannot read"):
            techniques.load("nosuch.json")


class CaseKey(unittest.TestCase):
    ROW = {"experiment": "oit", "variant": "", "pass": "total", "width": "64", "height": "64",
           "technique": "BASE-IS", "block": "8", "parameters": "technique;block"}

    def test_identity_from_the_schema(self):
        self.assertEqual(casekey.IDENTITY, ["experiment", "variant", "pass", "width", "height"])

    def test_the_forms_agree_on_the_identity(self):
        key = casekey.key(self.ROW, ["technique", "block"])
        self.assertEqual(key[:5], ("oit", "", "total", "64", "64"))
        self.assertEqual(key[5], "BASE-IS")
        self.assertEqual(key[6], "", "block applies to RBS techniques only (applies_where)")
        self.assertEqual(casekey.key(self.ROW, ["technique", "block"], scoped=False)[6], "8")
        self.assertEqual(casekey.named_key(self.ROW, skip={"block"}), key[:5] + ("technique=BASE-IS",))
        self.assertEqual(casekey.named_key(self.ROW, pairs=True)[5:], (("technique", "BASE-IS"), ("block", "8")))
        self.assertEqual(casekey.key(self.ROW, [], with_pass=False), ("oit", "", "64", "64"))


class Templates(unittest.TestCase):
    def test_the_page_is_built_from_the_template_files(self):
        for name in ("page.html", "report.css", "check.js"):
            self.assertTrue(os.path.isfile(os.path.join(report.TEMPLATES, name)), name)
        html = report.Page("t <1>", {"k": "v"}).render()
        self.assertIn("<title>t &lt;1&gt;</title>", html)
        self.assertIn('<meta name="k" content="v">\n<meta name="viewport"', html)
        self.assertIn(report.template("report.css"), html)
        self.assertIn(report.template("check.js"), html)
        self.assertNotIn("${", html)


if __name__ == "__main__":
    unittest.main()
