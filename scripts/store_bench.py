#!/usr/bin/python3
"""The store at scale (issue 31 item 7; a benchmark, not a test): N synthetic runs of the knowles2014 grid's
shape (the committed reference run's rows, each run with its own run id, date and jittered medians) into a
store, timing ingest (rows/s), a history query over every run of one case, and the fleet page.

    scripts/store_bench.py --runs 1000 [--store URL]    # default: a new SQLite file in a temp folder
"""
import argparse
import csv
import math
import os
import random
import sys
import tempfile
import time
import uuid

from oitbench import cli, results
from oitbench.store import StoreError, fleet, open_store, queries
from oitbench.store import history as store_history

GRID = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "results", "llvmpipe", "presets",
                    "knowles2014.csv")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", type=cli.positive(int), default=1000, help="synthetic runs (default 1000)")
    ap.add_argument("--store", help="SQLite file or postgresql:// URL (default: a temp SQLite file)")
    ap.add_argument("--grid", default=GRID)
    args = ap.parse_args(argv)
    header, grid = results.read_csv(args.grid)  # refuses a bad file with FILE:LINE (exit 2 through cli.run)
    results.check_summary_header(args.grid, header)  # FILE:1 unless a summary file with every required column
    if not [r for r in grid if r.get("status") == "ok" and r.get("pass") == "total"]:
        raise results.ResultsError(f"{args.grid}:2: no ok row to copy (the grid needs at least one)")
    tmp = tempfile.mkdtemp(prefix="oitbench-store-bench-")
    url = args.store or os.path.join(tmp, "bench.sqlite")
    rng = random.Random(7)
    rows_in = 0
    t_ingest = 0.0
    try:
        with open_store(url) as store:
            for i in range(args.runs):
                path = os.path.join(tmp, f"run{i}.csv")
                run_id = str(uuid.UUID(int=rng.getrandbits(128), version=4))
                factor = math.exp(rng.gauss(0, 0.03))
                with open(path, "w", newline="", encoding="utf-8") as f:
                    w = csv.DictWriter(f, header, lineterminator="\n")
                    w.writeheader()
                    for r in grid:
                        r = dict(r, schema="5", run_id=run_id, timestamp_utc=f"2027-{1 + i // 28 % 12:02d}-"
                                 f"{1 + i % 28:02d}T{i % 24:02d}:00:00Z", git_sha=f"g{i:05d}")
                        if r.get("median_ms"):
                            r["median_ms"] = f"{float(r['median_ms']) * factor:.6g}"
                        w.writerow({k: r.get(k, "") for k in header})
                t = time.monotonic()
                rows_in += store.ingest(path)[1]
                t_ingest += time.monotonic() - t
                os.remove(path)
            t = time.monotonic()
            case = store.query("SELECT case_key FROM rows WHERE status = 'ok' AND pass = 'total' LIMIT 1")[0]["case_key"]
            series = store_history.history(store, queries.RunFilter(), case_like=case)
            t_history = time.monotonic() - t
            t = time.monotonic()
            fleet.page(store, os.path.join(os.path.dirname(GRID), "..", "..", "published"))
            t_fleet = time.monotonic() - t
    except StoreError as e:
        print(f"store_bench.py: {e}", file=sys.stderr)
        return 2
    print(f"{store.name}: {args.runs} runs, {rows_in} rows ingested in {t_ingest:.1f} s "
          f"({rows_in / t_ingest:.0f} rows/s); history of one case over {len(series[0].rows)} runs "
          f"{t_history:.2f} s; fleet page {t_fleet:.2f} s")
    return 0


if __name__ == "__main__":
    sys.exit(cli.run(main))
