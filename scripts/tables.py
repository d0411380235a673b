#!/usr/bin/python3
"""Our measurements beside the papers' published numbers.

    scripts/tables.py RUN.csv [RUN2.csv ...] [--paper DIR] [--format markdown|csv] [--table NAME]
    scripts/tables.py --error-memory RUN.csv [...] [--format markdown|csv]

DIR holds the tidy paper tables (source,table,gpu,resolution,scene,view,technique,size,metric,unit,value);
by default the repository's results/published (its README.md names each file's source), found from this
script's own path, so any working directory will do. Every table prints the paper's numbers with ours
beside them: absolute milliseconds, and speedups over the table's baseline technique computed the same
way for both, so the shapes compare across hardware. A paper row we have no measurement for shows "—".

How our rows map to the papers' techniques is the explicit table results/published/tables.json (read by
scripts/oitbench/papers.py): a technique matches a row of our experiment when the row's words (variant
and parameter values, split at punctuation, plus name=value forms) contain all the words of one of its
alternatives (`any`) and none of its excluded words (`exclude`).
"""
import argparse
import csv
import signal
import sys

from oitbench import cli
from oitbench import error_memory
from oitbench import results as oitres
from oitbench.papers import (
    CSV_COLUMNS, Ours, TABLES, TECHNIQUES, build_rows, default_paper_dir, load_paper, paired_markdown,
    render_markdown, select_tables)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("csv", nargs="*", help="summary CSVs written by `oitbench run --out`")
    ap.add_argument("--paper", default=default_paper_dir(),
                    help="folder of the papers' tidy CSVs (default: the repository's results/published)")
    ap.add_argument("--format", choices=("markdown", "csv"), default="markdown")
    ap.add_argument("--table", help="one table (e.g. bruell-A.1, knowles2014-2; a unique part of the name works)")
    ap.add_argument("--list", action="store_true", help="list the tables and the technique mapping")
    ap.add_argument("--paired", action="store_true",
                    help="print the runner's paired speedups (rows with a baseline) instead of the paper tables")
    ap.add_argument("--error-memory", action="store_true",
                    help="print each oit case's rmse beside its bytes per pixel, per scene and view, instead of the "
                         "paper tables (no paper numbers needed)")
    args = ap.parse_args(argv)
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)  # `tables.py | head` ends quietly
    if args.list:
        for t in TABLES:
            print(f"{t.name:<15} {t.title}")
        print("\ntechnique mapping (paper technique -> our experiment: alternatives of words, excluded words):")
        for tech, rule in TECHNIQUES.items():
            alts = " | ".join(" ".join(sorted(a)) for a in rule.alternatives)
            print(f"  {tech:<52} -> {rule.experiment}: {alts}" + (
                f"; not {' '.join(sorted(rule.exclude))}" if rule.exclude else ""))
        return 0
    if args.paired:
        try:
            runs = [oitres.Run.load(p) for p in args.csv]
        except oitres.ResultsError as e:
            print(f"tables.py: {e}", file=sys.stderr)
            return 2
        print(paired_markdown([r for run in runs for r in run.rows]))
        return 0
    if args.error_memory:
        try:
            rows = error_memory.rows_of([oitres.Run.load(p) for p in args.csv])
        except oitres.ResultsError as e:
            print(f"tables.py: {e}", file=sys.stderr)
            return 2
        if args.format == "csv":
            w = csv.DictWriter(sys.stdout, fieldnames=error_memory.COLUMNS, lineterminator="\n")
            w.writeheader()
            w.writerows(rows)
        else:
            print(error_memory.markdown(rows), end="")
        return 0
    try:
        tables = select_tables(args.table)
        paper_rows = load_paper(args.paper)
        ours = Ours([oitres.Run.load(p) for p in args.csv])
    except oitres.ResultsError as e:
        print(f"tables.py: {e}", file=sys.stderr)
        return 2
    if args.format == "csv":
        w = csv.DictWriter(sys.stdout, fieldnames=CSV_COLUMNS, lineterminator="\n")
        w.writeheader()
    for t in tables:
        rows = build_rows(t, paper_rows, ours)
        if args.format == "csv":
            for r in rows:
                w.writerow({k: ("" if v is None else (f"{v:.6g}" if isinstance(v, float) else v))
                            for k, v in r.items()})
        else:
            print(render_markdown(t, rows, ours, paper_rows))
    return 0


if __name__ == "__main__":
    sys.exit(cli.run(main))
