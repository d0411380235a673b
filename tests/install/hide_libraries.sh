#!/usr/bin/env bash
# Run inside a fresh mount namespace (unshare -rm): hides the libraries NAMES (each soname, and the
# files it names with a suffix, libfoo.so.5 and libfoo.so.5.2.4) in each DIR, then runs COMMAND.
# Each DIR is replaced by a folder of links to everything else it holds, so the loader's cache and
# search paths still find the rest (the GL driver among it) but not these. COMMAND must not need a
# hidden library itself (bash does: libtinfo), so it is exec'd straight away.
# Usage: hide_libraries.sh WORK "NAME..." DIR... -- COMMAND...
set -euo pipefail
work=$1 names=$2
shift 2
dirs=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do dirs+=("$1"); shift; done
[ $# -gt 1 ] || { echo "usage: hide_libraries.sh WORK \"NAME...\" DIR... -- COMMAND..." >&2; exit 2; }
shift
skip=()
for n in $names; do skip+=(! -name "$n" ! -name "$n.*"); done
i=0
for dir in "${dirs[@]}"; do
  i=$((i + 1))
  mkdir -p "$work/orig$i" "$work/farm$i"
  mount --bind "$dir" "$work/orig$i"
  find "$work/orig$i" -mindepth 1 -maxdepth 1 "${skip[@]}" -exec ln -s -t "$work/farm$i" {} +
  mount --bind "$work/farm$i" "$dir"
done
exec "$@"
