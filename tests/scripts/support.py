"""Running the scripts the way a user does: /usr/bin/python3 (Debian's, with matplotlib) in a subprocess."""
import csv
import os
import shutil
import subprocess
import tempfile
import unittest

from synthetic import SCRIPTS

PYTHON = "/usr/bin/python3"
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def run_script(name, *args, check=True, timeout=300):
    env = dict(os.environ, MPLBACKEND="Agg")
    proc = subprocess.run([PYTHON, os.path.join(SCRIPTS, name)] + [str(a) for a in args], env=env,
                          capture_output=True, text=True, timeout=timeout)
    if check and proc.returncode != 0:
        raise AssertionError(f"{name} {' '.join(map(str, args))} exited {proc.returncode}:\n"
                             f"{proc.stdout}\n{proc.stderr}")
    return proc


def oitbench_exe():
    """The binary under test (ctest passes OITBENCH_EXE), or None: tests needing it are skipped."""
    exe = os.environ.get("OITBENCH_EXE")
    return exe if exe and os.access(exe, os.X_OK) else None


def run_oitbench(*args):
    proc = subprocess.run([oitbench_exe()] + [str(a) for a in args], capture_output=True, text=True, timeout=300)
    if proc.returncode != 0:
        raise AssertionError(f"oitbench {' '.join(map(str, args))} exited {proc.returncode}:\n{proc.stderr}")
    return proc


class TempDirTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="oitbench-scripts-")

    def tearDown(self):
        shutil.rmtree(self.dir, ignore_errors=True)

    def path(self, name):
        return os.path.join(self.dir, name)

    def assertPng(self, path):
        self.assertTrue(os.path.isfile(path), f"{path} was not written")
        with open(path, "rb") as f:
            head = f.read(8)
        self.assertEqual(head, PNG_MAGIC, f"{path} is not a PNG")
        self.assertGreater(os.path.getsize(path), 5000, f"{path} is suspiciously small")


def edit_csv(path, change):
    """Rewrites a CSV through change(header, rows) -> (header, rows)."""
    with open(path, newline="", encoding="utf-8") as f:
        reader = csv.DictReader(f)
        header, rows = list(reader.fieldnames), [dict(r) for r in reader]
    header, rows = change(header, rows)
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, fieldnames=header, lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
