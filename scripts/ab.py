#!/usr/bin/python3
"""A/B: alternate whole short runs of two configurations and compare them round by round.

    scripts/ab.py [--rounds N] [-o DIR] [A/B options] -- RUN ARGUMENTS...

RUN ARGUMENTS are what both configurations run (`oitbench run` arguments: experiments, --set, --preset,
--quick, ...). The two configurations differ by what the A/B options add to each:

    --a-exe PATH / --b-exe PATH      two binaries (two builds, two commits; default: build/oitbench)
    --a-env NAME=V / --b-env NAME=V  two environments (repeatable; e.g. --b-env LP_NUM_THREADS=1)
    --a-args "..." / --b-args "..."  two sets of run arguments (--driver zink, --set draws=70, ...)

Rounds go A B B A A B B A ..., each run a child process of its own (`oitbench run ... --out
DIR/A/round-NN.csv --raw ...`), so neither configuration always runs first, or always after the other, and
drift between runs falls on both alike. Round pair k is the k-th A and the k-th B, run back to back. For
every case (experiment, variant, pass, resolution, parameters; a parameter that --a-args or --b-args sets
with --set is left out of the key, so `--set draws=64` pairs with `--set draws=70`):

    ratio       the median over the round pairs of median(B_k) / median(A_k): above 1, B is slower;
    interval    the distribution-free interval of that median (order statistics of the paired ratios)
                at 1 - 0.05 / cases (Bonferroni: the chance that any case of an identical pair is flagged
                stays at 5 %); with too few round pairs for it, there is no interval and no verdict;
    noise       how far two runs of the same configuration move apart: the robust spread (1.4826 MAD) of
                the log ratios of consecutive runs of one configuration (the A's and the B's that are
                neighbours in A B B A A B ...), in %;
    verdict     SLOWER / FASTER when the interval lies wholly beyond 1 +- --min-effect (default 1 %),
                else "no difference resolved".

Writes DIR/A/ and DIR/B/ (each round's CSV and raw CSV), DIR/ab.csv (one row per case: ratio, interval,
noise, verdict, the per-pair ratios) and DIR/ab-<experiment>.png/.svg; prints the table. Exit codes: 0 the
comparison was made (whatever its verdicts); 1 a run failed (its output is kept); 2 usage error.
`ab.py --summarize DIR...` summarizes trials (several out dirs of the same comparison); scripts/ab_bench.sh
runs the trials that docs/ab-measurements.md reports.
"""
import argparse
import os
import shlex
import signal
import subprocess
import sys

from oitbench import cli
from oitbench import results as oitres
from oitbench.stats import pairs_needed
from oitbench.ab import (
    DEFAULT_EXE, MIN_EFFECT, compare_rounds, describe, draw, parse_env, round_order,
    run_identity, set_names, summarize, write_table)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 usage="ab.py [options] -- RUN ARGUMENTS...")
    ap.add_argument("--rounds", type=cli.positive(int), default=10, help="round pairs: A and B runs each (default 10)")
    ap.add_argument("-o", "--out-dir", default="ab", help="where the runs and the comparison go (default ab/)")
    for c in ("a", "b"):
        ap.add_argument(f"--{c}-exe", default=DEFAULT_EXE, help=f"{c.upper()}'s oitbench binary")
        ap.add_argument(f"--{c}-env", action="append", metavar="NAME=VALUE", help=f"{c.upper()}'s environment")
        ap.add_argument(f"--{c}-args", default="", help=f"{c.upper()}'s own run arguments (one string)")
        ap.add_argument(f"--{c}-label", default=c.upper(), help=f"{c.upper()}'s name in the output")
    ap.add_argument("--min-effect", type=cli.non_negative(), default=MIN_EFFECT,
                    help=f"smallest relative difference flagged (default {MIN_EFFECT:g}: 1%%)")
    ap.add_argument("--compare-only", action="store_true", help="compare the rounds already in the out dir")
    ap.add_argument("--summarize", nargs="+", metavar="DIR",
                    help="summarize the trials in these out dirs (their ab.csv) and exit")
    ap.add_argument("run_args", nargs=argparse.REMAINDER, help="-- then the arguments of `oitbench run`")
    args = ap.parse_args(argv)
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)
    if args.summarize:
        print(summarize(args.summarize))
        return 0
    run_args = args.run_args[1:] if args.run_args[:1] == ["--"] else args.run_args
    if not run_args and not args.compare_only:
        ap.error("give the run arguments after --, e.g. -- occupancy --quick")
    if os.path.exists(args.out_dir) and not os.path.isdir(args.out_dir):
        ap.error(f"-o/--out-dir {args.out_dir}: is a file, not a folder")
    own_args = {}
    for c in ("a", "b"):
        try:
            own_args[c] = shlex.split(getattr(args, f"{c}_args"))
        except ValueError as e:
            ap.error(f"--{c}-args '{getattr(args, f'{c}_args')}': {e}")
    for bad in ("--out", "-o", "--raw"):
        if bad in run_args:
            ap.error(f"{bad} is ab.py's to set")
    configs = {}
    for c in ("A", "B"):
        lc = c.lower()
        configs[c] = {"exe": getattr(args, f"{lc}_exe"), "env": parse_env(getattr(args, f"{lc}_env"), ap),
                      "args": own_args[lc], "label": getattr(args, f"{lc}_label")}
    skip = set_names(args.a_args) | set_names(args.b_args)
    paths = {c: [] for c in configs}
    failed = []
    for c in configs:
        if not args.compare_only:
            os.makedirs(os.path.join(args.out_dir, c), exist_ok=True)
    for c, k in round_order(args.rounds):
        out = os.path.join(args.out_dir, c, f"round-{k + 1:02d}.csv")
        raw = os.path.join(args.out_dir, c, f"round-{k + 1:02d}_raw.csv")
        paths[c].append(out)
        if args.compare_only:
            continue
        for p in (out, raw):
            if os.path.exists(p):
                os.remove(p)
        cfg = configs[c]
        cmd = [cfg["exe"], "run"] + run_args + cfg["args"] + ["--out", out, "--raw", raw, "--no-progress"]
        print(f"[ab] round {k + 1}/{args.rounds} {c} ({cfg['label']}): {shlex.join(cmd)}", flush=True)
        try:
            rc = subprocess.call(cmd, env={**os.environ, **cfg["env"]})
        except OSError as e:
            print(f"ab.py: cannot run {cfg['exe']}: {e}", file=sys.stderr)
            return 2
        if rc == 130:
            print("ab.py: interrupted", file=sys.stderr)
            return 130
        if rc not in (0, 3):
            failed.append(f"{c} round {k + 1} (exit {rc})")
    # Pairs are rounds: a round that lost either run is left out whole, never shifted onto the next.
    both = [k for k in range(args.rounds) if os.path.exists(paths["A"][k]) and os.path.exists(paths["B"][k])]
    present = {c: [paths[c][k] for k in both] for c in paths}
    n = len(both)
    if n == 0 and args.compare_only:
        raise oitres.ResultsError(f"{args.out_dir}: no round pair to compare (A/round-NN.csv and B/round-NN.csv, "
                                  "as ab.py writes them)")
    if n == 0:
        print("ab.py: no round wrote a CSV", file=sys.stderr)
        return 1
    results, left_out = compare_rounds(present["A"], present["B"], skip, args.min_effect)
    if not results:
        why = (f"{args.out_dir}: no case ran ok in every round of A and B; nothing to compare"
               + (f" ({len(left_out)} case(s) missing from some round)" if left_out else ""))
        if args.compare_only:
            raise oitres.ResultsError(why)  # the rounds given are not rounds of one comparison: exit 2
        print(f"ab.py: {why}" + (f"; failed runs: {', '.join(failed)}" if failed else ""), file=sys.stderr)
        return 1
    labels = (configs["A"]["label"], configs["B"]["label"])
    print(f"A = {labels[0]}: {run_identity(present['A'][0])}")
    print(f"B = {labels[1]}: {run_identity(present['B'][0])}")
    print(f"{n} round pair(s) A B B A ...; ratio = B / A per pair, its median and interval (at "
          f"{100 * (1 - 0.05 / max(1, len(results))):.2f}% each, 95% for all {len(results)} together); "
          "noise = spread of neighbouring runs of one configuration\n")
    print(f"{'case':<60} {'ratio':>7} {'interval':>17} {'noise':>7}  verdict")
    for r in results:
        ci = f"[{r.ci[0]:.3f}, {r.ci[1]:.3f}]" if r.ci else "-"
        print(f"{describe(r.key):<60} {r.ratio:>6.3f}x {ci:>17} {r.noise:>6.1f}%  {r.verdict}")
    for k in left_out:
        print(f"not in every round: {describe(k)}")
    if results and n < pairs_needed(len(results)):
        print(f"note: {len(results)} case(s) need at least {pairs_needed(len(results))} round pairs for an interval "
              f"(--rounds); these {n} give none, so nothing can be flagged")
    flagged = [r for r in results if r.flagged]
    print(f"\n{len(flagged)} of {len(results)} case(s) flagged "
          f"({sum(r.verdict == 'SLOWER' for r in flagged)} slower, {sum(r.verdict == 'FASTER' for r in flagged)} "
          f"faster) beyond +-{100 * args.min_effect:g}%")
    write_table(os.path.join(args.out_dir, "ab.csv"), results)
    for p in draw(args.out_dir, results, labels):
        if p.endswith(".png"):
            print(f"figure: {p}")
    if failed:
        print(f"ab.py: failed runs: {', '.join(failed)}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(cli.run(main))
