"""The result schema is defined once, in C++ (micro/core/schema.cpp and each experiment's metric_specs()).
scripts/schema.json is a committed copy of `oitbench list --schema json` that the scripts read; these
tests fail when the two differ (a column added on one side only), when a file the binary writes has a
header the schema does not describe, and when a script types a column list of its own."""
import ast
import csv
import difflib
import json
import os
import subprocess
import unittest

from support import PYTHON, TempDirTest, oitbench_exe, run_oitbench
from synthetic import SCRIPTS

from oitbench import results as oitres

SCHEMA_JSON = os.path.join(SCRIPTS, "schema.json")


def schema_differences(committed, generated):
    """Readable differences between two schema JSON texts: columns added, removed or changed."""
    a, b = json.loads(committed), json.loads(generated)
    out = []
    for section in ("summary_columns", "raw_columns"):
        ca = {c["name"]: c for c in a.get(section, [])}
        cb = {c["name"]: c for c in b.get(section, [])}
        out += [f"{section}: '{n}' only in the binary" for n in cb if n not in ca]
        out += [f"{section}: '{n}' only in scripts/schema.json" for n in ca if n not in cb]
        out += [f"{section}: '{n}' differs" for n in ca if n in cb and ca[n] != cb[n]]
        if not out and [c["name"] for c in a.get(section, [])] != [c["name"] for c in b.get(section, [])]:
            out.append(f"{section}: the column order differs")
    if a.get("schema") != b.get("schema"):
        out.append(f"schema version {a.get('schema')} vs {b.get('schema')}")
    if a.get("statuses") != b.get("statuses"):
        out.append("statuses differ")
    if not out and committed != generated:
        out.append("the texts differ:\n" + "".join(difflib.unified_diff(
            committed.splitlines(True), generated.splitlines(True), "scripts/schema.json", "oitbench list --schema json")))
    return out


@unittest.skipUnless(oitbench_exe(), "needs the oitbench binary (OITBENCH_EXE)")
class CommittedSchemaIsTheBinarys(TempDirTest):
    def test_committed_copy_equals_the_binary_output(self):
        generated = run_oitbench("list", "--schema", "json").stdout
        with open(SCHEMA_JSON, encoding="utf-8") as f:
            committed = f.read()
        diffs = schema_differences(committed, generated)
        self.assertEqual(diffs, [], "scripts/schema.json is stale; regenerate it with "
                                    "`build/oitbench list --schema json > scripts/schema.json`:\n" + "\n".join(diffs))

    def test_the_check_fails_on_a_column_added_on_one_side(self):
        generated = run_oitbench("list", "--schema", "json").stdout
        j = json.loads(generated)
        extra = dict(j["summary_columns"][0], name="added_in_cpp_only")
        j["summary_columns"].append(extra)
        diffs = schema_differences(generated, json.dumps(j, indent=2) + "\n")
        self.assertIn("summary_columns: 'added_in_cpp_only' only in the binary", diffs)
        j = json.loads(generated)
        del j["raw_columns"][-1]
        self.assertTrue(schema_differences(generated, json.dumps(j, indent=2) + "\n"))

    def test_written_headers_are_the_schemas_columns_in_order(self):
        out, raw = os.path.join(self.dir, "o.csv"), os.path.join(self.dir, "r.csv")
        run_oitbench("run", "occupancy", "--quick", "--set", "size=1", "--reps", "1", "--no-progress",
                     "--out", out, "--raw", raw)
        with open(out, newline="") as f:
            header = next(csv.reader(f))
        with open(raw, newline="") as f:
            raw_header = next(csv.reader(f))
        self.assertEqual(header, [c["name"] for c in oitres.SCHEMA["summary_columns"]])
        self.assertEqual(raw_header, [c["name"] for c in oitres.SCHEMA["raw_columns"]])
        with open(out, newline="") as f:
            rows = list(csv.DictReader(f))
        self.assertTrue(rows)
        for r in rows:
            self.assertIn(r["status"], oitres.STATUSES)
            self.assertEqual(r["schema"], str(oitres.SCHEMA_VERSION))


class SchemaPageIsGenerated(TempDirTest):
    def test_committed_page_equals_the_generated_one(self):
        out = os.path.join(self.dir, "csv-schema.md")
        proc = subprocess.run([PYTHON, os.path.join(SCRIPTS, "schema_doc.py"), "-o", out], capture_output=True, text=True)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        with open(out, encoding="utf-8") as f:
            generated = f.read()
        with open(os.path.join(SCRIPTS, "..", "docs", "csv-schema.md"), encoding="utf-8") as f:
            committed = f.read()
        self.assertEqual(committed, generated, "docs/csv-schema.md is stale: /usr/bin/python3 scripts/schema_doc.py")
        for c in oitres.SCHEMA["summary_columns"]:
            self.assertIn(f"`{c['name']}`", generated)


class ScriptsTypeNoColumnList(unittest.TestCase):
    def column_lists(self, path):
        """List, tuple and set literals in a script with three or more of the schema's column names."""
        names = {c["name"] for c in oitres.SCHEMA["summary_columns"]} | {c["name"] for c in oitres.SCHEMA["raw_columns"]}
        with open(path, encoding="utf-8") as f:
            tree = ast.parse(f.read(), path)
        found = []
        for node in ast.walk(tree):
            if isinstance(node, (ast.List, ast.Tuple, ast.Set)):
                strings = [e.value for e in node.elts if isinstance(e, ast.Constant) and isinstance(e.value, str)]
                hits = [s for s in strings if s in names]
                if len(hits) >= 3 and len(hits) == len(node.elts):
                    found.append((node.lineno, hits))
        return found

    def test_the_reader_derives_every_column_list_from_the_schema(self):
        self.assertEqual(self.column_lists(os.path.join(SCRIPTS, "oitbench", "results.py")), [])
        self.assertIn("median_ms", oitres.BASE_COLUMNS)
        self.assertIn("rmse", oitres.KNOWN_METRICS)
        self.assertIn("backend", oitres.RUN_COLUMNS)
        self.assertEqual(oitres.FRAMEWORK_PARAMS, ["fault", "seed"])

    def test_the_check_finds_a_typed_list(self):
        path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "_typed_list_probe.py")
        try:
            with open(path, "w", encoding="utf-8") as f:
                f.write('COLS = ["experiment", "variant", "median_ms"]\n')
            self.assertEqual(len(self.column_lists(path)), 1)
        finally:
            os.remove(path)


if __name__ == "__main__":
    unittest.main()
