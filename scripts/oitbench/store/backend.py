"""The two backends behind one interface: SQLite (python3's sqlite3, a local file) and PostgreSQL (Debian's
python3-psycopg, psycopg 3) by URL. They differ only in how they connect, lock and stage rows; the SQL
is the same (quoted identifiers, INSERT ... ON CONFLICT DO NOTHING)."""
import datetime
import json
import os
import re
import sqlite3
import time
import urllib.parse

from oitbench.store import csvfile, sqlschema
from oitbench.store.sqlschema import q

DEFAULT_SQLITE = os.path.join("results", "local", "oitbench.sqlite")


class StoreError(Exception):
    """Anything that keeps the store from being opened or a file from being stored: the message says what."""


def redact_url(url):
    """The URL without its password (postgresql://user:***@host/db; password=*** in a key=value string)."""
    try:
        parts = urllib.parse.urlsplit(url)
        if parts.password is not None:
            host = parts.netloc.rsplit("@", 1)[1]
            user = parts.username or ""
            parts = parts._replace(netloc=f"{user}:***@{host}")
        query = re.sub(r"(^|&)password=[^&]*", r"\1password=***", parts.query)
        url = urllib.parse.urlunsplit(parts._replace(query=query))
    except ValueError:
        pass
    return re.sub(r"password\s*=\s*\S+", "password=***", url)


def is_postgres_url(url):
    return url.startswith(("postgresql://", "postgres://")) or bool(re.match(r"^\s*\w+\s*=", url))


def open_store(url=None, connect_timeout=5):
    """A Store for a PostgreSQL URL (postgresql://USER[:PASSWORD]@HOST[:PORT]/DB, or ...?host=/socket/dir) or
    a SQLite file (a path, or sqlite:///path). Default: $OITBENCH_STORE, else results/local/oitbench.sqlite."""
    url = url or os.environ.get("OITBENCH_STORE") or DEFAULT_SQLITE
    if is_postgres_url(url):
        return PostgresStore(url, connect_timeout)
    if url.startswith("sqlite:///"):
        url = url[len("sqlite://"):]
    elif url.startswith("sqlite:"):
        url = url[len("sqlite:"):]
    return SqliteStore(url)


def _now():
    return datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")


class Store:
    dialect = ""
    ph = "?"

    def __init__(self):
        self.conn = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        if self.conn is not None:
            self.conn.close()
            self.conn = None

    # --- reading ---------------------------------------------------------------------------------------
    def query(self, sql, params=()):
        """Rows of a SELECT as dicts; `?` placeholders in either backend."""
        cur = self.conn.cursor()
        cur.execute(self._sql(sql), tuple(params))
        names = [d[0] for d in cur.description]
        out = [dict(zip(names, r)) for r in cur.fetchall()]
        self._end_read()
        return out

    def _sql(self, sql):
        return sql if self.ph == "?" else sql.replace("%", "%%").replace("?", self.ph)

    def _end_read(self):
        pass

    def _columns_now(self, table):
        """The table's columns as the database has them."""
        cur = self.conn.cursor()
        out = self._existing_columns(cur, table)
        self._end_read()
        return out

    def columns(self, table):
        return [n for n, _ in sqlschema.table_columns(table, self.dialect)]

    # --- setup -----------------------------------------------------------------------------------------
    def _meta(self):
        """store_meta as a dict, or None where the table does not exist yet."""
        if not self._has_table("store_meta"):
            return None
        return {r["key"]: r["value"] for r in self.query("SELECT key, value FROM store_meta")}

    def _check_versions(self, meta):
        store_version = int(meta.get("store_version", sqlschema.STORE_VERSION))
        csv_schema = int(meta.get("csv_schema", sqlschema.CSV_SCHEMA))
        if store_version > sqlschema.STORE_VERSION or csv_schema > sqlschema.CSV_SCHEMA:
            raise StoreError(f"{self.name}: written by a newer oitbench (store layout {store_version}, CSV "
                             f"schema {csv_schema}; this one knows up to {sqlschema.STORE_VERSION} and "
                             f"{sqlschema.CSV_SCHEMA}): update this checkout before reading or writing it")
        return store_version == sqlschema.STORE_VERSION and csv_schema == sqlschema.CSV_SCHEMA

    def _setup(self):
        """Creates the tables, or checks a store's versions and adds the columns a newer schema has. A store
        of this very version is only checked (no DDL, no lock)."""
        meta = self._meta()
        if meta is not None and self._check_versions(meta):
            return
        with self._write_transaction(setup=True) as cur:
            cur.execute("CREATE TABLE IF NOT EXISTS store_meta (key TEXT PRIMARY KEY, value TEXT NOT NULL)")
            cur.execute("SELECT key, value FROM store_meta")
            self._check_versions(dict(cur.fetchall()))
            for stmt in sqlschema.create_statements(self.dialect):
                cur.execute(stmt)
            for table in ("runs", "rows", "samples"):
                have = set(self._existing_columns(cur, table))
                for name, sql_type in sqlschema.table_columns(table, self.dialect):
                    if name not in have:
                        cur.execute(f"ALTER TABLE {table} ADD COLUMN {q(name)} {sql_type.replace(' PRIMARY KEY', '')}")
            for k, v in (("store_version", sqlschema.STORE_VERSION), ("csv_schema", sqlschema.CSV_SCHEMA)):
                cur.execute(self._sql("INSERT INTO store_meta (key, value) VALUES (?, ?) ON CONFLICT (key) DO "
                                      "UPDATE SET value = excluded.value"), (k, str(v)))

    # --- ingest ----------------------------------------------------------------------------------------
    def ingest(self, path):
        """Stores one CSV (summary or --raw) in one transaction. Returns (rows in the file, rows added): a
        file stored before adds 0. Raises StoreError naming the file (and line) for a file it refuses."""
        try:
            f = csvfile.read(path)
        except csvfile.CsvRefused as e:
            raise StoreError(str(e)) from e
        if self._file_known(f.sha256):
            return len(f.rows), 0
        prepared = self._prepare(f)
        for attempt in range(8):
            try:
                with self._write_transaction() as cur:
                    added = self._insert(cur, f, *prepared)
                return len(f.rows), added
            except Exception as e:  # noqa: BLE001: only the backends' transient conflicts are retried
                if not self._retryable(e) or attempt == 7:
                    raise
                time.sleep(0.05 * (attempt + 1))
        return len(f.rows), 0

    def _file_known(self, sha):
        return bool(self.query("SELECT 1 AS k FROM files WHERE sha256 = ?", (sha,)))

    def _prepare(self, f):
        table = "rows" if f.kind == "summary" else "samples"
        cols = self.columns(table)
        folder = os.path.dirname(os.path.abspath(f.path))
        hashes = csvfile.row_hashes(f.rows)
        records, runs, tags = [], {}, {}
        for row, line, h in zip(f.rows, f.lines, hashes):
            run_id = row.get("run_id") or csvfile.legacy_run_id(row, folder)
            values, extra = csvfile.split_row(row, f.types)
            values.update(row_hash=h, run_id=run_id, file_sha=f.sha256, line=line, case_key=csvfile.case_key(row),
                          extra=extra)
            records.append(tuple(values.get(c) for c in cols))
            if run_id not in runs:
                run_values, _ = csvfile.split_row({k: v for k, v in row.items() if k in sqlschema.RUN_COLUMNS},
                                                  sqlschema.SUMMARY_TYPES)
                run_values.update(run_id=run_id, first_utc=row.get("timestamp_utc") or None,
                                  source="csv" if row.get("run_id") else "derived")
                runs[run_id] = tuple(run_values.get(c) for c in self.columns("runs"))
                tags[run_id] = _decode_tags(row.get("tags", ""))
            elif row.get("timestamp_utc"):
                i = self.columns("runs").index("first_utc")
                if runs[run_id][i] is None or row["timestamp_utc"] < runs[run_id][i]:
                    runs[run_id] = runs[run_id][:i] + (row["timestamp_utc"],) + runs[run_id][i + 1:]
        records.sort(key=lambda r: r[0])  # one lock order for concurrent writers
        return table, cols, records, sorted(runs.values()), tags

    def _insert(self, cur, f, table, cols, records, runs, tags):
        cur.execute(self._sql("SELECT 1 FROM files WHERE sha256 = ?"), (f.sha256,))
        if cur.fetchone():
            return 0
        run_cols = self.columns("runs")
        self._insert_many(cur, "runs", run_cols, runs, "run_id")
        tag_rows = sorted((rid, k, v) for rid, kv in tags.items() for k, v in kv.items())
        self._insert_many(cur, "run_tags", ["run_id", "key", "value"], tag_rows, "run_id, key")
        added = self._insert_many(cur, table, cols, records, "row_hash")
        cur.execute(self._sql("INSERT INTO files (sha256, path, kind, rows_in_file, rows_added, ingested_utc) "
                              "VALUES (?, ?, ?, ?, ?, ?) ON CONFLICT (sha256) DO NOTHING"),
                    (f.sha256, f.path, f.kind, len(f.rows), added, _now()))
        return added

    def read_back(self, path):
        """The stored rows of a CSV file, in its order, as text dicts over the file's header (for checking
        that a file comes back value for value)."""
        f = csvfile.read(path)
        table = "rows" if f.kind == "summary" else "samples"
        hashes = csvfile.row_hashes(f.rows)
        by_hash = {}
        for i in range(0, len(hashes), 500):
            chunk = hashes[i:i + 500]
            marks = ",".join("?" * len(chunk))
            for r in self.query(f"SELECT * FROM {table} WHERE row_hash IN ({marks})", chunk):
                by_hash[r["row_hash"]] = r
        out = []
        for h in hashes:
            r = by_hash.get(h)
            if r is None:
                out.append(None)
                continue
            extra = json.loads(r["extra"]) if r["extra"] else {}
            row = {}
            for name in f.header:
                if name in extra:
                    row[name] = extra[name]
                elif name == "run_id":
                    row[name] = r["run_id"] if "run_id" in f.header else ""
                else:
                    v = r.get(name)
                    row[name] = "" if v is None else str(v)
            out.append(row)
        return f, out


def _decode_tags(column):
    tags = {}
    for item in column.split(";") if column else []:
        if "=" in item:
            k, v = item.split("=", 1)
            tags[k] = re.sub(r"%([0-9A-Fa-f]{2})", lambda m: chr(int(m.group(1), 16)), v)
    return tags


class _Transaction:
    def __init__(self, store, begin):
        self.store, self.begin = store, begin

    def __enter__(self):
        self.cur = self.store.conn.cursor()
        self.begin(self.cur)
        return self.cur

    def __exit__(self, exc_type, *exc):
        if exc_type is None:
            self.store.conn.commit()
        else:
            self.store.conn.rollback()
        return False


class SqliteStore(Store):
    dialect = "sqlite"
    ph = "?"

    def __init__(self, path):
        super().__init__()
        self.name = path
        folder = os.path.dirname(os.path.abspath(path))
        try:
            os.makedirs(folder, exist_ok=True)
            self.conn = sqlite3.connect(path, timeout=120, isolation_level=None)
            self.conn.execute("PRAGMA busy_timeout = 120000")
            if self.conn.execute("PRAGMA journal_mode").fetchone()[0] != "wal":
                self.conn.execute("PRAGMA journal_mode = WAL")
            self._setup()
        except sqlite3.DatabaseError as e:
            raise StoreError(f"{path}: not a usable SQLite store ({e})") from e
        except OSError as e:
            raise StoreError(f"{path}: cannot create the store ({e.strerror})") from e

    def _write_transaction(self, setup=False):
        return _Transaction(self, lambda cur: cur.execute("BEGIN IMMEDIATE"))

    def _has_table(self, name):
        return bool(self.query("SELECT 1 AS k FROM sqlite_master WHERE type = 'table' AND name = ?", (name,)))

    def _existing_columns(self, cur, table):
        return [r[1] for r in cur.execute(f"PRAGMA table_info({table})").fetchall()]

    def _insert_many(self, cur, table, cols, records, key):
        if not records:
            return 0
        names = ", ".join(q(c) for c in cols)
        before = self.conn.total_changes
        cur.executemany(f"INSERT INTO {table} ({names}) VALUES ({', '.join('?' * len(cols))}) "
                        f"ON CONFLICT ({key}) DO NOTHING", records)
        return self.conn.total_changes - before

    def _retryable(self, e):
        return isinstance(e, sqlite3.OperationalError) and "locked" in str(e)

    def _end_read(self):
        pass


class PostgresStore(Store):
    dialect = "postgresql"
    ph = "%s"

    def __init__(self, url, connect_timeout=5):
        super().__init__()
        self.name = redact_url(url)
        try:
            import psycopg
        except ImportError as e:
            raise StoreError("PostgreSQL stores need psycopg 3 (Debian: apt-get install python3-psycopg)") from e
        self._psycopg = psycopg
        try:
            self.conn = psycopg.connect(url, connect_timeout=connect_timeout, autocommit=False)
        except psycopg.Error as e:
            msg = str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__
            raise StoreError(f"{self.name}: cannot connect ({redact_url(msg)})") from None
        try:
            self._setup()
        except psycopg.Error as e:
            self.close()
            raise StoreError(f"{self.name}: {str(e).strip()}") from None

    def _write_transaction(self, setup=False):
        # Creating and migrating tables holds the store's advisory lock exclusively, ingesting shares it: DDL
        # never interleaves with writers (its table locks would deadlock against theirs).
        lock = "pg_advisory_xact_lock" if setup else "pg_advisory_xact_lock_shared"
        return _Transaction(self, lambda cur: cur.execute(f"SELECT {lock}(3131)"))

    def _has_table(self, name):
        return bool(self.query("SELECT 1 AS k FROM information_schema.tables WHERE table_name = ? AND "
                               "table_schema = current_schema()", (name,)))

    def _existing_columns(self, cur, table):
        cur.execute("SELECT column_name FROM information_schema.columns WHERE table_name = %s AND "
                    "table_schema = current_schema()", (table,))
        return [r[0] for r in cur.fetchall()]

    def _insert_many(self, cur, table, cols, records, key):
        if not records:
            return 0
        names = ", ".join(q(c) for c in cols)
        stage = f"stage_{table}"
        cur.execute(f"CREATE TEMP TABLE IF NOT EXISTS {stage} (LIKE {table} INCLUDING DEFAULTS) ON COMMIT DELETE ROWS")
        with cur.copy(f"COPY {stage} ({names}) FROM STDIN") as copy:
            for r in records:
                copy.write_row(r)
        first = q(key.split(",")[0].strip())
        cur.execute(f"INSERT INTO {table} ({names}) SELECT {names} FROM {stage} ORDER BY {first} "
                    f"ON CONFLICT ({key}) DO NOTHING")
        return cur.rowcount

    def _retryable(self, e):
        errors = self._psycopg.errors
        return isinstance(e, (errors.DeadlockDetected, errors.SerializationFailure))

    def _end_read(self):
        self.conn.rollback()  # no transaction left open between reads
