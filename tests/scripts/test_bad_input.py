"""Bad input to every script (issue 27, class 2), table-driven: tests/scripts/bad_input.tsv lists, per
script, its arguments, the kinds of bad file to feed it (generated here: a last row cut short, garbage,
a binary file, a NUL byte, a missing column, a CSV that is not oitbench's, an unknown schema version, an
empty file, a folder, a missing file) or a bad option value, the exit status (2) and the message that
must name the file (and line) or the option. Never a traceback. Every script in scripts/*.py has a line;
a shell script's lines (scripts/*.sh, run with bash) cover its options."""
import concurrent.futures
import glob
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import unittest

import synthetic as syn
from support import PYTHON, TempDirTest, run_script

TABLE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bad_input.tsv")
WORKERS = 4  # the runs are independent processes
KINDS = ["cut", "garbage", "binary", "nul", "missing-column", "foreign", "schema", "empty", "folder", "missing"]


def read_table(path=TABLE):
    """[(line, script, args, kinds, status, expected)] of the data file."""
    out = []
    with open(path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            if not line.strip() or line.startswith("#"):
                continue
            fields = line.rstrip("\n").split("\t")
            if len(fields) != 5:
                raise ValueError(f"{path}:{n}: {len(fields)} tab-separated fields, expected 5")
            script, args, kinds, status, expected = fields
            kinds = KINDS if kinds == "*" else [] if kinds == "-" else kinds.split(",")
            unknown = [k for k in kinds if k not in KINDS]
            if unknown:
                raise ValueError(f"{path}:{n}: unknown kind {unknown}")
            out.append((n, script, args, kinds, int(status), expected))
    return out


def good_files(folder):
    good, raw = os.path.join(folder, "good.csv"), os.path.join(folder, "good_raw.csv")
    syn.write_summary(good, syn.sort_rows(), [], ["n", "keys"], raw_path=raw)
    return good, raw


def write_bad(path, kind, good):
    """Writes the bad file of `kind` at `path` (nothing for `missing`); returns the regular expression its
    message must match, {BAD} standing for the path."""
    with open(good, encoding="utf-8") as f:
        lines = f.read().splitlines()
    header = lines[0].split(",")
    if kind == "cut":
        text = "\n".join(lines)
        with open(path, "w", encoding="utf-8") as f:
            f.write(text[:len(text) - len(lines[-1]) // 2])
        return r"{BAD}:%d: " % len(lines)
    if kind == "garbage":
        with open(path, "w", encoding="utf-8") as f:
            f.write('lorem ipsum, "dolor\nsit" amet, consectetur\nadipiscing\n')
        return r"{BAD}:\d+: "
    if kind == "binary":
        with open(path, "wb") as f:
            f.write(b"\x89PNG\r\n\x1a\n" + bytes(range(256)) * 8)
        return r"{BAD}:1: not a text file"
    if kind == "nul":
        with open(path, "w", encoding="utf-8") as f:
            f.write("\n".join(lines[:2] + [lines[2].replace(",", ",\0", 1)] + lines[3:]) + "\n")
        return r"{BAD}:3: not a text file"
    if kind == "missing-column":
        i = header.index("status")
        with open(path, "w", encoding="utf-8") as f:
            for line in lines:
                fields = line.split(",")
                f.write(",".join(fields[:i] + fields[i + 1:]) + "\n")
        return r"{BAD}:1: "
    if kind == "foreign":
        with open(path, "w", encoding="utf-8") as f:
            f.write("name,value,unit\nwidth,3,m\nheight,4,m\n")
        return r"{BAD}:1: not "
    if kind == "schema":
        i = header.index("schema")
        fields = lines[1].split(",")
        fields[i] = "99"
        with open(path, "w", encoding="utf-8") as f:
            f.write("\n".join([lines[0], ",".join(fields)] + lines[2:]) + "\n")
        return r"{BAD}:2: unknown schema version"
    if kind == "empty":
        open(path, "w", encoding="utf-8").close()
        return r"{BAD}"
    if kind == "folder":
        os.makedirs(path)
        return r"{BAD}"
    if kind == "missing":
        return r"{BAD}"
    raise ValueError(kind)


def clean(proc):
    """Why a bad-input run's output is not acceptable, or None: a traceback, or nothing said at all."""
    if "Traceback (most recent call last)" in proc.stderr:
        return "a Python traceback"
    if not proc.stderr.strip():
        return "no message on stderr"
    return None


class Case:
    """One line of the table with one kind of bad file: its arguments with the placeholders made real."""

    def __init__(self, folder, args, kind, good, raw):
        self.bad = None
        expected = None
        words = []
        for word in shlex.split(args):
            for name in ("BAD", "PRESETS", "ROUNDS", "ABDIR"):
                if "{" + name + "}" in word:
                    path, bad = self.place(folder, name)
                    expected = write_bad(bad, kind, good) if kind else None
                    self.bad = bad
                    word = word.replace("{" + name + "}", path)
            word = word.replace("{GOOD}", good).replace("{GOODRAW}", raw).replace("{OUT}", os.path.join(folder, "out"))
            words.append(word)
        self.args = words
        self.expected = expected.replace("{BAD}", re.escape(self.bad)) if expected else None

    @staticmethod
    def place(folder, name):
        """(the argument's path, the bad file's path) for a placeholder."""
        if name == "BAD":
            p = os.path.join(folder, "bad.csv")
            return p, p
        if name == "PRESETS":
            os.makedirs(os.path.join(folder, "results", "presets"), exist_ok=True)
            return os.path.join(folder, "results"), os.path.join(folder, "results", "presets", "default.csv")
        if name == "ROUNDS":
            for side in ("A", "B"):
                os.makedirs(os.path.join(folder, "ab", side), exist_ok=True)
            return os.path.join(folder, "ab"), os.path.join(folder, "ab", "A", "round-01.csv")
        os.makedirs(os.path.join(folder, "abdir"), exist_ok=True)
        return os.path.join(folder, "abdir"), os.path.join(folder, "abdir", "ab.csv")


class BadInputTable(TempDirTest):
    def run_case(self, n, script, args, kind, status, expected):
        """None, or what is wrong with this line's run on this kind of bad file."""
        folder = tempfile.mkdtemp(dir=self.dir)
        good, raw = good_files(folder)
        case = Case(folder, args, kind, good, raw)
        if case.bad and kind and os.path.basename(os.path.dirname(case.bad)) == "A":
            b = os.path.join(os.path.dirname(os.path.dirname(case.bad)), "B", "round-01.csv")
            if os.path.isdir(case.bad):
                os.makedirs(b)
            elif os.path.exists(case.bad):
                shutil.copy(case.bad, b)
        if script.endswith(".sh"):  # a shell script's options: run it as it is run
            proc = subprocess.run(["bash", os.path.join(syn.SCRIPTS, script)] + case.args, capture_output=True,
                                  text=True, timeout=120)
        else:
            proc = run_script(script, *case.args, check=False, timeout=120)
        where = f"{TABLE}:{n}: {script} {shlex.join(case.args)} ({kind or 'option'})"
        output = f"\n  stdout: {proc.stdout[-400:]!r}\n  stderr: {proc.stderr[-1500:]}"
        if proc.returncode != status:
            return f"{where}: exit {proc.returncode}, expected {status}{output}"
        if clean(proc):
            return f"{where}: {clean(proc)}{output}"
        if expected == "-":
            if case.expected is None:
                return f"{where}: '-' needs a bad file"
            if not re.search(case.expected, proc.stderr):
                return f"{where}: stderr does not match {case.expected}{output}"
        elif expected.replace("{BAD}", case.bad or "").replace("{GOOD}", good) not in proc.stderr:
            return f"{where}: stderr does not name {expected}{output}"
        return None

    def test_every_line_of_the_table(self):
        runs = [(n, script, args, kind, status, expected) for n, script, args, kinds, status, expected in read_table()
                for kind in kinds or [None]]
        with concurrent.futures.ThreadPoolExecutor(max_workers=WORKERS) as pool:
            problems = [p for p in pool.map(lambda r: self.run_case(*r), runs) if p]
        self.assertGreater(len(runs), 100)
        self.assertEqual(problems, [], f"{len(problems)} of {len(runs)} bad-input runs wrong:\n" + "\n".join(problems))

    def test_every_script_has_a_line(self):
        scripts_dir = os.path.join(syn.SCRIPTS)
        scripts = sorted(os.path.basename(p) for p in glob.glob(os.path.join(scripts_dir, "*.py")))
        covered = {script for _, script, _, _, _, _ in read_table()}
        self.assertEqual([s for s in scripts if s not in covered], [])
        # Shell scripts' lines are their options' (each must exist); every Python script has a line.
        self.assertEqual([s for s in covered if s not in scripts and not
                          (s.endswith(".sh") and os.path.isfile(os.path.join(scripts_dir, s)))], [])

    def test_every_kind_is_fed_to_some_script(self):
        fed = {k for _, _, _, kinds, _, _ in read_table() for k in kinds}
        self.assertEqual(sorted(set(KINDS) - fed), [])


class TheCheckFails(TempDirTest):
    """The assertions above catch what they are for: a script that traces back, one that says nothing,
    and a message that names another file."""

    def test_a_traceback_is_caught(self):
        proc = subprocess.run([PYTHON, "-c", "open('/nonexistent/x.csv')"], capture_output=True, text=True)
        self.assertNotEqual(proc.returncode, 0)
        self.assertEqual(clean(proc), "a Python traceback")

    def test_silence_is_caught(self):
        proc = subprocess.run([PYTHON, "-c", "import sys; sys.exit(2)"], capture_output=True, text=True)
        self.assertEqual(clean(proc), "no message on stderr")

    def test_a_message_without_the_line_does_not_match(self):
        good, _ = good_files(self.dir)
        case = Case(self.dir, "{BAD}", "binary", good, good)
        self.assertIsNone(re.search(case.expected, f"plot.py: {case.bad}: not a text file"))
        self.assertIsNotNone(re.search(case.expected, f"plot.py: {case.bad}:1: not a text file"))

    def test_the_table_reader_refuses_a_bad_line(self):
        path = self.path("t.tsv")
        with open(path, "w", encoding="utf-8") as f:
            f.write("plot.py\t{BAD}\tcut,nosuch\t2\t-\n")
        with self.assertRaisesRegex(ValueError, "unknown kind"):
            read_table(path)


MISSING = ("matplotlib", "numpy", "psycopg", "yaml")  # the third-party modules the scripts import


def without_modules(folder):
    """An environment whose Python cannot import MISSING: a package of each name, first on PYTHONPATH,
    that raises ModuleNotFoundError as a missing one does."""
    for name in MISSING:
        os.makedirs(os.path.join(folder, name), exist_ok=True)
        with open(os.path.join(folder, name, "__init__.py"), "w", encoding="utf-8") as f:
            f.write(f"raise ModuleNotFoundError(\"No module named '{name}'\", name='{name}')\n")
    return dict(os.environ, PYTHONPATH=folder)


class AMissingModule(TempDirTest):
    """A Python that cannot import a third-party module (another interpreter first in PATH, a package not
    installed) ends every script in one line naming the module, its Debian package and the interpreter,
    exit 1, never a traceback: at import time (oitbench's excepthook) and inside main (cli.run)."""

    def run_without(self, *args):
        env = without_modules(self.path("fake"))
        return subprocess.run([PYTHON, *args], capture_output=True, text=True, env=env, timeout=120)

    def test_every_script(self):
        problems = []
        for script in sorted(glob.glob(os.path.join(syn.SCRIPTS, "*.py"))):
            proc = self.run_without(script, "--help")
            name = os.path.basename(script)
            if clean(proc) == "a Python traceback":
                problems.append(f"{name}: a traceback\n{proc.stderr[-600:]}")
            elif proc.returncode not in (0, 1) or (proc.returncode == 1 and "cannot import" not in proc.stderr):
                problems.append(f"{name}: exit {proc.returncode}: {proc.stderr[-300:]}")
        self.assertEqual(problems, [])

    def test_a_figure_names_the_module_and_its_package(self):
        good, _ = good_files(self.dir)
        proc = self.run_without(os.path.join(syn.SCRIPTS, "plot.py"), good, "-o", self.path("out"))
        self.assertEqual(proc.returncode, 1, proc.stderr)
        self.assertIn("cannot import matplotlib: install python3-matplotlib", proc.stderr)
        self.assertIn(PYTHON.rsplit("/", 1)[-1], proc.stderr)
        self.assertEqual(clean(proc), None)

    def test_the_check_fails_without_the_hook(self):
        proc = self.run_without("-c", "import matplotlib")
        self.assertEqual(clean(proc), "a Python traceback")


if __name__ == "__main__":
    unittest.main(argv=sys.argv)
