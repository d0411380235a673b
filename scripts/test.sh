#!/usr/bin/env bash
# Builds and runs every test (unit, GPU on the embedded default, scripts) with ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh
scripts/build.sh
cd build
ctest --output-on-failure -j2 "$@"
