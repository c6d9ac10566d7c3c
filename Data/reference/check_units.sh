#!/bin/sh
# Unit checks of render_cycles.py (README.md, "Unit checks"): small Cycles renders whose pixel
# values are known in closed form. Prints the numbers; exits non-zero if one is off.
#   sh Data/reference/check_units.sh [WORKDIR]        (a minute or two on 2 cores)
set -e
HERE=$(cd "$(dirname "$0")" && pwd)
SCENES="$HERE/../scenes"
W=${1:-$(mktemp -d)}
mkdir -p "$W"
render() { blender -b --factory-startup --python "$HERE/render_cycles.py" -- "$@" 2>&1 | grep -e '^render_cycles' -e rror; }
expect() { blender -b --factory-startup --python "$HERE/exr_stats.py" -- expect "$@" 2>&1 | grep -v -e '^$' -e '^Blender'; }
status=0

echo "== 1. emitter seen from the front: pixels = emission (2, 3, 4) exactly"
render --scene "$HERE/checks/lamp_over_floor.scene" --camera lamp_front --out "$W/front.exr" --samples 64
expect "$W/front.exr" --mean 2 3 4 --tol 1e-6 || status=1

echo "== 2. emitter seen from behind: black"
render --scene "$HERE/checks/lamp_over_floor.scene" --camera lamp_back --out "$W/back.exr" --samples 64
expect "$W/back.exr" --mean 0 0 0 --tol 1e-6 || status=1

echo "== 3. floor under a unit square lamp at height 1: L = rho Le F, F = 0.2394565 (point to"
echo "      parallel square, on the axis); rho = 0.5, Le = (2, 3, 4), the lamp reflects nothing"
render --scene "$HERE/checks/lamp_over_floor.scene" --camera floor_centre --out "$W/floor.exr" --samples 65536
expect "$W/floor.exr" --mean 0.2394565 0.3591847 0.4789129 --tol 5e-4 || status=1

echo "== 4. the same lamp turned away from the floor (one-sided emitter): floor black"
render --scene "$HERE/checks/lamp_facing_away.scene" --camera floor_centre --out "$W/away.exr" --samples 4096
expect "$W/away.exr" --mean 0 0 0 --tol 1e-6 || status=1

echo "== 5. white furnace (furnace_box.scene, Le = 1, rho = (0.3, 0.6, 0.8)): L = Le / (1 - rho)"
render --scene "$SCENES/furnace_box.scene" --out "$W/furnace.exr" --samples 1024 --passes 4 --width 64 --height 64
expect "$W/furnace.exr" --mean 1.4285714 2.5 5 --tol 1e-3 || status=1

echo "== 6. the furnace with --bounces 0 (Cycles: direct light only): L = Le (1 + rho)"
render --scene "$SCENES/furnace_box.scene" --out "$W/furnace_b0.exr" --samples 256 --width 64 --height 64 --bounces 0
expect "$W/furnace_b0.exr" --mean 1.3 1.6 1.8 --tol 1e-3 || status=1

echo "== 7. Cycles' Glossy BSDF (GGX, roughness 0.5, colour 0.8 0.6 0.4: the origin of"
echo "      ../brdf/ggx_r050.brdf.csv) on the floor of a closed box of emitters (Le = 1, no reflection):"
echo "      L = colour x the lobe's albedo at the view angle, from make_ggx_table.py's formula"
for view in normal:0 at60:60; do
    camera=${view%%:*}; angle=${view##*:}
    render --scene "$HERE/checks/ggx_furnace.scene" --camera "$camera" --out "$W/ggx_$camera.exr" --samples 4096 --passes 2
    expect "$W/ggx_$camera.exr" --mean $(python3 "$HERE/../brdf/tools/make_ggx_table.py" --albedo "$angle") --tol 5e-4 || status=1
done

[ $status -eq 0 ] && echo "all unit checks passed" || echo "SOME UNIT CHECKS FAILED"
exit $status
