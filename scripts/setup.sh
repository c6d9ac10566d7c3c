#!/usr/bin/env bash
# Installs the Debian 12 packages SphericalCover needs (only those missing), then configures
# and builds the project into build/ (incrementally on later runs).
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
packages=(
  g++ cmake ninja-build pkg-config
  paraview paraview-dev python3-paraview python3-dev
  libglew-dev libdouble-conversion-dev mpi-default-dev libx11-dev zlib1g-dev
  libglm-dev nlohmann-json3-dev libcli11-dev libopenexr-dev libembree-dev
  libgtest-dev libgmp-dev libeigen3-dev
  openexr
  xvfb xauth
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  sudo=()
  if [[ $(id -u) -ne 0 ]]; then sudo=(sudo); fi
  "${sudo[@]}" apt-get update
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
fi

if [[ ! -f "$build/CMakeCache.txt" ]]; then
  cmake -S "$root" -B "$build" -G Ninja \
    -DCMAKE_BUILD_TYPE=Release \
    -DPython3_EXECUTABLE=/usr/bin/python3
fi
cmake --build "$build" -j "$jobs"
