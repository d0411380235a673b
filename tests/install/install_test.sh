#!/usr/bin/env bash
# install.FromAnyFolder: `cmake --install BUILD --prefix P` into a temp prefix, then from / with the
# OITBENCH_* variables unset: --version exits 0; info names P/share/oitbench/{shaders,scenes,presets};
# a quick occupancy run writes ok rows; a render finds its scene; a shader broken in P (and only there)
# turns the rows into errors naming it, so the rows came from P's shaders, not the source tree's; the
# installed scripts read P's schema.json and results/published.
# Usage: install_test.sh CMAKE BUILD_DIR [PYTHON3]
set -euo pipefail
cmake=$1 build=$2 python=${3:-}
case $python in *NOTFOUND) python= ;; esac
T=$(mktemp -d "${TMPDIR:-/tmp}/oitbench-install-test.XXXXXX")
trap 'rm -rf "$T"' EXIT
P=$T/prefix
fail() { echo "FAIL: $*" >&2; exit 1; }

"$cmake" --install "$build" --prefix "$P" >"$T/install.log"
for f in bin/oitbench share/oitbench/shaders/common/oitbench.glsl share/oitbench/scenes/planes.json \
         share/oitbench/presets/default.json share/oitbench/scripts/oitbench/results.py share/oitbench/scripts/tables.py \
         share/oitbench/scripts/report.py share/oitbench/scripts/schema.json share/oitbench/scripts/bundle.sh \
         share/oitbench/results/published/README.md share/doc/oitbench/README.md share/doc/oitbench/docs/usage.md; do
  [ -e "$P/$f" ] || fail "cmake --install did not install $f"
done
[ -x "$P/share/oitbench/scripts/tables.py" ] || fail "scripts lost their executable bit"
echo "installed into $P: $(find "$P" -type f | wc -l) files"

cd /
unset OITBENCH_SHADERS OITBENCH_SCENES OITBENCH_PRESETS OITBENCH_MODELS OITBENCH_EXE
exe=$P/bin/oitbench
"$exe" --version >"$T/version.txt" || fail "oitbench --version exited $?"
head -1 "$T/version.txt" | grep -q '^oitbench [0-9v]' || fail "--version: $(cat "$T/version.txt")"
cat "$T/version.txt"

"$exe" info >"$T/info.txt" || fail "info exited $?"
for kind in shaders scenes presets; do
  grep -qxF "$(printf '%-15s %s' "$kind:" "$P/share/oitbench/$kind (walking up from the binary)")" "$T/info.txt" ||
    fail "info does not name $P/share/oitbench/$kind: $(grep "^$kind:" "$T/info.txt")"
done
grep -E '^(shaders|scenes|presets):' "$T/info.txt"

"$exe" run occupancy --quick --no-progress --out "$T/occ.csv" || fail "run occupancy --quick exited $?"
# status is a column of its own; every data row must be ok, and there must be some.
status_col=$(head -1 "$T/occ.csv" | tr ',' '\n' | grep -nx status | cut -d: -f1)
ok=$(tail -n +2 "$T/occ.csv" | cut -d, -f"$status_col" | grep -cx ok || true)
rows=$(($(wc -l <"$T/occ.csv") - 1))
[ "$rows" -gt 0 ] && [ "$ok" -eq "$rows" ] || fail "$ok of $rows rows ok in occ.csv"
echo "run occupancy --quick from /: $ok ok rows"

"$exe" render --scene planes --view fwd --resolution 64x64 --out "$T/planes.png" >"$T/render.log" 2>&1 ||
  fail "render --scene planes exited $?: $(tail -3 "$T/render.log")"
[ -s "$T/planes.png" ] || fail "render wrote no image"

# The rows' shaders are P's: break P's occupancy shader (the source tree's stays as it is).
for f in "$P"/share/oitbench/shaders/occupancy/*; do echo "#error oitbench-install-check" >>"$f"; done
if "$exe" run occupancy --quick --no-progress --set size=8 --set variant=dynamic --out "$T/broken.csv" 2>"$T/broken.err"; then
  fail "a run on P's broken shader exited 0"
fi
grep -q "oitbench-install-check" "$T/broken.csv" || fail "the error row does not come from P's shader: $(cat "$T/broken.err")"
echo "a shader broken in the prefix breaks the rows: they read the prefix's shaders"

if [ -n "$python" ]; then
  "$python" - "$P/share/oitbench/scripts" <<'PY' || fail "the installed scripts do not read the prefix's data"
import os, sys
sys.path.insert(0, sys.argv[1])
from oitbench import results
import tables
share = os.path.dirname(sys.argv[1])
assert results.SCHEMA_PATH == os.path.join(share, "scripts", "schema.json"), results.SCHEMA_PATH
assert tables.default_paper_dir() == os.path.join(share, "results", "published"), tables.default_paper_dir()
print("scripts read", results.SCHEMA_PATH, "and", tables.default_paper_dir())
PY
  "$python" "$P/share/oitbench/scripts/tables.py" "$T/occ.csv" --format csv >"$T/tables.csv" ||
    fail "installed tables.py exited $?"
  grep -q '^bruell-A.1,' "$T/tables.csv" || fail "installed tables.py printed no paper numbers"
fi
echo "PASS"
