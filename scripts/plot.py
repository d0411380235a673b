#!/usr/bin/python3
"""Figures from oitbench runs: one PNG and one SVG per experiment and input file.

    scripts/plot.py RUN.csv [RUN2.csv ...] [-o DIR] [--fastest]

Only valid rows (status ok, valid 1) are drawn; the others are listed on stdout and in a note on the
figure. Every valid row is drawn in some panel or named in that note with the reason (stdout counts both
per figure), panels wrap into rows of the report page's width, and bars and points are keyed on every
parameter that tells cases apart. --fastest adds the fastest exact technique per view and driver.
Each experiment gets its own plot function from PLOTTERS; an experiment without one gets
generic_plot(): median ms against its main numeric parameter, one line per variant, MAD as error bars.
Adding a figure for a new experiment: write `def plot_<name>(data)` returning a Figure and decorate it
with @plotter("<name>"); curves() and bars() do most of the work.
"""
import argparse
import os
import signal
import sys

from oitbench import cli
from oitbench import results as oitres
from oitbench.figures import plt
from oitbench.figures import (
    FASTEST_HEADER, draw, fastest_figure, fastest_lines, fastest_table, figure_name, save, unique_labels)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("csv", nargs="+", help="summary CSVs written by `oitbench run --out`")
    ap.add_argument("-o", "--out-dir", help="where the figures go (default: figures/ beside the first CSV)")
    ap.add_argument("--raw", nargs="*", default=[], help="matching --raw files (make parameter columns exact)")
    ap.add_argument("--format", default="png,svg",
                    help="comma-separated figure formats (default png,svg); none: draw and count, write nothing")
    ap.add_argument("--fastest", action="store_true",
                    help="also the fastest exact technique per view and driver over all the given runs "
                         "(fastest.FORMAT, and its table on stdout)")
    args = ap.parse_args(argv)
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)

    try:
        raws = args.raw + [None] * (len(args.csv) - len(args.raw))
        runs = [oitres.Run.load(p, r) for p, r in zip(args.csv, raws)]
    except oitres.ResultsError as e:
        print(f"plot.py: {e}", file=sys.stderr)
        return 2
    unique_labels(runs)
    out_dir = args.out_dir or os.path.join(os.path.dirname(os.path.abspath(args.csv[0])), "figures")
    os.makedirs(out_dir, exist_ok=True)
    count = {}
    for run in runs:
        for exp in run.experiments():
            count[exp] = count.get(exp, 0) + 1
    # "none": every figure drawn and counted, no file written (the reference CSVs' test).
    formats = [f.strip() for f in args.format.split(",") if f.strip() and f.strip() != "none"]
    known = plt.gcf().canvas.get_supported_filetypes()
    unknown = [f for f in formats if f not in known]
    if unknown:
        ap.error(f"--format {args.format}: unknown format {', '.join(unknown)} (known: {', '.join(sorted(known))}, "
                 "none)")
    for run in runs:
        for exp in run.experiments():
            data, fig, lines = draw(run, exp)
            for line in lines + data.not_drawn_lines:
                print(f"{run.label}: {exp}: not plotted: {line}")
            name = figure_name(exp, run, count[exp] > 1)
            save(fig, os.path.join(out_dir, name), formats)
            drawn, noted = data.counts()
            print(f"{run.label}: {exp}: {len(data.valid)} valid rows, {len(lines)} not plotted; "
                  f"{drawn} drawn, {noted} named in the note -> {os.path.join(out_dir, name)}.{{{args.format}}}")
    if args.fastest:
        entries = fastest_table(runs)
        if not entries:
            print("plot.py: --fastest: no view of the given runs has two or more exact oit techniques", file=sys.stderr)
            return 2
        save(fastest_figure(entries), os.path.join(out_dir, "fastest"), formats)
        print(" | ".join(FASTEST_HEADER))
        for line in fastest_lines(entries):
            print(" | ".join(line))
        print(f"fastest: {len(entries)} views -> {os.path.join(out_dir, 'fastest')}.{{{args.format}}}")
    return 0


if __name__ == "__main__":
    sys.exit(cli.run(main))
