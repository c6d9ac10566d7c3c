#!/usr/bin/env bash
# The main job: set up and build (scripts/setup.sh), then run sphcover on a scene from Data/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
build="${SPHCOVER_BUILD_DIR:-$root/build}"
"$build/bin/sphcover" info "$root/Data/scenes/cornell_box.scene"
