"""The store's SQL schema, generated from scripts/schema.json: every summary column typed as the C++ schema
types it (text, integer, number, flag), the raw columns likewise, plus the store's own columns (a row's
content hash, its run, file and line, its case key and `extra`: values of columns this schema does not
have, or that do not parse as their type, kept as text so nothing of a file is lost)."""
import json
import os

SCHEMA_PATH = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                           "schema.json")
# The layout of the store's own tables; a store with a higher one was written by a newer oitbench.
STORE_VERSION = 1


def load_schema(path=SCHEMA_PATH):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


SCHEMA = load_schema()
CSV_SCHEMA = SCHEMA["schema"]
SUMMARY_TYPES = {c["name"]: c["type"] for c in SCHEMA["summary_columns"]}
RAW_TYPES = {c["name"]: c["type"] for c in SCHEMA["raw_columns"]}
PARAMETERS = [c["name"] for c in SCHEMA["summary_columns"] if c["role"] == "parameter"]
RUN_COLUMNS = [c["name"] for c in SCHEMA["summary_columns"] if c.get("group") == "run"]

SQL_TYPES = {
    "sqlite": {"text": "TEXT", "integer": "INTEGER", "number": "REAL", "flag": "INTEGER"},
    "postgresql": {"text": "TEXT", "integer": "BIGINT", "number": "DOUBLE PRECISION", "flag": "SMALLINT"},
}
# The store's own columns of rows and samples, before the schema's.
OWN_COLUMNS = [("row_hash", "TEXT PRIMARY KEY"), ("run_id", "TEXT NOT NULL"), ("file_sha", "TEXT NOT NULL"),
               ("line", "INTEGER NOT NULL"), ("case_key", "TEXT NOT NULL"), ("extra", "TEXT")]
RUN_TABLE_COLUMNS = ["run_id", "first_utc", "source"] + [c for c in RUN_COLUMNS if c not in ("run_id",)]


def q(name):
    """A quoted identifier: the schema has columns named like SQL words (group, schema, pass)."""
    return '"' + name.replace('"', '""') + '"'


def table_columns(table, dialect):
    """[(name, SQL type)] of a table as this schema defines it."""
    types = SQL_TYPES[dialect]
    if table == "rows":
        return OWN_COLUMNS + [(n, types[t]) for n, t in SUMMARY_TYPES.items() if n != "run_id"]
    if table == "samples":
        return OWN_COLUMNS + [(n, types[t]) for n, t in RAW_TYPES.items() if n != "run_id"]
    if table == "runs":
        return ([("run_id", "TEXT PRIMARY KEY"), ("first_utc", "TEXT"), ("source", "TEXT")] +
                [(n, types[SUMMARY_TYPES[n]]) for n in RUN_COLUMNS if n != "run_id"])
    raise KeyError(table)


def create_statements(dialect):
    """CREATE TABLE/INDEX IF NOT EXISTS for every table of this schema."""
    def create(table):
        cols = ",\n  ".join(f"{q(n)} {t}" for n, t in table_columns(table, dialect))
        return f"CREATE TABLE IF NOT EXISTS {table} (\n  {cols}\n)"
    return [
        "CREATE TABLE IF NOT EXISTS store_meta (key TEXT PRIMARY KEY, value TEXT NOT NULL)",
        "CREATE TABLE IF NOT EXISTS files (sha256 TEXT PRIMARY KEY, path TEXT NOT NULL, kind TEXT NOT NULL, "
        "rows_in_file INTEGER NOT NULL, rows_added INTEGER NOT NULL, ingested_utc TEXT NOT NULL)",
        create("runs"),
        "CREATE TABLE IF NOT EXISTS run_tags (run_id TEXT NOT NULL, key TEXT NOT NULL, value TEXT NOT NULL, "
        "PRIMARY KEY (run_id, key))",
        create("rows"),
        create("samples"),
        "CREATE INDEX IF NOT EXISTS rows_run ON rows (run_id)",
        "CREATE INDEX IF NOT EXISTS rows_case ON rows (case_key, run_id)",
        "CREATE INDEX IF NOT EXISTS rows_experiment ON rows (experiment, status)",
        "CREATE INDEX IF NOT EXISTS samples_run_case ON samples (run_id, case_key)",
        "CREATE INDEX IF NOT EXISTS runs_driver ON runs (driver, gl_renderer)",
        "CREATE INDEX IF NOT EXISTS runs_commit ON runs (git_sha)",
        "CREATE INDEX IF NOT EXISTS runs_time ON runs (first_utc)",
        "CREATE INDEX IF NOT EXISTS run_tags_kv ON run_tags (key, value)",
    ]
