#!/usr/bin/env bash
# Installs the Debian 12 packages oitbench needs, only those missing. As root it runs apt-get;
# otherwise it prints the exact apt-get line and stops.
set -euo pipefail
PACKAGES=(
  g++ cmake ninja-build pkg-config git clang-format
  libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri   # EGL + Mesa (llvmpipe)
  mesa-vulkan-drivers                                 # lavapipe: the second driver, zink over lavapipe
  libosmesa6-dev                                      # optional OSMesa backend
  libglfw3-dev xvfb xauth                             # GLFW window backend, tested under xvfb-run
  python3-glad                                        # glad2: the GL loader is generated at build time
  libglm-dev libcli11-dev nlohmann-json3-dev libstb-dev
  libassimp-dev assimp-testmodels                     # model loading and the stand-in scenes
  libgtest-dev googletest                             # tests
  python3 python3-matplotlib python3-yaml             # figures, tables, comparisons; deploy/ recipes parsed in tests
  postgresql python3-psycopg                          # the shared result store (scripts/store.py) and its tests
  slurm-wlm munge                                     # tests/fleet: a single-node Slurm cluster runs a sharded array
  chromium                                            # the report page is tested in headless chromium
  patchelf                                            # scripts/bundle.sh: the bundled binary's rpath
)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
if [ "$(id -u)" -ne 0 ]; then
  echo "oitbench: missing packages; run as root (or with sudo):" >&2
  echo "  apt-get update && apt-get install -y ${missing[*]}" >&2
  exit 1
fi
echo "oitbench: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}"
