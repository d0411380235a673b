#!/usr/bin/python3
"""Compare oitbench runs from different drivers, GPUs or commits, case by case, against the first.

    scripts/compare.py A.csv B.csv [C.csv ...] [--raw A_raw.csv B_raw.csv ...] [--repeat A2.csv ...] [-o DIR]

A case is (experiment, variant, pass, resolution, every parameter); the driver, renderer, git sha and
timestamp columns describe the run and stay out of the key. For every case and every later run this
prints ratio = median(run) / median(first): above 1 is slower. The 95% confidence interval comes from
a bootstrap over the repetitions when the --raw files are given, else from each median's MAD.

Each comparison gets one of four verdicts:
  no measurable difference   the interval includes 1;
  inside the noise band      the interval excludes 1, but the ratio lies inside the case's between-run
                             noise band, max(--min-effect, exp(k * sqrt(cv_a^2 + cv_b^2))), cv = 1.4826 *
                             MAD / median, the spread of single repetitions: a real difference between
                             these two runs, but one that identical code also shows between runs, so one
                             run of each cannot attribute it to the driver or the code;
  overlapping repetitions    beyond the band, but the two runs' repetitions overlap (a stalled repetition
                             among a handful), so not attributable either;
  SLOWER / FASTER            changed: the interval excludes 1, the ratio is beyond the band and the
                             repetitions are apart.
With --repeat FILE... (the first configuration run again) the band's floor comes from the data instead of
--min-effect: the 95th percentile, over an experiment's cases, of how far a repeat lies from the first run.
For differences below that, alternate whole runs with scripts/ab.py, which pairs them round by round.
On a shared 2-core VM identical code moves 20-30% between runs (up to 2x for sub-millisecond cases),
which a within-run interval alone does not capture: hence the band. The last line counts the verdicts.
Exit code 0 whatever the verdict; 2 for unreadable input.
"""
import argparse
import os
import signal
import sys

from oitbench import cli
from oitbench import results as oitres
from oitbench.compare import add_statistics_options, compare, draw_figures, print_report, write_csv


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("csv", nargs="+", help="summary CSVs (`oitbench run --out`); the first is the baseline")
    ap.add_argument("--raw", nargs="+", default=[], help="the runs' --raw files, in the same order")
    ap.add_argument("-o", "--out-dir", help="write compare-<experiment>.png/.svg and compare.csv here")
    ap.add_argument("--labels", help="comma-separated run labels (default: file names)")
    ap.add_argument("--repeat", nargs="+", default=[],
                    help="summary CSVs of the first configuration run again: the noise band comes from how far "
                         "they lie from the first run (replaces --min-effect's fixed band)")
    add_statistics_options(ap)
    args = ap.parse_args(argv)
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)
    if len(args.csv) < 2:
        ap.error("give at least two runs")
    if args.raw and len(args.raw) != len(args.csv):
        ap.error(f"--raw needs one file per run ({len(args.csv)}), got {len(args.raw)}")
    labels = args.labels.split(",") if args.labels else [None] * len(args.csv)
    if len(labels) != len(args.csv):
        ap.error("--labels needs one label per run")
    raw_paths = args.raw or [None] * len(args.csv)
    try:
        runs = [oitres.Run.load(p, r, lab) for p, r, lab in zip(args.csv, raw_paths, labels)]
        if len({r.label for r in runs}) < len(runs):  # same file names in different folders
            for i, r in enumerate(runs):
                r.label = f"{i + 1}:{r.label}"
        comparisons, missing, params_of, notes = compare(runs, raw_paths, args)
    except oitres.ResultsError as e:
        print(f"compare.py: {e}", file=sys.stderr)
        return 2
    print_report(runs, comparisons, missing, params_of, notes, args)
    if args.out_dir:
        os.makedirs(args.out_dir, exist_ok=True)
        write_csv(os.path.join(args.out_dir, "compare.csv"), comparisons, params_of)
        for path in draw_figures(args.out_dir, runs, comparisons, params_of, args):
            if path.endswith(".png"):
                print(f"figure: {path}")
    return 0


if __name__ == "__main__":
    sys.exit(cli.run(main))
