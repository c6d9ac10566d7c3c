"""`sphcover` on scenes of many named surfaces (issue 39, item 2): a closed room of tiles, every
tile a named surface (Data/scenes/tools/tiled_room.py), as a CAD or mesh scene of thousands of
named parts.

- 20,184 tiles, each with a material of its own: `info` loads them (the loader is linear: hashed
  names and materials) and `solve` under a small --memory-limit is refused before any work, with
  one line naming the budget and no report written.
- 1,014 tiles solved: the report's form factors are the sparse `pairs` (no dense `matrix` beyond
  256 surfaces), each [from, to, F] between two different tiles (a flat tile does not see
  itself), at most one per region of a tile's hemisphere; every tile's row sums to 1 (a closed
  room: its hemisphere is covered) and the room absorbs what its lamp emits.
- 216 tiles: the report keeps the dense `matrix` too, and it holds the pairs' values, 0 elsewhere.

The whole pipeline at 20,184 tiles (minutes on two cores) is measured by
Testing/Benchmarks/many_surfaces.py, not here; the figures of 20,184 surfaces are checked in
seconds by SolutionFigures.TwentyThousandNamedSurfacesOfAClosedRoom.
"""
import json
import os
import subprocess
import sys
import tempfile

sphcover, data = sys.argv[1:3]
sys.path.insert(0, os.path.join(data, "scenes", "tools"))
from tiled_room import write_room  # noqa: E402

failures = []
folder = tempfile.mkdtemp()
# The room's settings (tiled_room.py): one patch per tile, a 4 x 16 hemisphere grid.
CELLS = 4 * 16


def run(*arguments):
    return subprocess.run([sphcover, *arguments], capture_output=True, text=True, timeout=600)


# 20,184 named surfaces with a material each: loaded, and refused before the work when the limit
# cannot hold them.
large = os.path.join(folder, "room_20000.scene")
tiles = write_room(large, 20000, own_materials=True)
result = run("info", large)
if result.returncode != 0 or f"Surfaces: {tiles} named" not in result.stdout:
    failures.append(f"info of {tiles} named surfaces: exit {result.returncode}, "
                    f"{result.stderr.strip()[-300:]}")
else:
    print(f"info: {tiles} named surfaces, {tiles} materials loaded")
report = os.path.join(folder, "refused.json")
result = run("solve", large, "--report", report, "--quiet", "--memory-limit", "8")
lines = result.stderr.strip().splitlines()
if (result.returncode == 0 or len(lines) != 1 or "--memory-limit (8 MiB)" not in lines[0] or
        f"{tiles} patches of {tiles} named surfaces" not in lines[0] or
        "before any is split" not in lines[0] or os.path.exists(report)):
    failures.append(f"solve of {tiles} surfaces under 8 MiB: exit {result.returncode}, "
                    f"stderr {result.stderr!r}, report written: {os.path.exists(report)}")
else:
    print(lines[0])


def solve(count):
    scene = os.path.join(folder, f"room_{count}.scene")
    tiles = write_room(scene, count)
    report = os.path.join(folder, f"room_{count}.json")
    result = run("solve", scene, "--report", report, "--quiet", "--direct-nodes", "0",
                 "--memory-limit", "512")
    if result.returncode != 0:
        failures.append(f"solve of {tiles} tiles failed: {result.stderr.strip()}")
        return tiles, None
    return tiles, json.load(open(report))


tiles, report = solve(1000)
if report:
    factors = report["form_factors"]
    pairs = factors["pairs"]
    if "matrix" in factors or len(factors["names"]) != tiles or len(report["surfaces"]) != tiles:
        failures.append(f"{tiles} tiles: names {len(factors['names'])}, surfaces "
                        f"{len(report['surfaces'])}, matrix given: {'matrix' in factors}")
    rows = [0.0] * tiles
    seen = [0] * tiles
    for a, b, value in pairs:
        if not (0 <= a < tiles and 0 <= b < tiles and a != b and value > 0.0):
            failures.append(f"{tiles} tiles: pair {[a, b, value]}")
            break
        rows[a] += value
        seen[a] += 1
    points = report["counts"]["characteristic_points"]
    worst = max(abs(row - 1.0) for row in rows)
    print(f"{tiles} tiles: {len(pairs)} pairs (the dense matrix: {tiles * tiles}), at most "
          f"{max(seen)} per tile, worst |row - 1| {worst:.1e}, imbalance "
          f"{report['energy']['relative_imbalance']:.1e}")
    if points != tiles or max(seen) > CELLS or len(pairs) > points * CELLS:
        failures.append(f"{tiles} tiles: {len(pairs)} pairs for {points} points, up to "
                        f"{max(seen)} per tile on a grid of {CELLS} cells")
    # To float precision: the rows that see the lamp keep their measure per region as a float
    # (its regions measured on the lamp, the others scaled: SphericalCover.h, "Measured regions").
    if worst > 1e-6:
        failures.append(f"{tiles} tiles: a row of the closed room sums to 1 {worst:+.1e}")
    for emitted, absorbed in zip(report["energy"]["emitted_w"], report["energy"]["absorbed_w"]):
        if not emitted > 0 or abs(absorbed - emitted) > 1e-4 * emitted:
            failures.append(f"{tiles} tiles: absorbed {absorbed} W for {emitted} W emitted")

tiles, report = solve(216)
if report:
    factors = report["form_factors"]
    listed = {(a, b): value for a, b, value in factors["pairs"]}
    matrix = factors.get("matrix")
    if (matrix is None or len(matrix) != tiles or
            any(value != listed.get((a, b), 0.0) for a, row in enumerate(matrix)
                for b, value in enumerate(row))):
        failures.append(f"{tiles} tiles: the report's matrix is not its pairs")
    else:
        print(f"{tiles} tiles: the matrix holds the {len(listed)} pairs, 0 elsewhere")

if failures:
    print("FAILED:\n  " + "\n  ".join(failures))
    sys.exit(1)
print("OK")
