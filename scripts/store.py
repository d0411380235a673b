#!/usr/bin/python3
"""oitbench's result store: CSV files into one SQL database, and the questions asked of many runs.

    scripts/store.py [--store URL] ingest FILE_OR_FOLDER...   # summary and --raw CSVs; idempotent
    scripts/store.py [--store URL] runs [--tag K=V] [--driver D] [--renderer R] [--commit SHA] [--since DATE]
    scripts/store.py history [RUN FILTER] [--experiment E] [--case PATTERN] [--order date|commit|driver]
                     [--repo DIR] [-o F.png]    # commit: the git commit graph's order (DIR: this repository)
    scripts/store.py compare --a-tag K=V ... --b-tag K=V ... (or --a-driver, --b-commit, ...) [--experiment E]
    scripts/store.py fleet -o fleet.html
    scripts/store.py bencher [RUN FILTER] -o bmf.json       # the latest matching run, Bencher's metric format

The store is a SQLite file by default (results/local/oitbench.sqlite, or $OITBENCH_STORE) or a shared
PostgreSQL database by URL: --store postgresql://USER[:PASSWORD]@HOST[:PORT]/DB (docs/store.md).
Exit codes: 0 done; 1 nothing matched; 2 bad input (a refused file, an unreachable store).
"""
import argparse
import json
import os
import sys

from oitbench import cli
from oitbench.store import StoreError, bencher, fleet, open_store, queries
from oitbench.store import compare as store_compare
from oitbench.store import history as store_history


def csv_files(paths):
    """The CSV files named, folders searched recursively (sorted), summary files before their raw files."""
    out = []
    for p in paths:
        if os.path.isdir(p):
            for root, dirs, files in os.walk(p):
                dirs.sort()
                out += [os.path.join(root, f) for f in sorted(files) if f.endswith(".csv")]
        else:
            out.append(p)
    return out


def cmd_ingest(store, args):
    total_rows = total_added = refused = 0
    for path in csv_files(args.paths):
        try:
            rows, added = store.ingest(path)
        except StoreError as e:
            if not args.skip_foreign or "not an oitbench" not in str(e):
                print(f"store.py: {e}", file=sys.stderr)
                refused += 1
            continue
        total_rows += rows
        total_added += added
        if args.verbose:
            print(f"{path}: {rows} rows, {added} new")
    print(f"{total_rows} rows read, {total_added} new -> {store.name}")
    return 2 if refused else 0


FILTERS = ("tag", "driver", "renderer", "commit", "run", "preset", "host", "since", "until")


def add_filter_options(ap, prefix=""):
    p = f"--{prefix}-" if prefix else "--"
    d = prefix.replace("-", "_") + "_" if prefix else ""
    ap.add_argument(f"{p}tag", dest=f"{d}tag", action="append", default=[], metavar="KEY=VALUE",
                    help="runs with this tag (repeatable: all of them)")
    ap.add_argument(f"{p}driver", dest=f"{d}driver", help="the driver column (llvmpipe, zink-lavapipe, ...)")
    ap.add_argument(f"{p}renderer", dest=f"{d}renderer", help="a part of GL_RENDERER")
    ap.add_argument(f"{p}commit", dest=f"{d}commit", help="git_sha prefix")
    ap.add_argument(f"{p}run", dest=f"{d}run", help="run id prefix")
    ap.add_argument(f"{p}preset", dest=f"{d}preset")
    ap.add_argument(f"{p}host", dest=f"{d}host", help="hostname")
    ap.add_argument(f"{p}since", dest=f"{d}since", help="runs from this UTC date/time on (2026-12-01T10:00)")
    ap.add_argument(f"{p}until", dest=f"{d}until", help="runs before this UTC date/time")


def run_filter(args, prefix=""):
    d = prefix + "_" if prefix else ""
    v = {f: getattr(args, d + f) for f in FILTERS}
    for t in v["tag"]:
        if "=" not in t:
            raise StoreError(f"--{prefix + '-' if prefix else ''}tag {t}: give KEY=VALUE")
    return queries.RunFilter(v["tag"], v["driver"], v["renderer"], v["commit"], v["run"], v["preset"], v["host"],
                             v["since"], v["until"])


def cmd_history(store, args):
    if args.repo is not None and not os.path.isdir(args.repo):
        raise StoreError(f"--repo {args.repo}: no such folder")
    notes = []
    series = store_history.history(store, run_filter(args), args.experiment, args.case, args.order, args.alpha,
                                   repo=args.repo, notes=notes, statistic=args.statistic)
    for n in notes:
        print(f"note: {n}", file=sys.stderr)
    if not series:
        print("store.py history: no ok row of any run matches the filter (see: store.py runs)", file=sys.stderr)
        return 1
    for w in store_history.machine_warnings(series):
        print(f"warning: {w}", file=sys.stderr)
    for s in series:
        steps = {i: (ratio, p) for i, ratio, p in s.steps}
        print(f"{s.case_key}: {len(s.rows)} runs, "
              f"{len(s.steps)} change point(s)" + "".join(f"; at run {i + 1}: x{ratio:.3f} (p={p:.3g})"
                                                         for i, ratio, p in s.steps))
        if args.verbose:
            for i, r in enumerate(s.rows):
                lo = "" if r["ci_lo_ms"] is None else f"{r['ci_lo_ms']:.4g}"
                hi = "" if r["ci_hi_ms"] is None else f"{r['ci_hi_ms']:.4g}"
                mark = "  <- step" if i in steps else ""
                print(f"  {i + 1:3} {r['run_id'][:8]} {r['first_utc'] or '':20} {r['git_sha'] or '':12} "
                      f"{r['driver'] or '':14} {r['median_ms']:.4g} [{lo}, {hi}]{mark}")
    if args.output:
        store_history.draw(series, args.output, args.order)
        print(f"figure -> {args.output}")
    return 0


def cmd_compare(store, args):
    comparisons, warnings = store_compare.compare(store, run_filter(args, "a"), run_filter(args, "b"),
                                                  args.experiment, args.case, args.min_effect)
    for w in warnings:
        print(f"warning: {w}", file=sys.stderr)
    if not comparisons:
        print("store.py compare: the two sets share no ok case (see: store.py runs)", file=sys.stderr)
        return 1
    counts = {}
    for c in comparisons:
        counts[c.kind] = counts.get(c.kind, 0) + 1
        print(f"{c.key}: {c.ratio:.3f}x [{c.ci[0]:.3f}, {c.ci[1]:.3f}] {c.verdict}")
    print(f"{len(comparisons)} cases: " + ", ".join(f"{counts.get(k, 0)} {k}" for k in
                                                   (store_compare.NO_DIFFERENCE, store_compare.IN_BAND,
                                                    store_compare.OVERLAP, store_compare.CHANGED)))
    return 0


def cmd_fleet(store, args):
    text = fleet.page(store, args.published)
    with open(args.output, "w", encoding="utf-8") as f:
        f.write(text)
    print(f"fleet page -> {args.output}")
    return 0


def cmd_bencher(store, args):
    run_id = bencher.latest_run(store, run_filter(args))
    if run_id is None:
        print("store.py bencher: no run matches", file=sys.stderr)
        return 1
    bmf, meta = bencher.export_run(store, run_id)
    text = json.dumps(bmf, indent=1, sort_keys=True) + "\n"
    if args.output == "-":
        sys.stdout.write(text)
    else:
        with open(args.output, "w", encoding="utf-8") as f:
            f.write(text)
        print(f"{len(bmf)} benchmarks of run {run_id} -> {args.output}\n"
              f"bencher run --adapter json --file {args.output} --testbed {meta['testbed']} "
              f"--branch {meta['branch']} --hash {meta['hash']}")
    return 0


def cmd_runs(store, args):
    runs = queries.runs(store, run_filter(args))
    if args.json:
        print(json.dumps(runs, indent=1, default=str))
    else:
        for r in runs:
            tags = ";".join(f"{k}={v}" for k, v in sorted(r["tags"].items()))
            print(f"{r['run_id'][:8]}  {r['first_utc'] or '?':20}  {r['driver'] or '?':14} {r['git_sha'] or '?':12} "
                  f"{r['preset'] or '-':18} {r['ok_rows']}/{r['rows_stored']} ok  {r['hostname'] or ''} {tags}")
    if not runs:
        print("store.py runs: no run matches", file=sys.stderr)
        return 1
    return 0


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--store", help="SQLite file or postgresql:// URL (default: $OITBENCH_STORE, else "
                    "results/local/oitbench.sqlite)")
    sub = ap.add_subparsers(dest="command", required=True)
    p = sub.add_parser("ingest", help="store CSV files (summary and --raw), idempotently")
    p.add_argument("paths", nargs="+")
    p.add_argument("--skip-foreign", action="store_true",
                   help="pass over CSVs that are not oitbench run output (papers' tables, histograms) silently")
    p.add_argument("-v", "--verbose", action="store_true")
    p.set_defaults(func=cmd_ingest)
    p = sub.add_parser("runs", help="list runs, filtered")
    add_filter_options(p)
    p.add_argument("--json", action="store_true")
    p.set_defaults(func=cmd_runs)
    p = sub.add_parser("history", help="cases across runs, with change points and a figure")
    add_filter_options(p)
    p.add_argument("--experiment")
    p.add_argument("--case", help="case key pattern, SQL LIKE (%% any text): occupancy/unrolled/total/%%size=32")
    p.add_argument("--order", choices=store_history.ORDERS, default="date")
    p.add_argument("--alpha", type=cli.number(float, low=0.0, high=1.0, low_open=True, high_open=True), default=0.01, help="the change points' significance (default 0.01)")
    p.add_argument("--statistic", choices=store_history.STATISTICS, default="median",
                   help="each run's value the change points are found in: its samples' median (default) or mean")
    p.add_argument("--repo", default=store_history.default_repo(),
                   help="the git repository whose commit graph --order commit follows (default: the one these "
                   "scripts are in; where it does not know a run's commit, history orders by date and says so)")
    p.add_argument("-o", "--output", help="figure (PNG or SVG)")
    p.add_argument("-v", "--verbose", action="store_true", help="every run's median and interval")
    p.set_defaults(func=cmd_history)
    p = sub.add_parser("compare", help="two sets of runs, case by case (B / A)")
    add_filter_options(p, "a")
    add_filter_options(p, "b")
    p.add_argument("--experiment")
    p.add_argument("--case", help="case key pattern, SQL LIKE")
    p.add_argument("--min-effect", type=cli.number(float, low=1.0), default=store_compare.MIN_EFFECT,
                   help="the smallest ratio B / A called a change (>= 1; default %(default)s)")
    p.set_defaults(func=cmd_compare)
    p = sub.add_parser("fleet", help="the fleet page (HTML)")
    p.add_argument("-o", "--output", default="fleet.html")
    p.add_argument("--published", default=os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                                                      "results", "published"))
    p.set_defaults(func=cmd_fleet)
    p = sub.add_parser("bencher", help="the latest matching run in Bencher's metric format")
    add_filter_options(p)
    p.add_argument("-o", "--output", default="-")
    p.set_defaults(func=cmd_bencher)
    args = ap.parse_args(argv)
    try:
        with open_store(args.store) as store:
            return args.func(store, args)
    except StoreError as e:
        print(f"store.py: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        return 130


if __name__ == "__main__":
    sys.exit(cli.run(main))
