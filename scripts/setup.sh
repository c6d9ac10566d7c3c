#!/usr/bin/env bash
# Installs the Debian 12 packages SphericalCover needs (those missing), upgrades them and what
# they depend on to today's versions (those outdated), then configures and builds the project into build/ (incrementally on later runs).
#
#   scripts/setup.sh            # as root, or as a user with sudo
#
# Environment: SPHCOVER_BUILD_DIR (default: <repo>/build), SPHCOVER_JOBS (default: nproc).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${SPHCOVER_BUILD_DIR:-$root/build}"
jobs="${SPHCOVER_JOBS:-$(nproc)}"

# ParaView 5.11 bundles its own VTK 9.2; we build against it (libvtk9-dev would conflict with
# python3-paraview). ParaView's VTK CMake config also needs the -dev packages on the second line.
# clang and its runtimes build the fuzz harnesses (Testing/Fuzz) that scripts/test.sh runs;
# clang-format checks the sources' layout (Structure.ClangFormat).
# qttools5-dev (Qt5Help, qhelpgenerator) and qtxmlpatterns5-dev-tools (xmlpatterns) compile the
# plug-in's XML documentation into the help that ParaView's "?" shows.
# libpng-dev decodes the materials' texture PNGs in Core (Core/scene/Texture.cxx).
packages=(
  g++ cmake ninja-build pkg-config
  paraview paraview-dev python3-paraview python3-dev
  qttools5-dev qtxmlpatterns5-dev-tools
  libglew-dev libdouble-conversion-dev mpi-default-dev libx11-dev zlib1g-dev
  libglm-dev nlohmann-json3-dev libcli11-dev libopenexr-dev libembree-dev
  libgtest-dev libgmp-dev libeigen3-dev libpng-dev
  openexr
  xvfb xauth
  clang libclang-rt-14-dev clang-format
)

sudo=()
if [[ $(id -u) -ne 0 ]]; then sudo=(sudo); fi
apt_get() { DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get "$@"; }

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
# A fresh machine gets today's Debian 12 packages; a machine set up earlier keeps the versions it
# had. Bring the packages the project uses, and everything they depend on, to today's versions,
# so that CI and developers see what a newcomer sees (libexpat1 2.5.0-1+deb12u5 changed how
# ParaView's VTK reads XML files, and only an up-to-date machine showed it).
# Refreshing the lists needs root: as a user whose sudo asks for a password, the lists the machine
# has decide what is outdated, and they are refreshed only when a package is missing.
refreshed=false
if [[ $(id -u) -eq 0 ]] || sudo -n true 2>/dev/null; then
  if apt_get update -qq; then refreshed=true; else echo "setup: apt-get update failed" >&2; fi
fi
mapfile -t closure < <(apt-cache depends --recurse --no-recommends --no-suggests \
    --no-conflicts --no-breaks --no-replaces --no-enhances "${packages[@]}" 2>/dev/null |
  grep -v '^ ' | sort -u)
mapfile -t upgradable < <(apt list --upgradable 2>/dev/null | sed -n 's|^\([^/]*\)/.*|\1|p' | sort -u)
mapfile -t outdated < <(comm -12 <(printf '%s\n' "${closure[@]}") <(printf '%s\n' "${upgradable[@]}"))
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  if [[ $refreshed == false ]]; then apt_get update; fi
  apt_get install -y --no-install-recommends "${missing[@]}"
fi
if ((${#outdated[@]})); then
  echo "setup: upgrading ${outdated[*]}" >&2
  apt_get install -y --no-install-recommends --only-upgrade "${outdated[@]}"
fi

if [[ ! -f "$build/CMakeCache.txt" ]]; then
  cmake -S "$root" -B "$build" -G Ninja \
    -DCMAKE_BUILD_TYPE=Release \
    -DPython3_EXECUTABLE=/usr/bin/python3
fi
cmake --build "$build" -j "$jobs"
