#!/usr/bin/env python3
"""Writes the scenes of the non-diffuse references (issue 39 item 3): a room with a perfect
mirror and its unfolded twin, and a room with a glossy (tabulated GGX) floor.

    python3 Data/scenes/tools/nondiffuse_rooms.py       (writes the three scenes next to this folder)

- `mirror_room.scene`: a closed room, 3 x 2.4 x 3 m (x, y up, z), lit by a ceiling panel, a
  block on the floor; its right wall (x = 3) is a perfect mirror (reflectance 1). The camera
  looks across the room at the mirror, the back wall and the floor.
- `mirror_room_unfolded.scene`: the same room unfolded across the mirror plane x = 3 (the
  method of images): every surface but the mirror, plus its reflection x -> 6 - x, all diffuse;
  the mirror is gone, so the two halves are one closed room [0, 6] x [0, 2.4] x [0, 3] with two
  lamps. Why the two scenes show the same picture through the same camera:
    * the unfolded room is symmetric about x = 3, so its radiance field is too: whatever crosses
      the plane from the left comes back, mirrored, from the right, exactly what a mirror of
      reflectance 1 sends back (a mirror of reflectance r < 1 would need the image half seen
      through a filter of r, which a diffuse scene cannot hold);
    * fronts: a reflected surface keeps its front mirrored (the reflection reverses a quad's
      winding, so its P10 and P01 are swapped): walls still face into their half, the block's
      faces out of its image, the lamp's image down; one-sided backs stay backs;
    * the lamp is reflected too: in the mirror room the floor under the mirror receives the
      lamp's light once directly and once through the mirror, the second lamp of the twin;
    * the camera stays in the real half (x < 3): what it sees of the mirror in the mirror room
      it sees of the image half in the twin, and the rest is the same room.
  Rendered by Cycles as an all-diffuse scene (Data/reference/render_cycles.py), it is the
  mirror room's independent reference (Cycles' own sharp glossy as a mirror came out 14 % dark
  against it, issue 39, so the mirror is never given to Cycles).
- `glossy_room.scene`: a closed room, 2.4 x 2 x 2.4 m, lit by a ceiling panel, a block on the
  floor; the floor is `tabulated` with Data/brdf/ggx_r050.brdf.csv, Cycles' GGX Glossy BSDF of
  roughness 0.5 tabulated (Data/brdf/tools/make_ggx_table.py). The camera looks down at the
  floor toward the back wall, so the floor shows the walls' and the block's glossy reflections.

The scenes carry no settings block: they are rendered at the filters' defaults (32 x 128 at
max_level 5), at which the project is judged; at 32 x 128 the mirror's image (the hemisphere's
cells seen in the mirror direction) is resolved to 2.8 degrees.
Plain python3, no third-party packages.
"""

import copy
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

from make_scenes import bilinear_surface as quad, box_faces  # noqa: E402
from scenegeom import write_scene  # noqa: E402

SCENES = os.path.dirname(HERE)


def room(size, names, materials, lamp, block, block_material):
    """A closed room [0, size] of the named walls (fronts inward), a lamp quad facing down and
    an outward block standing on the floor (no bottom face)."""
    surfaces = [quad(names[k], v, materials[names[k]])
                for k, v in box_faces([0, 0, 0], size, inward=True).items()]
    (x0, z0), (x1, z1), y = lamp
    # Counter-clockwise seen from below: the front faces down (-y).
    surfaces.append(quad("lamp", [[x0, y, z0], [x1, y, z0], [x1, y, z1], [x0, y, z1]], "lamp"))
    for k, v in box_faces(block[0], block[1], inward=False).items():
        if k != "y_min":
            surfaces.append(quad("block_" + k, v, block_material))
    return surfaces


MIRROR_SIZE = [3.0, 2.4, 3.0]
MIRROR_WALLS = {"x_min": "left_wall", "x_max": "mirror", "y_min": "floor", "y_max": "ceiling",
                "z_min": "front_wall", "z_max": "back_wall"}


def mirror_room():
    # Distinct colours per wall, so that the mirror's image shows which wall it reflects (the
    # front wall behind the camera, the red left wall) and a wrong mirror direction shows.
    materials = {
        "left": {"type": "diffuse", "reflectance": [0.70, 0.30, 0.25]},
        "front": {"type": "diffuse", "reflectance": [0.35, 0.60, 0.35]},
        "back": {"type": "diffuse", "reflectance": [0.50, 0.60, 0.75]},
        "floor": {"type": "diffuse", "reflectance": [0.60, 0.55, 0.45]},
        "ceiling": {"type": "diffuse", "reflectance": [0.80, 0.80, 0.80]},
        "block": {"type": "diffuse", "reflectance": [0.75, 0.70, 0.30]},
        "lamp": {"type": "diffuse", "reflectance": [0.0, 0.0, 0.0], "emission": [12.0, 11.0, 9.5]},
        "mirror": {"type": "mirror", "reflectance": [1.0, 1.0, 1.0]},
    }
    of_wall = {"left_wall": "left", "mirror": "mirror", "floor": "floor", "ceiling": "ceiling",
               "front_wall": "front", "back_wall": "back"}
    surfaces = room(MIRROR_SIZE, MIRROR_WALLS, of_wall, ((0.9, 1.1), (1.7, 1.9), 2.39),
                    ([1.9, 0.0, 1.7], [2.5, 0.9, 2.4]), "block")
    camera = {"name": "main", "position": [0.6, 1.4, 0.35], "focal_point": [2.4, 0.7, 2.1],
              "view_up": [0, 1, 0], "view_angle": 50.0, "width": 256, "height": 256}
    return {"version": 1, "unit": "m", "materials": materials, "surfaces": surfaces,
            "cameras": [camera]}


def reflect_x(points, plane):
    """The bilinear quad reflected across x = plane with its front mirrored: the reflection
    reverses the winding ((R a) x (R b) = -R (a x b) for a reflection R), so P10 and P01 swap."""
    q = [[2 * plane - p[0], p[1], p[2]] for p in points]
    return [q[0], q[3], q[2], q[1]]


def unfold(scene, mirror, plane):
    """The scene unfolded across the mirror surface `mirror` in the plane x = `plane`: the
    mirror removed, every other surface kept and its reflection added (named NAME_image), every
    material made diffuse-only (a mirror elsewhere would not unfold)."""
    out = copy.deepcopy(scene)
    kept = [s for s in out["surfaces"] if s["name"] != mirror]
    for s in kept:
        if s["type"] != "bilinear":
            raise ValueError(f"{s['name']}: only bilinear surfaces unfold here")
        if any(p[0] > plane for p in s["points"]):
            raise ValueError(f"{s['name']}: lies beyond the mirror plane")
    images = [dict(s, name=s["name"] + "_image", points=reflect_x(s["points"], plane)) for s in kept]
    out["surfaces"] = kept + images
    del out["materials"][next(s["material"] for s in scene["surfaces"] if s["name"] == mirror)]
    for name, m in out["materials"].items():
        if m["type"] != "diffuse":
            raise ValueError(f"material {name}: only diffuse scenes unfold to a diffuse twin")
    return out


def mirror_room_unfolded():
    return unfold(mirror_room(), "mirror", MIRROR_SIZE[0])


def glossy_room():
    materials = {
        "left": {"type": "diffuse", "reflectance": [0.70, 0.30, 0.25]},
        "right": {"type": "diffuse", "reflectance": [0.30, 0.55, 0.70]},
        "walls": {"type": "diffuse", "reflectance": [0.70, 0.68, 0.62]},
        "ceiling": {"type": "diffuse", "reflectance": [0.80, 0.80, 0.80]},
        "glossy": {"type": "tabulated", "file": "../brdf/ggx_r050.brdf.csv"},
        "block": {"type": "diffuse", "reflectance": [0.75, 0.70, 0.30]},
        "lamp": {"type": "diffuse", "reflectance": [0.0, 0.0, 0.0], "emission": [12.0, 11.0, 9.5]},
    }
    names = {"x_min": "left_wall", "x_max": "right_wall", "y_min": "floor", "y_max": "ceiling",
             "z_min": "front_wall", "z_max": "back_wall"}
    of_wall = {"left_wall": "left", "right_wall": "right", "floor": "glossy", "ceiling": "ceiling",
               "front_wall": "walls", "back_wall": "walls"}
    surfaces = room([2.4, 2.0, 2.4], names, of_wall, ((0.8, 0.8), (1.6, 1.6), 1.99),
                    ([1.3, 0.0, 1.4], [1.8, 0.6, 1.9]), "block")
    camera = {"name": "main", "position": [1.2, 1.6, 0.1], "focal_point": [1.2, 0.4, 1.8],
              "view_up": [0, 1, 0], "view_angle": 55.0, "width": 256, "height": 256}
    return {"version": 1, "unit": "m", "materials": materials, "surfaces": surfaces,
            "cameras": [camera]}


ALL = {
    "mirror_room.scene": mirror_room,
    "mirror_room_unfolded.scene": mirror_room_unfolded,
    "glossy_room.scene": glossy_room,
}


def main():
    for name, make in ALL.items():
        write_scene(os.path.join(SCENES, name), make())
        print("wrote", os.path.join(SCENES, name))


if __name__ == "__main__":
    main()
