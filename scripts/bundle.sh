#!/usr/bin/env bash
# Writes dist/oitbench-VERSION-linux-ARCH.tar.gz: the built binary, every shared library it needs that
# is not the GL driver or the C runtime (as ldd finds them on this machine), and the data, so that it runs
# on another Linux machine without building there and without the -dev packages, on that machine's own
# GL/EGL driver (NVIDIA's on a GPU machine).
#
#   oitbench-VERSION-linux-ARCH/
#     README.txt                 how to run it, what is inside and what the machine must have
#     bin/oitbench               the binary, debug info stripped, RUNPATH $ORIGIN/../lib
#     lib/                       the bundled libraries (each with RUNPATH $ORIGIN)
#     share/oitbench/            shaders/, scenes/, presets/, scripts/, results/published/ (as installed)
#     share/doc/oitbench/        README.md, docs/, and licenses/: each bundled library's Debian copyright
#
# Not bundled, taken from the machine it runs on:
#   - the GL driver and its dispatch: libGL*, libEGL*, libGLX*, libGLES*, libGLdispatch, libOpenGL,
#     libvulkan, libgbm, libdrm (the point: the machine's own driver, through glvnd);
#   - glibc (libc, libm, libdl, libpthread, librt, ld-linux...): it cannot be swapped under a process;
#   - libstdc++ and libgcc_s: in practice a distribution with a glibc this new (Debian 12's) has a
#     libstdc++ at least as new as this build's, and a bundled older copy would shadow the system's for
#     the driver, which loads into the same process (Mesa's LLVM, NVIDIA's libraries) and may need the
#     newer one. README.txt names the symbol versions needed.
# Bundled although Mesa's: libOSMesa (when the build links it) with its libglapi and libLLVM, which
# must be the ones it was built with; they are most of the bundle's size. A build configured with
# -DOITBENCH_WITH_OSMESA=OFF gives a bundle without them (scripts/bundle.sh --build THAT_BUILD).
#
# Usage: scripts/bundle.sh [--build DIR] [--out DIR]   (defaults: build/ and dist/ of this checkout)
# Needs patchelf (scripts/deps.sh installs it). Prints the tarball's path on stdout.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$root/build
out=$root/dist
while [ $# -gt 0 ]; do
  case $1 in
    --build) build=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    -h | --help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "bundle.sh: unknown argument '$1' (usage: scripts/bundle.sh [--build DIR] [--out DIR])" >&2; exit 2 ;;
  esac
done
exe=$build/oitbench
[ -x "$exe" ] || { echo "bundle.sh: no $exe: build first (scripts/build.sh)" >&2; exit 1; }
for tool in patchelf objcopy objdump cmake; do
  command -v "$tool" >/dev/null || { echo "bundle.sh: $tool not found (scripts/deps.sh installs what is needed)" >&2; exit 1; }
done

# The libraries taken from the machine the bundle runs on (see above); prints why, or fails.
system_library() {
  case $1 in
    ld-linux* | linux-vdso* | libc.so.* | libm.so.* | libdl.so.* | libpthread.so.* | librt.so.* | libresolv.so.* | \
      libutil.so.* | libanl.so.* | libmvec.so.* | libnsl.so.* | libBrokenLocale.so.*) echo "glibc" ;;
    libstdc++.so.* | libgcc_s.so.*) echo "C++ runtime" ;;
    libGL.so.* | libGLX* | libEGL* | libGLES* | libGLdispatch.so.* | libOpenGL.so.* | libvulkan.so.* | libgbm.so.* | \
      libdrm.so.* | libdrm_*.so.* | libnvidia* | libcuda.so.*) echo "GL driver" ;;
    *) return 1 ;;
  esac
}

version=$("$exe" --version | head -1 | cut -d' ' -f2)
name=oitbench-$version-linux-$(uname -m)
stage=$(mktemp -d "${TMPDIR:-/tmp}/oitbench-bundle.XXXXXX")
trap 'rm -rf "$stage"' EXIT
dest=$stage/$name

cmake --install "$build" --prefix "$dest" >/dev/null
objcopy --strip-debug "$dest/bin/oitbench"
mkdir -p "$dest/lib" "$dest/share/doc/oitbench/licenses"
# The models the shipped scenes load (engine-grid, house) from Debian's assimp-testmodels, into
# share/oitbench/models/, which the scene loader searches beside scenes/: a GPU machine rarely has them.
models_copied=0
while IFS= read -r file; do
  for root in /usr/share/assimp/models; do
    if [ -f "$root/$file" ]; then
      mkdir -p "$dest/share/oitbench/models/$(dirname "$file")"
      cp "$root/$file" "$dest/share/oitbench/models/$file"
      models_copied=$((models_copied + 1))
    fi
  done
done < <(sed -n 's/.*"file": *"\([^"]*\)".*/\1/p' "$root"/scenes/*.json | sort -u)
if [ $models_copied -gt 0 ] && [ -r /usr/share/doc/assimp-testmodels/copyright ]; then
  cp -L /usr/share/doc/assimp-testmodels/copyright "$dest/share/doc/oitbench/licenses/assimp-testmodels.copyright"
fi

ldd_out=$(env -u LD_LIBRARY_PATH -u LD_PRELOAD ldd "$exe")
if grep -q "not found" <<<"$ldd_out"; then
  echo "bundle.sh: $exe has libraries this machine does not find:" >&2
  grep "not found" <<<"$ldd_out" >&2
  exit 1
fi
bundled=() left=()
while read -r soname arrow path _; do
  if [ "$arrow" != "=>" ]; then # linux-vdso.so.1 (0x...) and the loader itself
    left+=("$(basename "$soname") (glibc)")
    continue
  fi
  if why=$(system_library "$soname"); then
    left+=("$soname ($why)")
    continue
  fi
  real=$(readlink -f "$path")
  cp "$real" "$dest/lib/$soname"
  chmod 0644 "$dest/lib/$soname"
  patchelf --set-rpath '$ORIGIN' "$dest/lib/$soname"
  pkg=$(dpkg -S "*/$(basename "$real")" 2>/dev/null | head -1 | cut -d: -f1 || true)
  ver=""
  if [ -n "$pkg" ]; then
    ver=$(dpkg-query -W -f='${Version}' "$pkg" 2>/dev/null || true)
    [ -r "/usr/share/doc/$pkg/copyright" ] && cp -L "/usr/share/doc/$pkg/copyright" "$dest/share/doc/oitbench/licenses/$pkg.copyright"
  fi
  bundled+=("$(printf '%-22s %s %s' "$soname" "${pkg:-?}" "$ver")")
done <<<"$ldd_out"
patchelf --set-rpath '$ORIGIN/../lib' "$dest/bin/oitbench"

# What the machine must offer: the newest glibc and libstdc++ symbol versions anything here references.
newest() { objdump -T "$dest/bin/oitbench" "$dest"/lib/*.so* 2>/dev/null | grep -o "$1[0-9.]*" | sort -uV | tail -1; }
glibc_needed=$(newest 'GLIBC_2\.')
glibcxx_needed=$(newest 'GLIBCXX_3\.')

osmesa_note=""
if [ -e "$dest/lib/libOSMesa.so.8" ]; then
  osmesa_note="lib/libOSMesa.so.8 and libglapi.so.0 (with LLVM) are this build's Mesa, for the osmesa
backend. On a machine whose own driver is a Mesa of another version that also loads libglapi.so.0,
the bundled libglapi is the one that process gets; if that driver then fails, use a bundle built with
-DOITBENCH_WITH_OSMESA=OFF (docs/usage.md). NVIDIA's driver does not use libglapi.

"
fi
cat >"$dest/README.txt" <<EOF
oitbench $version for Linux $(uname -m): GPU microbenchmarks for order-independent transparency.

Unpack anywhere and run; no build, no -dev packages, no LD_LIBRARY_PATH:

  tar xzf $name.tar.gz
  $name/bin/oitbench --version
  $name/bin/oitbench info                          # the driver this machine gives
  $name/bin/oitbench info --drivers                # every GL driver it offers
  $name/bin/oitbench run occupancy --quick --out occ.csv
  $name/bin/oitbench run --preset default --out run.csv --backend egl-device --device 0   # on a GPU

It renders through this machine's own GL driver (EGL through glvnd: NVIDIA's on an NVIDIA machine,
Mesa's elsewhere), so the machine needs that driver and libEGL.so.1 (Debian: libegl1 and the driver).
It also needs glibc with ${glibc_needed:-GLIBC_2.x} and libstdc++ with ${glibcxx_needed:-GLIBCXX_3.4.x} (Debian 12 has
both); these are not bundled. Every other library is in lib/, found through the binary's RUNPATH
(\$ORIGIN/../lib); LD_LIBRARY_PATH still overrides it, and a library deleted from lib/ is taken from the
system. A library that is missing everywhere stops the binary at start with the loader's message,
which names it ("error while loading shared libraries: libNAME.so.N: cannot open shared object file").

${osmesa_note}The shaders, scenes and presets are in share/oitbench/ and are found from the binary, from any working
directory (oitbench info names the folders in use; OITBENCH_SHADERS, OITBENCH_SCENES and
OITBENCH_PRESETS override them). The models the scenes engine-grid and house load (from Debian's
assimp-testmodels) are in share/oitbench/models/, found beside scenes/; OITBENCH_MODELS overrides.
The scripts (plot, tables, compare, report; Python 3, matplotlib for figures) are in
share/oitbench/scripts/, the papers' numbers in share/oitbench/results/published/, the manual in
share/doc/oitbench/ (docs/usage.md, "Install and bundle").

Bundled libraries (soname, Debian package, version; copyrights in share/doc/oitbench/licenses/):
$(printf '  %s\n' "${bundled[@]}")
Taken from the machine:
$(printf '  %s\n' "${left[@]}")
EOF

mkdir -p "$out"
tarball=$out/$name.tar.gz
mtime=$(git -C "$root" log -1 --format=%ct 2>/dev/null || date +%s)
tar -C "$stage" --sort=name --owner=0 --group=0 --numeric-owner --mtime="@$mtime" -cf - "$name" | gzip -n >"$tarball.part"
mv "$tarball.part" "$tarball"
echo "bundle.sh: $tarball: $(du -h "$tarball" | cut -f1), ${#bundled[@]} libraries bundled" >&2
echo "$tarball"
