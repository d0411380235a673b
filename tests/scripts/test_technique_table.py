"""The technique table (micro/oit/techniques.cpp) is the one place that knows the oit experiment's
techniques; scripts/techniques.json is its committed export (`oitbench list --techniques --json`),
which the scripts read. These tests fail when the two differ, when the table names a parameter the
experiment does not have, or when a parameter's scope in the result schema disagrees with the table."""
import json
import os
import re
import subprocess
import unittest

from support import oitbench_exe, run_oitbench
from synthetic import SCRIPTS

TECHNIQUES_JSON = os.path.join(SCRIPTS, "techniques.json")
SCHEMA_JSON = os.path.join(SCRIPTS, "schema.json")


def table_differences(committed, printed):
    """What differs between two exports, technique by technique and field by field."""
    a = {t["name"]: t for t in committed.get("techniques", [])}
    b = {t["name"]: t for t in printed.get("techniques", [])}
    out = [f"'{n}' only in the binary" for n in b if n not in a]
    out += [f"'{n}' only in scripts/techniques.json" for n in a if n not in b]
    for n in a:
        if n in b:
            out += [f"'{n}': {k} differs" for k in sorted(set(a[n]) | set(b[n])) if a[n].get(k) != b[n].get(k)]
    if not out and list(a) != list(b):
        out.append("the order differs")
    if not out and committed != printed:
        out.append("the fields around the techniques differ")
    return out


class TechniqueTableTest(unittest.TestCase):
    def setUp(self):
        if not oitbench_exe():
            self.skipTest("no oitbench binary (OITBENCH_EXE)")

    def printed(self):
        out = run_oitbench("list", "--techniques", "--json")
        self.assertEqual(out.returncode, 0, out.stderr)
        return json.loads(out.stdout)

    def test_committed_export_equals_the_binary(self):
        with open(TECHNIQUES_JSON, encoding="utf-8") as f:
            committed = json.load(f)
        self.assertEqual(table_differences(committed, self.printed()), [],
                         "regenerate: build/oitbench list --techniques --json > scripts/techniques.json")

    def test_a_changed_export_is_caught(self):
        printed = self.printed()
        changed = json.loads(json.dumps(printed))
        changed["techniques"][0]["params"].append("nodes")
        del changed["techniques"][-1]
        self.assertEqual(table_differences(changed, printed),
                         [f"'{printed['techniques'][-1]['name']}' only in the binary",
                          f"'{printed['techniques'][0]['name']}': params differs"])

    def test_parameters_and_their_scope_come_from_the_table(self):
        # Every parameter a technique reads is an oit parameter whose `applies_where` lists exactly
        # the techniques that read it, in the table's order.
        with open(SCHEMA_JSON, encoding="utf-8") as f:
            params = {c["name"]: c for c in json.load(f)["summary_columns"] if c.get("role") == "parameter"}
        techniques = self.printed()["techniques"]
        readers = {}
        for t in techniques:
            for p in t["params"]:
                readers.setdefault(p, []).append(t["name"])
        for p, names in readers.items():
            self.assertIn(p, params, f"{p}: not a parameter of any experiment")
            self.assertEqual(params[p].get("applies_where", {}).get("oit"), "technique in {" + ", ".join(names) + "}", p)

    def test_the_technique_parameter_is_described_from_the_table(self):
        # `oitbench list` describes the technique parameter from the table: every technique outside the
        # exact family is named there by name, so a new one shows up without an edit.
        out = run_oitbench("list")
        self.assertEqual(out.returncode, 0, out.stderr)
        line = next(l for l in out.stdout.splitlines() if l.strip().startswith("technique  resolve:"))
        for t in self.printed()["techniques"]:
            if t["family"] != "exact":
                self.assertRegex(line, r"(; |, )" + re.escape(t["name"]) + r"(, |: )", t["name"])

    def test_json_only_with_techniques(self):
        out = subprocess.run([oitbench_exe(), "list", "--json"], capture_output=True, text=True, timeout=60)
        self.assertEqual(out.returncode, 2, out.stderr)
        self.assertIn("--techniques", out.stderr)


if __name__ == "__main__":
    unittest.main()
