"""The result store (scripts/oitbench/store, scripts/store.py) on both backends: SQLite in a temp file and a
real PostgreSQL 15 started for the test (pgserver.py). Every committed oitbench CSV under results/ ingests
and reads back value for value; ingesting again adds nothing; four concurrent ingesters of overlapping
files lose and duplicate nothing; damaged files, unknown schema versions, unreachable servers and stores of
a newer schema are refused with a clear message."""
import json
import math
import os
import shutil
import subprocess
import tempfile
import time
import unittest

from synthetic import SCRIPTS  # noqa: F401  (puts scripts/ on sys.path)
import pgserver
from oitbench.store import StoreError, open_store, redact_url
from oitbench.store import csvfile, sqlschema

REPO = os.path.dirname(SCRIPTS)
RESULTS = os.path.join(REPO, "results")
PYTHON = "/usr/bin/python3"
SERVER = None


def setUpModule():
    global SERVER
    SERVER = pgserver.PgServer.start()


def tearDownModule():
    if SERVER:
        SERVER.stop()


def run_csvs():
    """Every committed CSV that `oitbench run` wrote (summary or --raw): papers' tables, image histograms and
    compare.py's output are not run results."""
    out = []
    for root, dirs, files in os.walk(RESULTS):
        dirs.sort()
        for f in sorted(files):
            if f.endswith(".csv"):
                p = os.path.join(root, f)
                with open(p, encoding="utf-8") as fh:
                    header = fh.readline().strip().split(",")
                if "schema" in header and csvfile.file_kind(header):
                    out.append(p)
    return out


def same_value(name, stored, original, types):
    if stored == original:
        return True
    t = types.get(name)
    if t in ("number", "integer", "flag") and stored != "" and original != "":
        return math.isclose(float(stored), float(original), rel_tol=1e-15, abs_tol=0)
    return False


def store_cli(store_url, *args, check=True):
    proc = subprocess.run([PYTHON, os.path.join(SCRIPTS, "store.py"), "--store", store_url] + list(args),
                          capture_output=True, text=True, timeout=600)
    if check and proc.returncode != 0:
        raise AssertionError(f"store.py {' '.join(args)} exited {proc.returncode}:\n{proc.stdout}{proc.stderr}")
    return proc


class Backend:
    """The tests, run once per backend (SqliteStoreTest, PostgresStoreTest)."""

    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="oitbench-store-")
        self.url = self.new_store()

    def tearDown(self):
        shutil.rmtree(self.dir, ignore_errors=True)

    def write(self, name, text):
        path = os.path.join(self.dir, name)
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)
        return path

    def small_csv(self, name="small.csv", version="5", rows=3, cut=False):
        header = "schema,experiment,variant,pass,status,valid,width,height,median_ms,driver,run_id,tags,parameters,size"
        lines = [header]
        for i in range(rows):
            lines.append(f"{version},occupancy,unrolled,total,ok,1,64,64,{1.5 + i},llvmpipe,"
                         f"0f8fad5b-d9cb-469f-a165-70867728950e,pool=ci,size,{i}")
        text = "\n".join(lines) + "\n"
        if cut:
            text = text[:-9]
        return self.write(name, text)

    def count(self, store, table):
        return store.query(f"SELECT COUNT(*) AS n FROM {table}")[0]["n"]

    def test_every_committed_csv_ingests_and_reads_back_value_for_value(self):
        files = run_csvs()
        self.assertGreater(len(files), 50)
        with open_store(self.url) as s:
            for path in files:
                rows, added = s.ingest(path)
                self.assertEqual(rows, len(csvfile.read(path).rows))
            n_rows, n_samples = self.count(s, "rows"), self.count(s, "samples")
            for path in files:
                f, back = s.read_back(path)
                types = f.types
                for line, original, stored in zip(f.lines, f.rows, back):
                    self.assertIsNotNone(stored, f"{path}:{line} not stored")
                    for name in f.header:
                        self.assertTrue(same_value(name, stored[name], original[name], types),
                                        f"{path}:{line} {name}: stored {stored[name]!r}, file {original[name]!r}")
            # Everything again: nothing new.
            for path in files:
                self.assertEqual(s.ingest(path)[1], 0, path)
            self.assertEqual((self.count(s, "rows"), self.count(s, "samples")), (n_rows, n_samples))
        # A copy of a file under another name (its bytes differ: a line end more) adds nothing either.
        copy = self.write("copy.csv", open(files[0], encoding="utf-8").read())
        with open_store(self.url) as s:
            self.assertEqual(s.ingest(copy)[1], 0)
        print(f"{type(self).__name__}: {len(files)} files, {n_rows} rows, {n_samples} samples")

    def test_a_schema_6_time_account_reads_back_value_for_value(self):
        header = ("schema,experiment,variant,pass,status,valid,width,height,median_ms,driver,run_id,tags,"
                  "case_wall_s,phase_samples_s,phase_reference_s,phase_other_s,parameters,size")
        path = self.write("account.csv", header + "\n" + "".join(
            f"6,occupancy,unrolled,total,ok,1,64,64,{1.5 + i},llvmpipe,0f8fad5b-d9cb-469f-a165-70867728950e,,"
            f"{2.5 + i},{1.25 + i},0.75,0.5,size,{i}\n" for i in range(2)))
        with open_store(self.url) as s:
            self.assertEqual(s.ingest(path)[0], 2)
            f, back = s.read_back(path)
            for line, original, stored in zip(f.lines, f.rows, back):
                for name in f.header:
                    self.assertTrue(same_value(name, stored[name], original[name], f.types),
                                    f"{line} {name}: stored {stored[name]!r}, file {original[name]!r}")

    def test_the_command_ingests_folders_and_lists_runs(self):
        small = self.small_csv()
        proc = store_cli(self.url, "ingest", small)
        self.assertIn("3 rows read, 3 new", proc.stdout)
        proc = store_cli(self.url, "ingest", small)
        self.assertIn("3 rows read, 0 new", proc.stdout)
        proc = store_cli(self.url, "runs", "--tag", "pool=ci")
        self.assertIn("0f8fad5b", proc.stdout)
        self.assertIn("pool=ci", proc.stdout)
        proc = store_cli(self.url, "runs", "--tag", "pool=nightly", check=False)
        self.assertEqual(proc.returncode, 1)
        self.assertIn("no run matches", proc.stderr)

    def test_concurrent_ingesters_lose_and_duplicate_nothing(self):
        files = []
        for i in range(6):
            header = "schema,experiment,variant,pass,status,valid,width,height,median_ms,run_id,parameters,size"
            rows = [f"5,occupancy,unrolled,total,ok,1,64,64,{1 + j / 7},{i:08d}-0000-4000-8000-000000000000,"
                    f"size,{j}" for j in range(400)]
            files.append(self.write(f"f{i}.csv", "\n".join([header] + rows) + "\n"))
        # Four writers, each with four of the six files (every file by two or three writers), at once.
        sets = [files[0:4], files[2:6], files[1:5], [files[0], files[5], files[3], files[1]]]
        procs = [subprocess.Popen([PYTHON, os.path.join(SCRIPTS, "store.py"), "--store", self.url, "ingest"] + s,
                                  stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) for s in sets]
        added = 0
        for p in procs:
            out, err = p.communicate(timeout=600)
            self.assertEqual(p.returncode, 0, err)
            added += int(out.split(" rows read, ")[1].split(" new")[0])
        self.assertEqual(added, 6 * 400)
        with open_store(self.url) as s:
            self.assertEqual(self.count(s, "rows"), 6 * 400)
            self.assertEqual(self.count(s, "runs"), 6)
            self.assertEqual(self.count(s, "files"), 6)

    def test_damaged_or_unknown_files_are_refused_whole(self):
        cut = self.small_csv("cut.csv", cut=True)
        newer = self.small_csv("newer.csv", version=str(sqlschema.CSV_SCHEMA + 1))
        short = self.write("short.csv", open(self.small_csv(), encoding="utf-8").read() + "5,occupancy,unrolled\n")
        with open_store(self.url) as s:
            with self.assertRaisesRegex(StoreError, r"cut\.csv:4: damaged row: 12 fields where the header has 14"):
                s.ingest(cut)
            with self.assertRaisesRegex(StoreError, rf"newer\.csv:2: unknown schema version "
                                                    rf"'{sqlschema.CSV_SCHEMA + 1}'"):
                s.ingest(newer)
            with self.assertRaisesRegex(StoreError, r"short\.csv:5: damaged row"):
                s.ingest(short)
            self.assertEqual(self.count(s, "rows"), 0)
            self.assertEqual(self.count(s, "runs"), 0)
            self.assertEqual(self.count(s, "files"), 0)
        unterminated = self.write("unterminated.csv", open(self.small_csv(), encoding="utf-8").read().rstrip("\n"))
        proc = store_cli(self.url, "ingest", unterminated, check=False)
        self.assertEqual(proc.returncode, 2)
        self.assertIn("unterminated.csv:4: the last row is cut off", proc.stderr)
        self.assertNotIn("Traceback", proc.stderr)

    def test_a_store_of_a_newer_schema_is_refused(self):
        with open_store(self.url) as s:
            s.ingest(self.small_csv())
            with s._write_transaction() as cur:
                cur.execute(s._sql("UPDATE store_meta SET value = ? WHERE key = 'csv_schema'"),
                            (str(sqlschema.CSV_SCHEMA + 1),))
        with self.assertRaisesRegex(StoreError, "written by a newer oitbench"):
            open_store(self.url)
        proc = store_cli(self.url, "runs", check=False)
        self.assertEqual(proc.returncode, 2)
        self.assertIn("written by a newer oitbench", proc.stderr)

    def test_an_older_store_gains_the_new_columns(self):
        with open_store(self.url) as s:
            s.ingest(self.small_csv())
            with s._write_transaction() as cur:
                cur.execute('ALTER TABLE rows DROP COLUMN "machine_id"')
                cur.execute('ALTER TABLE rows DROP COLUMN "phase_samples_s"')  # schema 6's time account
                cur.execute(s._sql("UPDATE store_meta SET value = '4' WHERE key = 'csv_schema'"))
        with open_store(self.url) as s:
            self.assertIn("machine_id", s._columns_now("rows"))
            self.assertIn("phase_samples_s", s._columns_now("rows"))
            self.assertEqual(s.query("SELECT value FROM store_meta WHERE key = 'csv_schema'")[0]["value"],
                             str(sqlschema.CSV_SCHEMA))
            self.assertEqual(self.count(s, "rows"), 3)


class SqliteStoreTest(Backend, unittest.TestCase):
    def new_store(self):
        return os.path.join(self.dir, "store.sqlite")

    def test_a_file_that_is_not_sqlite_is_refused(self):
        bad = self.write("bad.sqlite", "not a database" * 100)
        with self.assertRaisesRegex(StoreError, "bad.sqlite: not a usable SQLite store"):
            open_store(bad)


@unittest.skipIf(pgserver.available(), pgserver.available())
class PostgresStoreTest(Backend, unittest.TestCase):
    def new_store(self):
        self.db = f"t{os.getpid()}_{int(time.time() * 1000) % 10**9}"
        return SERVER.url(self.db)

    def tearDown(self):
        SERVER.drop(self.db)
        super().tearDown()

    def test_an_unreachable_server_is_named_without_its_password_within_seconds(self):
        for url in ("postgresql://alice:s3cret@127.0.0.1:1/oitbench",
                    f"postgresql://alice:s3cret@/nodb?host={self.dir}&port=1"):
            t = time.monotonic()
            with self.assertRaises(StoreError) as e:
                open_store(url)
            self.assertLess(time.monotonic() - t, 10)
            self.assertIn("alice:***@", str(e.exception))
            self.assertIn("cannot connect", str(e.exception))
            self.assertNotIn("s3cret", str(e.exception))
        proc = store_cli("postgresql://alice:s3cret@127.0.0.1:1/oitbench", "runs", check=False)
        self.assertEqual(proc.returncode, 2)
        self.assertNotIn("s3cret", proc.stderr)
        self.assertNotIn("Traceback", proc.stderr)
        self.assertEqual(redact_url("host=x password=s3cret dbname=y"), "host=x password=*** dbname=y")


if __name__ == "__main__":
    unittest.main()
