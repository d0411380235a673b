"""Scripts ask the technique table (scripts/oitbench/techniques.py, reading scripts/techniques.json) for
technique names instead of spelling them (issue 25: the table is the one place that knows techniques).
This test counts the string literals in scripts/*.py and scripts/oitbench/**/*.py that spell a technique
name or a resolve scheme's prefix ("BMA-", "CS-"); docstrings and comments are left out. What remains
is named in REMAINING, file by file, with why (the papers' own row names are data, in
results/published/tables.json). A file over its count fails, and the check is shown to fail on a probe."""
import glob
import io
import json
import os
import re
import tokenize
import unittest

from support import TempDirTest
from synthetic import SCRIPTS

# Files that still spell names, and how many string literals may: one sentence of fixed prose (why the
# thesis's unbounded variants gain nothing on a CPU rasteriser). The papers' own row names are data in
# results/published/tables.json.
REMAINING = {
    "oitbench/findings/approx.py": 1,
}


def spellings():
    """A regular expression matching any technique name or scheme prefix of the table, as a word."""
    with open(os.path.join(SCRIPTS, "techniques.json"), encoding="utf-8") as f:
        table = json.load(f)["techniques"]
    words = {t["name"] for t in table if not t["name"].islower()} | {t["scheme"] + "-" for t in table if t["scheme"]}
    words.add("CUDA-")  # the paper's name for our compute-shader scheme
    alternatives = "|".join(re.escape(w) for w in sorted(words, key=len, reverse=True))
    # A name that is an English word ("unsorted") counts where it is the whole literal.
    plain = "|".join(re.escape(t["name"]) for t in table if t["name"].islower())
    return re.compile(r"(?<![A-Za-z0-9_-])(?:" + alternatives + r")(?![A-Za-z0-9_])" +
                      (r"|^[\"'](?:" + plain + r")[\"']$" if plain else ""))


def literals_spelling(path, pattern):
    """(line, literal) for each string literal of a Python file, docstrings left out, that spells a name."""
    with open(path, encoding="utf-8") as f:
        source = f.read()
    found, previous = [], None
    for tok in tokenize.generate_tokens(io.StringIO(source).readline):
        if tok.type == tokenize.STRING:
            docstring = previous in (None, tokenize.INDENT, tokenize.NEWLINE, tokenize.DEDENT) \
                and tok.string.lstrip("rRbBuUfF")[:3] in ('"""', "'''")
            if not docstring and pattern.search(tok.string):
                found.append((tok.start[0], tok.string))
        if tok.type not in (tokenize.NL, tokenize.COMMENT):
            previous = tok.type
    return found


# C++ that still spells names outside the technique table (micro/oit/techniques.*), with why: RBS-G is also the
# label of a resolve sort in the sorts' own list (micro/oit/resolve/resolve_sort.cpp).
REMAINING_CPP = {
    "oit/resolve/resolve_sort.cpp": 1,
}
MICRO = os.path.join(os.path.dirname(SCRIPTS), "micro")
# A C++ token that may hold a name: a comment (skipped), a raw string, a character or a string literal.
CPP_TOKEN = re.compile(r'//[^\n]*|/\*.*?\*/|R"\((?:.|\n)*?\)"|\'(?:[^\'\\\n]|\\.)+\'|"(?:[^"\\\n]|\\.)*"', re.S)


def cpp_literals_spelling(path, pattern):
    """(line, literal) for each string literal of a C++ file, comments left out, that spells a name."""
    with open(path, encoding="utf-8") as f:
        source = f.read()
    return [(source.count("\n", 0, m.start()) + 1, m.group(0)) for m in CPP_TOKEN.finditer(source)
            if m.group(0)[0] in "R\"" and pattern.search(m.group(0))]


def cpp_files():
    files = glob.glob(os.path.join(MICRO, "**", "*.[ch]pp"), recursive=True)
    return sorted(os.path.relpath(p, MICRO) for p in files if not os.path.basename(p).startswith("techniques."))


def script_files():
    files = glob.glob(os.path.join(SCRIPTS, "*.py")) + glob.glob(os.path.join(SCRIPTS, "oitbench", "**", "*.py"),
                                                                 recursive=True)
    return sorted(os.path.relpath(p, SCRIPTS) for p in files)


class NoTechniqueNamesInScripts(TempDirTest):
    def assert_within_remaining(self, root, files, scan, remaining, at_least, advice):
        """Every file under `root` spells at most its `remaining` count of names (none where unlisted)."""
        pattern = spellings()
        self.assertGreater(len(files), at_least)
        over = {}
        for rel in files:
            found = scan(os.path.join(root, rel), pattern)
            if len(found) > remaining.get(rel, 0):
                over[rel] = [f"{line}: {text}" for line, text in found]
        self.assertEqual(over, {}, advice)

    def test_scripts_read_names_from_the_table(self):
        self.assert_within_remaining(SCRIPTS, script_files(), literals_spelling, REMAINING, 30,
                                     "these scripts spell technique names: ask oitbench.techniques instead")

    def test_cpp_outside_the_table_reads_names_from_it(self):
        self.assert_within_remaining(MICRO, cpp_files(), cpp_literals_spelling, REMAINING_CPP, 100,
                                     "these C++ files spell technique names: ask micro/oit/techniques.hpp instead")

    def test_the_cpp_check_finds_literals_but_not_comments(self):
        probe = self.path("probe.cpp")
        with open(probe, "w", encoding="utf-8") as f:
            f.write('// BASE-IS in a comment\n/* MLAB\n in a block */\nchar q = \'"\';\n'
                    'auto a = "BMA-RBS-L", b = "approx/unsorted.frag";\nauto c = "unsorted";\n'
                    'auto d = R"(x "CS-IS" y)"; auto e = "\\" WOIT";\n')
        self.assertEqual(cpp_literals_spelling(probe, spellings()),
                         [(5, '"BMA-RBS-L"'), (6, '"unsorted"'), (7, 'R"(x "CS-IS" y)"'), (7, '"\\" WOIT"')])

    def test_the_check_finds_names_but_not_docstrings_or_comments(self):
        probe = self.path("probe.py")
        with open(probe, "w", encoding="utf-8") as f:
            f.write('"""BASE-IS in a docstring."""\n# BMA-IS in a comment\n'
                    'def f(row):\n    """MLAB in a docstring."""\n'
                    '    if row["technique"] == "BMA-RBS-L":\n        return f"{row} CS-*"\n'
                    '    return "unsorted" + "SUBASE-IS" + "MLABS"\n')
        self.assertEqual(literals_spelling(probe, spellings()),
                         [(5, '"BMA-RBS-L"'), (6, 'f"{row} CS-*"'), (7, '"unsorted"')])


if __name__ == "__main__":
    unittest.main()
