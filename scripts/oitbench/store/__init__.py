"""The result store (issue 31): oitbench's CSV files in one SQL database, SQLite by default (a local file)
or PostgreSQL by URL (a shared store many machines write into), behind one interface.

    from oitbench.store import open_store
    with open_store("results/local/oitbench.sqlite") as s:        # or "postgresql://user@host/db"
        s.ingest("run.csv")                                        # idempotent, one transaction per file

The tables are generated from the one result schema (scripts/schema.json, sqlschema.py): runs, run_tags,
files, rows (the summary rows, typed columns) and samples (the --raw rows)."""
from oitbench.store.backend import DEFAULT_SQLITE, StoreError, open_store, redact_url  # noqa: F401
