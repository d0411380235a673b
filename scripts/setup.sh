#!/usr/bin/env bash
# The main job on a fresh Debian 12 machine: install what is missing, build, run the default
# suite on the embedded default (EGL surfaceless; Mesa llvmpipe where there is no GPU), and draw
# the figures. Usage: scripts/setup.sh [oitbench run arguments, default: --preset default]
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
echo "oitbench: results in $out (run.csv, raw.csv, figures/)"
exit $rc
