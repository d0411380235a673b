#!/usr/bin/env bash
# bundle.RunsUnpackedOnItsOwnLibraries: scripts/bundle.sh on the build, unpacked into a temp folder
# whose path has a space, then from / in a scrubbed environment (env -i, no LD_LIBRARY_PATH):
#   - the tarball is named after the binary's --version and carries no GL driver, glibc or C++ runtime;
#   - --version, info (naming the bundle's share/oitbench folders) and a quick occupancy run (ok rows);
#   - ldd and LD_DEBUG=libs: every library the bundle carries is loaded from its lib/, everything else
#     loaded is the machine's GL driver stack, glibc or the C++ runtime;
#   - in a mount namespace (unshare -rm) that hides the system's copies of the bundled libraries: the
#     build's own binary cannot start (so they are out of reach), the bundle runs info and the quick
#     occupancy run, and a bundle without libassimp stops at start with the loader naming libassimp.so.5.
# Without mount namespaces the last part is skipped: exit 77 (ctest: skipped) after the rest passed.
# Usage: bundle_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
src=$1 build=$2
here=$(cd "$(dirname "$0")" && pwd)
T=$(mktemp -d "${TMPDIR:-/tmp}/oitbench-bundle-test.XXXXXX")
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
scrubbed() { env -i PATH=/usr/bin:/bin HOME="$T/home" "$@"; }
mkdir -p "$T/home"
# The libraries the bundle must leave to the machine (scripts/bundle.sh says why).
machine_library='^(ld-linux.*|linux-vdso.*|lib(c|m|dl|pthread|rt|resolv|util|anl|mvec|nsl)\.so\..*|libstdc\+\+\.so\..*|libgcc_s\.so\..*|libGL.*|libEGL.*|libGLX.*|libGLES.*|libOpenGL\.so\..*|libvulkan\.so\..*|libgbm\.so\..*|libdrm.*|libnvidia.*|libcuda\.so\..*)$'

tarball=$("$src/scripts/bundle.sh" --build "$build" --out "$T/dist")
version=$("$build/oitbench" --version | head -1 | cut -d' ' -f2)
[ "$(basename "$tarball")" = "oitbench-$version-linux-$(uname -m).tar.gz" ] || fail "tarball named $(basename "$tarball")"
echo "bundle: $(basename "$tarball"), $(du -h "$tarball" | cut -f1)"

mkdir -p "$T/un packed"
tar -C "$T/un packed" -xzf "$tarball"
U="$T/un packed/oitbench-$version-linux-$(uname -m)"
[ -x "$U/bin/oitbench" ] && [ -f "$U/README.txt" ] && [ -f "$U/share/oitbench/shaders/common/oitbench.glsl" ] ||
  fail "the tarball lacks bin/oitbench, README.txt or share/oitbench/"
mapfile -t libs < <(ls "$U/lib")
[ ${#libs[@]} -gt 0 ] || fail "no libraries in lib/"
for l in "${libs[@]}"; do
  [[ $l =~ $machine_library ]] && fail "the bundle carries $l, which must come from the machine"
done
for l in libassimp.so.5 libglfw.so.3 libOSMesa.so.8; do
  if ldd "$build/oitbench" | grep -q "^[[:space:]]$l "; then
    [ -f "$U/lib/$l" ] || fail "the build links $l but the bundle lacks it"
  fi
done
readelf -d "$U/bin/oitbench" | grep -qF 'Library runpath: [$ORIGIN/../lib]' || fail "bin/oitbench's RUNPATH is not \$ORIGIN/../lib"
echo "lib/: ${libs[*]}"

cd /
scrubbed "$U/bin/oitbench" --version >"$T/version.txt" || fail "--version exited $?"
[ "$(head -1 "$T/version.txt")" = "oitbench $version" ] || fail "--version: $(head -1 "$T/version.txt")"

check_info() { # FILE: info names the bundle's data folders
  for kind in shaders scenes presets; do
    grep -qxF "$(printf '%-15s %s' "$kind:" "$U/share/oitbench/$kind (walking up from the binary)")" "$1" ||
      fail "info does not name the bundle's $kind: $(grep "^$kind:" "$1" || true)"
  done
}
check_rows() { # CSV: some rows, all ok
  local col ok rows
  col=$(head -1 "$1" | tr ',' '\n' | grep -nx status | cut -d: -f1)
  ok=$(tail -n +2 "$1" | cut -d, -f"$col" | grep -cx ok || true)
  rows=$(($(wc -l <"$1") - 1))
  [ "$rows" -gt 0 ] && [ "$ok" -eq "$rows" ] || fail "$ok of $rows rows ok in $1"
  echo "$ok ok rows"
}
scrubbed LD_DEBUG=libs "$U/bin/oitbench" info >"$T/info.txt" 2>"$T/ld_debug.txt" || fail "info exited $?: $(grep -v '^ *[0-9]*:' "$T/ld_debug.txt" | tail -3)"
check_info "$T/info.txt"
scrubbed "$U/bin/oitbench" run occupancy --quick --no-progress --out "$T/occ.csv" || fail "run occupancy --quick exited $?"
echo -n "scrubbed environment, from /: info names the bundle's data; run occupancy --quick: "
check_rows "$T/occ.csv"

# ldd: each library resolved, the bundle's from its lib/, the rest the machine's driver stack or runtime.
scrubbed ldd "$U/bin/oitbench" >"$T/ldd.txt"
grep -q "not found" "$T/ldd.txt" && fail "ldd: $(grep "not found" "$T/ldd.txt")"
lib_dir=$(readlink -f "$U/lib")
while read -r line; do # NAME => PATH (PATH may hold spaces)
  [[ $line == *" => "* ]] || continue
  name=${line%% => *} path=${line#* => }
  if [ -e "$lib_dir/$name" ]; then
    [ "$(dirname "$(readlink -f "$path")")" = "$lib_dir" ] || fail "ldd resolves $name to $path, not the bundle's"
  else
    [[ $name =~ $machine_library ]] || fail "ldd: $name ($path) is neither in the bundle nor the machine's driver or runtime"
  fi
done < <(sed 's/ (0x[0-9a-f]*)$//' "$T/ldd.txt")
# LD_DEBUG=libs: what info actually loaded (its GL driver included), each object once.
sed -n 's/^ *[0-9]*:[[:space:]]*calling init: //p' "$T/ld_debug.txt" | sort -u >"$T/loaded.txt"
machine=()
while read -r path; do
  name=$(basename "$path")
  if [ -e "$lib_dir/$name" ]; then
    [ "$(dirname "$(readlink -f "$path")")" = "$lib_dir" ] || fail "info loaded $name from $path, not the bundle"
  else
    machine+=("$name")
  fi
done <"$T/loaded.txt"
for l in "${libs[@]}"; do
  grep -q "/$l\$" "$T/loaded.txt" || fail "info never loaded the bundle's $l"
done
echo "ldd and LD_DEBUG: all ${#libs[@]} bundled libraries load from the bundle; from the machine: ${machine[*]}"

# A mount namespace in which the system's copies of the bundled libraries are gone.
if ! unshare -rm true 2>/dev/null; then
  echo "SKIP: no mount namespace here (unshare -rm): the run with the system's copies hidden and the missing-library check did not run"
  exit 77
fi
mapfile -t dirs < <(ldd "$build/oitbench" | sed -n 's/^.* => \(.*\) (0x[0-9a-f]*)$/\1/p' | while read -r p; do
  n=$(basename "$p")
  [ -e "$lib_dir/$n" ] && dirname "$(readlink -f "$p")"
done | sort -u)
hidden() { # WORK COMMAND...: COMMAND with the system's copies of the bundled libraries hidden
  local work=$1
  shift
  unshare -rm "$here/hide_libraries.sh" "$work" "${libs[*]}" "${dirs[@]}" -- env -i PATH=/usr/bin:/bin HOME="$T/home" "$@"
}
if hidden "$T/ns0" "$build/oitbench" --version >"$T/build_hidden.txt" 2>&1; then
  fail "the build's own binary still starts with the system's copies hidden (${dirs[*]})"
fi
echo "hidden in ${dirs[*]}: the build's binary cannot start: $(grep -o 'lib[^:]*: cannot open shared object file' "$T/build_hidden.txt" | head -1)"
hidden "$T/ns1" "$U/bin/oitbench" info >"$T/info_hidden.txt" 2>&1 || fail "info with the system's copies hidden: $(tail -3 "$T/info_hidden.txt")"
check_info "$T/info_hidden.txt"
hidden "$T/ns2" "$U/bin/oitbench" run occupancy --quick --no-progress --out "$T/occ_hidden.csv" ||
  fail "run occupancy --quick with the system's copies hidden exited $?"
echo -n "with them hidden, the bundle: info names its data; run occupancy --quick: "
check_rows "$T/occ_hidden.csv"

# Bad input: a bundle that lost a library stops at start, and the loader's message names it.
cp -a "$U" "$T/broken"
rm "$T/broken/lib/libassimp.so.5"
set +e
hidden "$T/ns3" "$T/broken/bin/oitbench" --version >"$T/broken.out" 2>"$T/broken.err"
rc=$?
set -e
[ "$rc" -ne 0 ] || fail "a bundle without libassimp.so.5 started"
grep -qF "error while loading shared libraries: libassimp.so.5: cannot open shared object file" "$T/broken.err" ||
  fail "a bundle without libassimp.so.5 exited $rc with: $(cat "$T/broken.err")"
echo "without lib/libassimp.so.5: exit $rc, $(cat "$T/broken.err")"
echo "PASS"
