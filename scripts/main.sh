#!/usr/bin/env bash
# The main job: set up and build (scripts/setup.sh), then render the Cornell box from Data/
# (the whole pipeline: subdivision, spherical cover, light propagation, rendering) to OpenEXR
# (HDR radiance), a tone-mapped PNG and a JSON report in $SPHCOVER_OUTPUT_DIR (default: output/ at the top of the repository).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
build="${SPHCOVER_BUILD_DIR:-$root/build}"
output="${SPHCOVER_OUTPUT_DIR:-$root/output}"
mkdir -p "$output"
"$build/bin/sphcover" render "$root/Data/scenes/cornell_box.scene" \
  -o "$output/cornell_box.exr" --png "$output/cornell_box.png" --report "$output/cornell_box.json"
