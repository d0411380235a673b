#!/usr/bin/python3
"""FINDINGS.md for a results folder: what the reference runs found, every number computed from its CSVs.

    scripts/findings.py RESULTS_DIR [-o FILE] [--paper DIR]

RESULTS_DIR holds presets/NAME.csv, one `oitbench run --preset NAME` each (NAME_raw.csv beside it), as
scripts/reference_runs.sh writes them into results/llvmpipe. The output (Markdown, stdout or FILE) is
tables and sentences whose every number is read or computed from those CSVs, and for the papers' numbers
from results/published (tables.py's --paper default), so new runs give new findings and nobody types a
measurement. Words that compare ("faster", "slower", "about even") come from the numbers too (word()).
Fixed text says why, never how much. The same CSVs give the same bytes: nothing here reads the clock,
the machine or the order of files on disk.

Columns are read by name, and by either name where the schema renamed one (max_frags_used, schema 2,
was max_frags in schema 1): see field(). A preset whose CSV is missing gets a line saying so.
Exit codes: 0 written; 2 no presets/ folder, no summary CSV in it, or an unreadable CSV.
"""
import argparse
import os
import signal
import sys

from oitbench import cli
from oitbench import papers
from oitbench import report
from oitbench import results as oitres
from oitbench.findings import render


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("results", help="a results folder with presets/NAME.csv (e.g. results/llvmpipe)")
    ap.add_argument("-o", "--out", help="write here (default: stdout)")
    ap.add_argument("--paper", default=papers.default_paper_dir(),
                    help="folder of the papers' tidy CSVs (default: the repository's results/published)")
    args = ap.parse_args(argv)
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)
    shown = report.shown_path(args.results).replace(os.sep, "/")
    try:
        text = render(args.results, args.paper, shown)
    except oitres.ResultsError as e:
        print(f"findings.py: {e}", file=sys.stderr)
        return 2
    if args.out:
        with open(args.out, "w", encoding="utf-8", newline="\n") as out:
            out.write(text)
    else:
        sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(cli.run(main))
