#!/usr/bin/env python3
"""A closed room of many named surfaces: the unit cube's six walls, each cut into k x k tiles.

Every tile is a bilinear surface of its own name (`floor_0`, `floor_1`, ...), facing into the
room; the middle tile of the ceiling is the lamp (emission 1), the others white (rho 0.5), or
each with a material of its own (`own_materials`): what a CAD or mesh scene of thousands of
named parts looks like to the loader and the figures (issue 39). Written, not shipped: the
scene of 20,000 tiles is 5 MiB of JSON.

    python3 tiled_room.py OUT.scene [COUNT]     (COUNT tiles or a few more; default 20000)

Used by Testing/Python/TestCommandLineManySurfaces.py and Testing/Benchmarks/many_surfaces.py.
Plain python3, no third-party packages.
"""

import json
import math
import sys


def tiles(k, origin, u, v):
    """k x k quads of the face origin + s u + t v (s, t in [0, 1]), front side u x v."""
    quads = []
    for j in range(k):
        for i in range(k):
            def point(a, b):
                return [origin[c] + (i + a) / k * u[c] + (j + b) / k * v[c] for c in range(3)]
            # Counter-clockwise seen from the front (u x v): P00, P10, P11, P01.
            quads.append([point(0, 0), point(1, 0), point(1, 1), point(0, 1)])
    return quads


def write_room(path, count, own_materials=False, settings=None):
    """A closed unit cube room of about `count` tiles facing inwards; returns the tile count."""
    k = max(1, round(math.sqrt(count / 6)))
    # Each wall as (origin, u, v) with u x v pointing into the room.
    walls = [("floor", [0, 0, 0], [0, 0, 1], [1, 0, 0]),
             ("ceiling", [0, 1, 0], [1, 0, 0], [0, 0, 1]),
             ("left", [0, 0, 0], [0, 1, 0], [0, 0, 1]),
             ("right", [1, 0, 0], [0, 0, 1], [0, 1, 0]),
             ("back", [0, 0, 1], [0, 1, 0], [1, 0, 0]),
             ("front", [0, 0, 0], [1, 0, 0], [0, 1, 0])]
    materials = {"white": {"type": "diffuse", "reflectance": [0.5, 0.5, 0.5]},
                 "lamp": {"type": "diffuse", "reflectance": [0.5, 0.5, 0.5],
                          "emission": [1, 1, 1]}}
    surfaces = []
    lamp = (k // 2) * k + k // 2  # the ceiling's middle tile
    for name, origin, u, v in walls:
        for t, points in enumerate(tiles(k, origin, u, v)):
            tile = f"{name}_{t}"
            if name == "ceiling" and t == lamp:
                material = "lamp"
            elif own_materials:
                material = f"m_{tile}"
                materials[material] = {"type": "diffuse", "reflectance": [0.5, 0.5, 0.5]}
            else:
                material = "white"
            surfaces.append({"name": tile, "type": "bilinear", "material": material,
                             "points": points})
    # A camera inside the room, by the front wall, looking at the back wall.
    camera = {"name": "inside", "position": [0.5, 0.5, 0.02], "focal_point": [0.5, 0.5, 1],
              "view_up": [0, 1, 0], "view_angle": 80, "width": 64, "height": 64}
    scene = {"version": 1, "materials": materials, "surfaces": surfaces, "cameras": [camera],
             "settings": settings or {"max_level": 0, "theta_bins": 4, "phi_bins": 16}}
    with open(path, "w") as f:
        json.dump(scene, f)
    return len(surfaces)


if __name__ == "__main__":
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    print(write_room(sys.argv[1], int(sys.argv[2]) if len(sys.argv) == 3 else 20000))
