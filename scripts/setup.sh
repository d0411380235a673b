#!/usr/bin/env bash
# The main job on a fresh Debian 12 machine: install what is missing, build, run the default
# suite on the embedded default (EGL surfaceless; Mesa llvmpipe where there is no GPU), draw the
# figures and add the run to the local result store (results/local/oitbench.sqlite).
# Usage: scripts/setup.sh [oitbench run arguments, default: --preset default]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh
scripts/build.sh
stamp=$(date -u +%Y%m%d-%H%M%S)
out=results/local/$stamp
mkdir -p "$out"
if [ $# -eq 0 ]; then set -- --preset default; fi
build/oitbench info | tee "$out/info.txt"
set +e
build/oitbench run "$@" --out "$out/run.csv" --raw "$out/raw.csv"
rc=$?
set -e
/usr/bin/python3 scripts/plot.py "$out/run.csv" -o "$out/figures"
# Every run of the main job also lands in the local result store (docs/store.md), so a newcomer's
# runs accumulate and compare without juggling files; OITBENCH_STORE points it at a shared one.
store_rc=0
/usr/bin/python3 scripts/store.py ingest "$out/run.csv" "$out/raw.csv" || store_rc=$?
echo "oitbench: results in $out (run.csv, raw.csv, figures/)"
if [ "$store_rc" -eq 0 ]; then
  echo "oitbench: stored in ${OITBENCH_STORE:-results/local/oitbench.sqlite} (scripts/store.py runs / history / compare)"
else
  echo "oitbench: storing the run failed (exit $store_rc); the CSV files are complete" >&2
fi
exit $rc
