#!/usr/bin/python3
"""One static HTML page from oitbench runs: what ran where, what failed and why, every figure, the
papers' tables beside ours, and the rendered images; or, with --compare, one page of per-case ratios
between two results folders (two drivers, machines or commits).

    scripts/report.py RUN.csv [RUN2.csv ...] -o DIR
    scripts/report.py RESULTS_DIR -o DIR [--paper PAPER_DIR] [--images IMAGES_DIR]
    scripts/report.py --compare A_DIR B_DIR -o DIR [--labels A,B] [--min-effect 1.5]

A folder argument stands for every summary CSV below it, found by its header (oitres.is_summary_header);
--raw files are left out (a NAME_raw.csv beside NAME.csv makes NAME's parameter columns exact), and so are
the output folder, the images folder and any folder holding a page this script wrote. DIR gets
index.html, figures/ (plot.py's figures, PNG and SVG) and images/ (copies of the rendered PNGs); every
link is relative, so DIR can be moved or committed. A results root that holds several driver folders
(RESULTS/DRIVER/presets/) links to the comparison pages below it, or says how to write one.

--compare pairs A/presets/NAME.csv with B/presets/NAME.csv (NAME.csv in the folder itself when it has no
presets/; NAME_raw.csv beside each when there is one) and runs compare.py's statistics on each pair:
the ratio B/A per case with its 95% interval (bootstrap over the repetitions with raw files on both
sides, else from the MADs) and its verdict, grouped per preset and experiment, with compare.py's
figures. The header names each side's driver, GL strings, backend, LP_NUM_THREADS, environment, commit,
machine and timestamps; cases on one side only, or not ok on one side, are listed with status and reason.

The page depends only on its inputs: the same results give the same files, byte for byte.
Exit codes: 0 written; 1 written, but a figure could not be drawn (the page says which); 2 no or
unreadable input (the message names the file or folder), or an output folder that holds something else.
"""
import argparse
import os
import signal
import sys

from oitbench import cli
from oitbench import compare
from oitbench import results as oitres
from oitbench.report import build, build_compare


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("inputs", nargs="*", metavar="CSV_OR_DIR",
                    help="summary CSVs (`oitbench run --out`) or folders to search for them")
    ap.add_argument("-o", "--out-dir", required=True, help="the report's folder (index.html, figures/, images/)")
    ap.add_argument("--paper", help="folder of the papers' tidy CSVs (default: tables.py's, "
                                    "the repository's results/published)")
    ap.add_argument("--images", help="folder of `oitbench render` PNGs (default: images/ in the results folder, "
                                     "or beside the first CSV, when there is one)")
    ap.add_argument("--title", help="the page's title (default: oitbench report: FOLDER)")
    ap.add_argument("--ab", nargs="+", action="extend", metavar="DIR",
                    help="folders of A/B comparisons (scripts/ab.py out folders, or scripts/ab_bench.sh's, e.g. "
                         "results/ab-llvmpipe): a section with each one's table or trial summary and a figure")
    cmp = ap.add_argument_group("comparison page", "scripts/report.py --compare A B -o DIR: the presets both "
                                "results folders ran (A/presets/NAME.csv beside B/presets/NAME.csv, with "
                                "NAME_raw.csv when there is one), case by case, as ratios B/A with 95% intervals "
                                "and compare.py's verdicts and figures")
    cmp.add_argument("--compare", nargs=2, metavar=("A", "B"), help="the two results folders; A is the baseline")
    cmp.add_argument("--labels", metavar="A,B", help="the two sides' names (default: their drivers, else their "
                                                     "folder names)")
    compare.add_statistics_options(cmp)
    args = ap.parse_args(argv)
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)
    if args.compare:
        if args.inputs:
            ap.error("give CSV_OR_DIR inputs or --compare A B, not both")
        if args.paper or args.images or args.ab:
            ap.error("--paper, --images and --ab are for the report of runs, not --compare")
        if args.labels and len(args.labels.split(",")) != 2:
            ap.error("--labels takes two names: A,B")
    elif not args.inputs:
        ap.error("the following arguments are required: CSV_OR_DIR (or --compare A B)")
    elif args.labels:
        ap.error("--labels is for --compare")
    if os.path.exists(args.out_dir) and not os.path.isdir(args.out_dir):
        print(f"report.py: {args.out_dir}: is a file, not a folder; give -o a new or empty folder "
              "(report.py never writes over a file)", file=sys.stderr)
        return 2
    try:
        return build_compare(args) if args.compare else build(args)
    except oitres.ResultsError as e:
        print(f"report.py: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(cli.run(main))
