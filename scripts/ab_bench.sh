#!/usr/bin/env bash
# What A/B comparisons resolve on this machine (issue 17): scripts/ab.py in repeated trials, each trial a
# whole ab.py invocation of ROUNDS round pairs, and a summary of the trials (ab.py --summarize).
#
#   scripts/ab_bench.sh [--trials N] [--rounds R] [--only identical,draws,drivers,knowles] [-o DIR]
#
#   identical  the same configuration on both sides (occupancy, 256x256, sizes 1 and 8, 64 draws, 6
#              repetitions per run): how often a case
#              is flagged when nothing changed
#   draws      occupancy size=8 at draws=64 against draws=70 (+9.4% work): how often it is flagged slower,
#              and the intervals
#   drivers    llvmpipe against zink over lavapipe on occupancy --quick and knowles2014-quick (one trial)
#   knowles    three runs of a Knowles 2014 grid (planes and hairball, rev, 128x128, BASE-IS as baseline):
#              each view's best paired resolve speedup per run (tables.py --paired)
#
# Defaults: 10 trials of 8 round pairs (2 cases need 7 for an interval at 97.5% each), every part, into results/ab-llvmpipe/ (beside, not inside, results/llvmpipe/, whose report takes every CSV below it). OITBENCH=path runs that
# binary (default build/oitbench). Exit codes: 0 done, 1 a trial failed, 2 usage error.
set -uo pipefail
cd "$(dirname "$0")/.."
PYTHON=/usr/bin/python3
OITBENCH=${OITBENCH:-build/oitbench}
trials=10
rounds=8
only=identical,draws,drivers,knowles
out=results/ab-llvmpipe
while [ $# -gt 0 ]; do
  case "$1" in
    --trials) trials=$2; shift 2 ;;
    --rounds) rounds=$2; shift 2 ;;
    --only) only=$2; shift 2 ;;
    -o) out=$2; shift 2 ;;
    -h|--help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
    *) echo "ab_bench.sh: unknown argument '$1' (try --help)" >&2; exit 2 ;;
  esac
done
[ -x "$OITBENCH" ] || { echo "ab_bench.sh: $OITBENCH is not an executable (OITBENCH=...)" >&2; exit 2; }
mkdir -p "$out"
failed=0
ab() { "$PYTHON" scripts/ab.py --a-exe "$OITBENCH" --b-exe "$OITBENCH" "$@" || failed=1; }
say() { printf '[ab_bench %s] %s\n' "$(date -u +%H:%M:%S)" "$*"; }
want() { [[ ",$only," == *",$1,"* ]]; }
# Whole draws (--max-sample-ms 0): scaled work would make 70 draws cost 70/64 of 64 by construction.
OCC=(occupancy --set variant=dynamic --resolution 256x256 --max-sample-ms 0 --reps 6)

if want identical; then
  for t in $(seq 1 "$trials"); do
    say "identical: trial $t/$trials"
    ab --rounds "$rounds" -o "$out/identical/trial-$t" -- "${OCC[@]}" --set size=1,8 --set draws=64 > /dev/null
  done
  "$PYTHON" scripts/ab.py --summarize "$out"/identical/trial-* | tee "$out/identical/SUMMARY.txt"
fi
if want draws; then
  for t in $(seq 1 "$trials"); do
    say "draws 64 against 70: trial $t/$trials"
    ab --rounds "$rounds" -o "$out/draws/trial-$t" --a-args "--set draws=64" --b-args "--set draws=70" \
      -- "${OCC[@]}" --set size=8 > /dev/null
  done
  "$PYTHON" scripts/ab.py --summarize "$out"/draws/trial-* | tee "$out/draws/SUMMARY.txt"
fi
if want drivers; then
  say "llvmpipe against zink: occupancy --quick, knowles2014-quick"
  # 10 cases need 9 round pairs for an interval at 1 - 0.05/10 each; knowles2014-quick's 180 rows (48 cases, every pass) need 13: 16 it is.
  ab --rounds $((rounds > 12 ? rounds : 12)) -o "$out/drivers-occupancy" --a-label llvmpipe --b-label zink --b-args "--driver zink" \
    -- occupancy --quick > "$out/drivers-occupancy.txt"
  ab --rounds $((rounds > 16 ? rounds : 16)) -o "$out/drivers-knowles2014-quick" --a-label llvmpipe --b-label zink \
    --b-args "--driver zink" -- --preset knowles2014-quick > "$out/drivers-knowles2014-quick.txt"
fi
if want knowles; then
  mkdir -p "$out/knowles"
  for t in 1 2 3; do
    say "knowles grid: run $t/3"
    rm -f "$out/knowles/run-$t.csv"
    "$OITBENCH" run oit --set scene=planes,hairball --set view=rev \
      --set technique=BASE-IS,BASE-IMS,BMA-IS,BMA-IMS,CS-IMS,BASE-RBS-L --set block=8 --resolution 128x128 \
      --baseline technique=BASE-IS --max-reps 12 --no-progress --out "$out/knowles/run-$t.csv" || failed=1
    "$PYTHON" scripts/tables.py --paired "$out/knowles/run-$t.csv" > "$out/knowles/run-$t.md"
  done
fi
say "done: $out"
exit $failed
