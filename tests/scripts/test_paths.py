"""Every source path named in the project's own text exists: a comment in micro/ or shaders/, a doc page, the
README. A file that moves without its references leaves a reader at a dead end (issue 25 found
micro/oit/approx.cpp cited five times after it had been split). A path is checked as written; a stem without
its extension (`micro/oit/storage_layout`) counts when a file of that stem exists. Placeholders (NAME, STEP,
a trailing `_` or `-`) and the made-up paths of tests' fixtures are not references."""
import os
import re
import subprocess
import unittest

from synthetic import SCRIPTS

ROOT = os.path.dirname(SCRIPTS)
# Where a path is a reference a reader follows (tests/ is left out: its fixtures name made-up files).
SCANNED = re.compile(r"^(micro|shaders)/|^docs/.*\.md$|^README\.md$")
PATH = re.compile(r"(?<![\w/.$-])((?:micro|shaders)/[A-Za-z0-9_./-]+)")


def tracked_files():
    out = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True)
    if out.returncode != 0:
        return None
    return [f for f in out.stdout.splitlines() if SCANNED.search(f)]


def exists(path):
    full = os.path.join(ROOT, path)
    if os.path.exists(full):
        return True
    folder, stem = os.path.split(full)
    return os.path.isdir(folder) and any(f.startswith(stem + ".") for f in os.listdir(folder))


def dead_references(files):
    out = []
    for f in files:
        with open(os.path.join(ROOT, f), encoding="utf-8", errors="replace") as fh:
            for line_no, line in enumerate(fh, 1):
                for m in PATH.finditer(line):
                    path = m.group(1).rstrip(".,:;)")
                    placeholder = "NAME" in path or "STEP" in path or path.endswith(("_", "-"))
                    if not placeholder and not exists(path):
                        out.append(f"{f}:{line_no}: {path}")
    return out


class PathTest(unittest.TestCase):
    def setUp(self):
        self.files = tracked_files()
        if self.files is None:
            self.skipTest("not a git checkout")

    def test_every_named_path_exists(self):
        self.assertEqual(dead_references(self.files), [])

    def test_a_dead_reference_is_found(self):
        # The check can fail: a file naming a path that is not there is reported with its line.
        probe = os.path.join(ROOT, "micro", "_probe_paths.txt")
        with open(probe, "w", encoding="utf-8") as f:
            f.write("see micro/oit/approx.cpp and micro/oit/scene\n")
        try:
            self.assertEqual(dead_references(["micro/_probe_paths.txt"]), ["micro/_probe_paths.txt:1: micro/oit/approx.cpp"])
        finally:
            os.remove(probe)


if __name__ == "__main__":
    unittest.main()
