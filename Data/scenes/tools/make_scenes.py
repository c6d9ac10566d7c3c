#!/usr/bin/env python3
"""Regenerate the reference scenes in Data/scenes/ from the models in Data/models/.

Run from anywhere:  python3 Data/scenes/tools/make_scenes.py
Then verify them:   python3 Data/scenes/tools/verify_scenes.py

Plain python3, no third-party packages. The geometry of cornell_box.scene is derived from the
OBJ files in Data/models/cornell_box/ (the Cornell data, in mm, y up).
"""

import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

from scenegeom import add, cross, dot, png_file, read_obj, sub, unit, write_scene  # noqa: E402

SCENES = os.path.dirname(HERE)
MODELS = os.path.join(os.path.dirname(SCENES), "models")
CBOX = os.path.join(MODELS, "cornell_box")

# Mitsuba's RGB conversion of Cornell's measured spectra (bsdfs-rgb.xml / cbox-rgb.xml).
CORNELL_MATERIALS = {
    "white": {"type": "diffuse", "reflectance": [0.885809, 0.698859, 0.666422]},
    "red": {"type": "diffuse", "reflectance": [0.570068, 0.0430135, 0.0443706]},
    "green": {"type": "diffuse", "reflectance": [0.105421, 0.37798, 0.076425]},
    "lamp": {"type": "diffuse", "reflectance": [0.78, 0.78, 0.78], "emission": [18.387, 10.9873, 2.75357]},
}

CORNELL_CAMERA = {"name": "main", "position": [278, 273, -800], "focal_point": [278, 273, -799],
                  "view_up": [0, 1, 0], "view_angle": 39.3077, "width": 512, "height": 512}

LIGHT_OFFSET_Y = -0.5  # cbox.xml: <translate x="0" y="-0.5" z="0"/> on the luminaire


def clean(p):
    """Round away float noise (e.g. 548.8 - 0.5) so the files show the Cornell numbers."""
    return [round(c, 6) + 0.0 for c in p]


def obj_quads(name):
    verts, faces = read_obj(os.path.join(CBOX, name))
    return [[clean(verts[i]) for i in f] for f in faces]


def block_faces(objname):
    """The 12 triangles of a MeshLab block, paired into its 6 quads (a, b, c), (a, c, d) -> a b c d."""
    verts, faces = read_obj(os.path.join(CBOX, objname))
    assert len(faces) == 12
    quads = []
    for k in range(0, 12, 2):
        t1, t2 = faces[k], faces[k + 1]
        assert t1[0] == t2[0] and t1[2] == t2[1], (objname, t1, t2)
        quads.append([clean(verts[i]) for i in (t1[0], t1[1], t1[2], t2[2])])
    return quads


def centroid(points):
    n = float(len(points))
    return [sum(p[i] for p in points) / n for i in range(3)]


def face_label(normal):
    """Name a block face by where its outward normal points, as seen from the Cornell camera
    (which looks along +z with y up, so screen-left is +x): top, front (-z), back (+z),
    left (+x, toward the red wall), right (-x, toward the green wall)."""
    x, y, z = normal
    if y > 0.9:
        return "top"
    if y < -0.9:
        return "bottom"
    if abs(z) >= abs(x):
        return "front" if z < 0 else "back"
    return "left" if x > 0 else "right"


def bilinear_surface(name, points, material):
    return {"name": name, "type": "bilinear", "material": material, "points": points}


# --------------------------------------------------------------------------- Cornell box


def cornell_box():
    surfaces = []
    walls = [("floor", "cbox_floor.obj", "white"), ("ceiling", "cbox_ceiling.obj", "white"),
             ("back_wall", "cbox_back.obj", "white"), ("red_wall", "cbox_redwall.obj", "red"),
             ("green_wall", "cbox_greenwall.obj", "green")]
    for name, obj, mat in walls:
        quads = obj_quads(obj)
        # The ceiling OBJ has a second face (the light opening, reversed winding): only the
        # first face, the big quad, is the ceiling.
        surfaces.append(bilinear_surface(name, quads[0], mat))
    light = [clean(add(p, [0, LIGHT_OFFSET_Y, 0])) for p in obj_quads("cbox_luminaire.obj")[0]]
    surfaces.append(bilinear_surface("light", light, "lamp"))
    for block, obj in (("short_block", "cbox_smallbox.obj"), ("tall_block", "cbox_largebox.obj")):
        quads = block_faces(obj)
        c = centroid([p for q in quads for p in q])
        for q in quads:
            n = unit(cross(sub(q[1], q[0]), sub(q[3], q[0])))
            if dot(n, sub(centroid(q), c)) < 0:  # make the front point out of the block
                q = [q[0], q[3], q[2], q[1]]
                n = [-x for x in n]
            label = face_label(n)
            if label == "bottom":  # lies on the floor: omitted
                continue
            surfaces.append(bilinear_surface(block + "_" + label, q, "white"))
    # The Cornell data are in millimetres: reported powers are converted to watts with it.
    # No settings block: the Cornell box is solved at the defaults a user's own scene gets
    # (issue 38; Documentation/notes/time-to-accuracy.md).
    return {"version": 1, "unit": "mm", "materials": CORNELL_MATERIALS, "surfaces": surfaces,
            "cameras": [CORNELL_CAMERA]}


def cornell_box_closed():
    """The Cornell box closed by a white front wall (z = 0, facing into the room): a closed,
    non-uniform scene, for the energy balance (emitted = absorbed at equilibrium). The camera is
    inside, by the front wall."""
    scene = cornell_box()
    floor, ceiling = scene["surfaces"][0]["points"], scene["surfaces"][1]["points"]
    front = [floor[1], floor[0], ceiling[0], ceiling[3]]  # the four corners at z = 0
    scene["surfaces"].append(bilinear_surface("front_wall", front, "white"))
    scene["cameras"] = [{"name": "inside", "position": [278, 273, 20], "focal_point": [278, 273, 559.2],
                         "view_up": [0, 1, 0], "view_angle": 80.0, "width": 512, "height": 512}]
    return scene


def cornell_box_meshes():
    rel = "../models/cornell_box/"
    entries = [("floor", "cbox_floor.obj", "white", None), ("ceiling", "cbox_ceiling.obj", "white", None),
               ("back_wall", "cbox_back.obj", "white", None), ("red_wall", "cbox_redwall.obj", "red", None),
               ("green_wall", "cbox_greenwall.obj", "green", None),
               ("light", "cbox_luminaire.obj", "lamp", {"translate": [0, LIGHT_OFFSET_Y, 0]}),
               ("short_block", "cbox_smallbox.obj", "white", None),
               ("tall_block", "cbox_largebox.obj", "white", None)]
    surfaces = []
    for name, obj, mat, tr in entries:
        s = {"name": name, "type": "mesh", "material": mat, "file": rel + obj}
        if tr:
            s["transform"] = tr
        surfaces.append(s)
    # The Cornell data are in millimetres: reported powers are converted to watts with it.
    return {"version": 1, "unit": "mm", "materials": CORNELL_MATERIALS, "surfaces": surfaces,
            "cameras": [CORNELL_CAMERA]}


# --------------------------------------------------------------------------- boxes


def box_faces(lo, hi, inward):
    """The 6 faces of the axis-aligned box [lo, hi] as bilinear point lists P00 P10 P11 P01,
    named x_min ... z_max, fronts pointing into the box (inward=True) or out of it."""
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    # Each listed counter-clockwise as seen from INSIDE the box, i.e. (P10-P00) x (P01-P00)
    # points into the box.
    faces = {
        "x_min": [[x0, y0, z0], [x0, y1, z0], [x0, y1, z1], [x0, y0, z1]],
        "x_max": [[x1, y0, z0], [x1, y0, z1], [x1, y1, z1], [x1, y1, z0]],
        "y_min": [[x0, y0, z0], [x0, y0, z1], [x1, y0, z1], [x1, y0, z0]],
        "y_max": [[x0, y1, z0], [x1, y1, z0], [x1, y1, z1], [x0, y1, z1]],
        "z_min": [[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0]],
        "z_max": [[x0, y0, z1], [x0, y1, z1], [x1, y1, z1], [x1, y0, z1]],
    }
    if not inward:
        faces = {k: [q[0], q[3], q[2], q[1]] for k, q in faces.items()}
    return faces


FURNACE_MATERIAL = {"furnace": {"type": "diffuse", "reflectance": [0.3, 0.6, 0.8], "emission": [1.0, 1.0, 1.0]}}


def furnace_box():
    faces = box_faces([0, 0, 0], [1, 1, 1], inward=True)
    surfaces = [bilinear_surface(k, v, "furnace") for k, v in faces.items()]
    camera = {"name": "inside", "position": [0.5, 0.5, 0.05], "focal_point": [0.5, 0.5, 1.0],
              "view_up": [0, 1, 0], "view_angle": 90.0, "width": 256, "height": 256}
    return {"version": 1, "materials": FURNACE_MATERIAL, "surfaces": surfaces,
            "cameras": [camera]}


CLAY_FURNACE_MATERIAL = {"clay": {"type": "tabulated", "file": "../brdf/clay.brdf.csv",
                                  "emission": [1.0, 1.0, 1.0]}}


def furnace_clay():
    # The white furnace with the tabulated clay BRDF (Data/brdf/clay.brdf.csv), whose
    # directional albedo is (0.75, 0.55, 0.35) in every direction.
    scene = furnace_box()
    scene["materials"] = CLAY_FURNACE_MATERIAL
    for surface in scene["surfaces"]:
        surface["material"] = "clay"
    return scene


def furnace_sphere():
    # sphere.bpt's patches have dP/du x dP/dv pointing OUT of the sphere (checked by
    # verify_scenes.py), so "flip" turns the fronts inward.
    surfaces = [{"name": "sphere", "type": "bpt", "material": "furnace",
                 "file": "../models/geonum2017/sphere.bpt", "flip": True}]
    camera = {"name": "inside", "position": [0.0, 0.0, -0.5], "focal_point": [0.0, 0.0, 1.0],
              "view_up": [0, 1, 0], "view_angle": 90.0, "width": 256, "height": 256}
    return {"version": 1, "materials": FURNACE_MATERIAL, "surfaces": surfaces,
            "cameras": [camera]}


MIXED_MATERIALS = {
    "lamp": {"type": "diffuse", "reflectance": [0.5, 0.5, 0.5], "emission": [1.0, 2.0, 3.0]},
    "mirror": {"type": "mirror", "reflectance": [0.9, 0.8, 0.7]},
    "glossy": {"type": "phong", "diffuse": [0.3, 0.2, 0.1], "specular": [0.5, 0.4, 0.6], "exponent": 30},
    "clay": {"type": "tabulated", "file": "../brdf/clay.brdf.csv"},
    "white": {"type": "diffuse", "reflectance": [0.7, 0.6, 0.5]},
    "satin": {"type": "phong", "diffuse": [0.1, 0.1, 0.1], "specular": [0.8, 0.8, 0.8], "exponent": 5},
}


def mixed_box():
    # A closed, non-uniform scene of all four reflectance kinds: the unit cube's walls a lamp,
    # a mirror, two phong surfaces, the tabulated clay and a white wall, around an outward-facing
    # glossy cube [0.35, 0.65]^3 that hides parts of them. The materials are listed (and so
    # first used) in another order than their names sort.
    walls = box_faces([0, 0, 0], [1, 1, 1], inward=True)
    kinds = ["lamp", "mirror", "glossy", "clay", "white", "satin"]
    surfaces = [bilinear_surface(k, v, m) for (k, v), m in zip(walls.items(), kinds)]
    cube = box_faces([0.35, 0.35, 0.35], [0.65, 0.65, 0.65], inward=False)
    surfaces += [bilinear_surface("cube_" + k, v, "glossy") for k, v in cube.items()]
    camera = {"name": "inside", "position": [0.5, 0.5, 0.05], "focal_point": [0.5, 0.5, 1.0],
              "view_up": [0, 1, 0], "view_angle": 90.0, "width": 256, "height": 256}
    return {"version": 1, "materials": MIXED_MATERIALS, "surfaces": surfaces,
            "cameras": [camera]}


# --------------------------------------------------------------------------- teapot room

ROOM_LO, ROOM_HI = [-6.0, 0.0, -6.0], [6.0, 8.0, 6.0]
LAMP_Y, LAMP_HALF = 7.99, 1.5


def teapot_room():
    materials = {
        "white": {"type": "diffuse", "reflectance": [0.75, 0.75, 0.75]},
        "floor": {"type": "diffuse", "reflectance": [0.55, 0.45, 0.35]},
        "red": {"type": "diffuse", "reflectance": [0.7, 0.15, 0.12]},
        "blue": {"type": "diffuse", "reflectance": [0.15, 0.25, 0.65]},
        "mirror": {"type": "mirror", "reflectance": [0.9, 0.9, 0.9]},
        "glossy": {"type": "phong", "diffuse": [0.5, 0.35, 0.1], "specular": [0.3, 0.3, 0.3], "exponent": 40},
        "lamp": {"type": "diffuse", "reflectance": [0.78, 0.78, 0.78], "emission": [12.0, 11.0, 9.5]},
    }
    f = box_faces(ROOM_LO, ROOM_HI, inward=True)
    walls = [("floor", f["y_min"], "floor"), ("ceiling", f["y_max"], "white"),
             ("mirror_wall", f["z_min"], "mirror"), ("front_wall", f["z_max"], "white"),
             ("left_wall", f["x_min"], "red"), ("right_wall", f["x_max"], "blue")]
    surfaces = [bilinear_surface(n, q, m) for n, q, m in walls]
    h = LAMP_HALF
    # Counter-clockwise seen from below: front faces -y (down into the room).
    lamp = [[-h, LAMP_Y, -h], [h, LAMP_Y, -h], [h, LAMP_Y, h], [-h, LAMP_Y, h]]
    surfaces.append(bilinear_surface("lamp", lamp, "lamp"))
    # teapot.bpt is z-up with its base at z = 0: rotating by -90 deg about x maps (x, y, z) to
    # (x, z, -y), so it stands on the floor y = 0 (touching it at the centre of its slightly
    # domed bottom), spout toward +x; then turned 30 deg about y (spout toward +x, -z) so that
    # the camera sees it in profile, spout to the right, and its other side in the mirror.
    surfaces.append({"name": "teapot", "type": "bpt", "material": "glossy", "file": "../models/teapot.bpt",
                     "transform": {"scale": 1.0, "rotate": [-90, 30, 0], "translate": [0, 0, 0]}})
    camera = {"name": "corner", "position": [4.5, 4.5, 5.0], "focal_point": [-0.6, 1.2, -1.0],
              "view_up": [0, 1, 0], "view_angle": 55.0, "width": 640, "height": 480}
    return {"version": 1, "materials": materials, "surfaces": surfaces, "cameras": [camera]}


# --------------------------------------------------------------------------- Howell


HOWELL_MATERIALS = {
    # A black emitter: nothing B reflects comes back, so B's mean irradiance is exactly
    # pi * Le * F_BA (see README.md).
    "lamp": {"type": "diffuse", "reflectance": [0.0, 0.0, 0.0], "emission": [1.0, 1.0, 1.0]},
    "white": {"type": "diffuse", "reflectance": [0.5, 0.5, 0.5]},
}


def howell_parallel():
    # C-11: two coaxial 1 x 2 rectangles (x in [0,1], z in [0,2]) at y = 0 and y = 1, facing each other.
    A = [[0, 0, 0], [0, 0, 2], [1, 0, 2], [1, 0, 0]]  # front +y
    B = [[0, 1, 0], [1, 1, 0], [1, 1, 2], [0, 1, 2]]  # front -y
    camera = {"name": "side", "position": [3.2, 0.5, 3.6], "focal_point": [0.5, 0.5, 1.0],
              "view_up": [0, 1, 0], "view_angle": 45.0, "width": 400, "height": 300}
    return {"version": 1, "materials": HOWELL_MATERIALS,
            "surfaces": [bilinear_surface("A", A, "lamp"), bilinear_surface("B", B, "white")],
            "cameras": [camera]}


def howell_perpendicular():
    # C-14: A = floor 1 x 2 (x in [0,1], z in [0,2], y = 0, front +y);
    #       B = wall 1 x 1.5 (x in [0,1], y in [0,1.5], z = 0, front +z); common edge x in [0,1].
    A = [[0, 0, 0], [0, 0, 2], [1, 0, 2], [1, 0, 0]]      # front +y
    B = [[0, 0, 0], [1, 0, 0], [1, 1.5, 0], [0, 1.5, 0]]  # front +z
    camera = {"name": "wedge", "position": [3.0, 2.2, 3.8], "focal_point": [0.5, 0.5, 0.8],
              "view_up": [0, 1, 0], "view_angle": 45.0, "width": 400, "height": 300}
    return {"version": 1, "materials": HOWELL_MATERIALS,
            "surfaces": [bilinear_surface("A", A, "lamp"), bilinear_surface("B", B, "white")],
            "cameras": [camera]}


# The unit disk (radius 1, centre at the origin, in the plane z = 0, front side +z) as four
# Bezier patches of degree 3 x 1: u runs along a quarter circle (the cubic arc with the usual
# handle length kappa = 4/3 (sqrt 2 - 1), radial error < 2.8e-4), v from the rim (v = 0) to the
# centre (v = 1, a collapsed edge).
UNIT_DISK_BPT = os.path.join(MODELS, "unit_disk.bpt")
KAPPA = 4.0 / 3.0 * (2.0 ** 0.5 - 1.0)


def unit_disk_bpt():
    def rotate(p, quarter):
        x, y = p
        for _ in range(quarter):
            x, y = -y, x
        return (x, y)

    arc = [(1.0, 0.0), (1.0, KAPPA), (KAPPA, 1.0), (0.0, 1.0)]
    lines = ["4"]
    for quarter in range(4):
        lines.append("3 1")
        for p in arc:
            x, y = rotate(p, quarter)
            lines.append("%r %r 0" % (x + 0.0, y + 0.0))  # + 0.0: no negative zeros
        lines += ["0 0 0"] * 4
    return "\n".join(lines) + "\n"


def howell_disks():
    # C-41: disk A (radius 1) in y = 0 facing +y, disk B (radius 0.5) in y = 0.8 facing -y, coaxial.
    rel = "../models/unit_disk.bpt"
    A = {"name": "A", "type": "bpt", "file": rel, "material": "lamp",
         "transform": {"scale": 1.0, "rotate": [-90, 0, 0]}}
    B = {"name": "B", "type": "bpt", "file": rel, "material": "white",
         "transform": {"scale": 0.5, "rotate": [90, 0, 0], "translate": [0, 0.8, 0]}}
    camera = {"name": "side", "position": [2.6, 1.6, 2.6], "focal_point": [0.0, 0.4, 0.0],
              "view_up": [0, 1, 0], "view_angle": 45.0, "width": 400, "height": 300}
    return {"version": 1, "materials": HOWELL_MATERIALS, "surfaces": [A, B],
            "cameras": [camera]}


TEXTURES = os.path.join(SCENES, "textures")


def srgb_code(linear):
    """The 8-bit sRGB code (IEC 61966-2-1) of a linear value in [0, 1]."""
    c = 12.92 * linear if linear <= 0.0031308 else 1.055 * linear ** (1 / 2.4) - 0.055
    return int(round(255 * c))


def ramp_texture():
    """textures/ramp.png, 16 x 16 sRGB: red grows with u (across the columns from the left), green
    with v (up the rows from the bottom), blue constant; smooth, so that a pixel's texture is
    about its centre's, and different along u and v, so that a transposed or flipped texture
    shows (Python.Textures)."""
    n = 16
    rows = []
    for row in range(n):  # the PNG's first row is the top: v near 1
        j = n - 1 - row
        line = bytearray()
        for i in range(n):
            line += bytes([srgb_code(0.15 + 0.8 * (i + 0.5) / n),
                           srgb_code(0.15 + 0.8 * (j + 0.5) / n), srgb_code(0.5)])
        rows.append(bytes(line))
    return png_file(n, n, 8, 2, rows)


def tiles_texture():
    """textures/tiles.png, 8 x 8 sRGB tiles of two greys (codes 235 and 120) with a reddish
    tile in the corner u, v < 1/8: a floor with sharp edges for the Cycles comparison."""
    n = 8
    rows = []
    for row in range(n):
        j = n - 1 - row
        line = bytearray()
        for i in range(n):
            if i == 0 and j == 0:
                line += bytes([235, 120, 120])
            else:
                line += bytes([235] * 3 if (i + j) % 2 == 0 else [120] * 3)
        rows.append(bytes(line))
    return png_file(n, n, 8, 2, rows)


def cornell_box_textured():
    # The Cornell box with a tiled floor (paper §5.4): compared with Cycles
    # (Data/reference/README.md, "Textures"), the texture changes the light the floor sends to
    # the walls and the blocks as well as the floor's own look.
    scene = cornell_box()
    scene["materials"]["tiles"] = {"type": "diffuse",
                                   "reflectance": list(CORNELL_MATERIALS["white"]["reflectance"]),
                                   "texture": "textures/tiles.png"}
    for surface in scene["surfaces"]:
        if surface["name"] == "floor":
            surface["material"] = "tiles"
    return scene


def textured_floor():
    # A textured floor (u along +x, v along -z) under a lamp that reflects nothing: the floor
    # receives the lamp's light only, the same with or without its texture, so its render is the
    # untextured one times the texture at each visible point (paper §5.4; Python.Textures).
    materials = {
        "tiles": {"type": "diffuse", "reflectance": [0.8, 0.8, 0.8], "texture": "textures/ramp.png"},
        "lamp": {"type": "diffuse", "reflectance": [0, 0, 0], "emission": [5, 5, 5]},
    }
    surfaces = [
        bilinear_surface("floor", [[0, 0, 1], [1, 0, 1], [1, 0, 0], [0, 0, 0]], "tiles"),
        bilinear_surface("lamp", [[0.35, 1, 0.35], [0.65, 1, 0.35], [0.65, 1, 0.65], [0.35, 1, 0.65]],
                         "lamp"),
    ]
    camera = {"name": "main", "position": [0.5, 0.8, -0.6], "focal_point": [0.5, 0, 0.5],
              "view_up": [0, 1, 0], "view_angle": 50.0, "width": 96, "height": 72}
    settings = {"theta_bins": 16, "phi_bins": 64, "max_level": 3, "tolerance": 0.05}
    return {"version": 1, "materials": materials, "surfaces": surfaces, "cameras": [camera],
            "settings": settings}


# --------------------------------------------------------------------------- benchmark rooms
# Rooms of other kinds than the Cornell box for Testing/Benchmarks/time_to_accuracy.py (issue
# 38), with no settings block: what a user's own scene gets.

ROOM_MATERIALS = {
    "wall": {"type": "diffuse", "reflectance": [0.72, 0.70, 0.66]},
    "floor": {"type": "diffuse", "reflectance": [0.42, 0.33, 0.24]},
    "ceiling": {"type": "diffuse", "reflectance": [0.80, 0.80, 0.80]},
    "clay": {"type": "diffuse", "reflectance": [0.35, 0.55, 0.30]},
    "box": {"type": "diffuse", "reflectance": [0.60, 0.25, 0.20]},
    "panel": {"type": "diffuse", "reflectance": [0.0, 0.0, 0.0], "emission": [30.0, 28.0, 24.0]},
}


def room_shell(size, skip=()):
    """The six inner faces of the room [0, size] (fronts inward), named by their place."""
    names = {"x_min": "left_wall", "x_max": "right_wall", "y_min": "floor", "y_max": "ceiling",
             "z_min": "back_wall", "z_max": "far_wall"}
    materials = {"floor": "floor", "ceiling": "ceiling"}
    faces = box_faces([0, 0, 0], size, inward=True)
    return [bilinear_surface(names[k], v, materials.get(names[k], "wall"))
            for k, v in faces.items() if names[k] not in skip]


def metre_room():
    """A 4 x 3 x 5 m room lit by a large ceiling panel (1.6 x 1.0 m), with a bicubic mound and a
    box on the floor: metres, a large emitter, curved patches."""
    surfaces = room_shell([4.0, 3.0, 5.0])
    surfaces.append(bilinear_surface("panel", [[1.2, 2.99, 2.0], [2.8, 2.99, 2.0],
                                               [2.8, 2.99, 3.0], [1.2, 2.99, 3.0]], "panel"))
    # The mound: a bicubic patch over [0.6, 2.2] x [2.6, 4.2] (x, z), its border on the floor,
    # its inner control points 0.9 m up; u along z and v along x, so its front faces up.
    heights = [[0, 0, 0, 0], [0, 0.9, 0.9, 0], [0, 0.9, 0.6, 0], [0, 0, 0, 0]]
    points = []
    for j in range(4):
        for i in range(4):
            points.append(clean([0.6 + 1.6 * j / 3, heights[j][i], 2.6 + 1.6 * i / 3]))
    surfaces.append({"name": "mound", "type": "bezier", "degree": [3, 3], "material": "clay",
                     "points": points})
    for k, v in box_faces([2.6, 0.0, 3.2], [3.4, 0.7, 4.0], inward=False).items():
        if k != "y_min":
            surfaces.append(bilinear_surface("box_" + k, v, "box"))
    camera = {"name": "main", "position": [2.0, 1.6, 0.3], "focal_point": [2.0, 1.0, 5.0],
              "view_up": [0, 1, 0], "view_angle": 60.0, "width": 256, "height": 256}
    return {"version": 1, "unit": "m", "materials": ROOM_MATERIALS, "surfaces": surfaces,
            "cameras": [camera]}


def gap_room():
    """A 4 x 2.5 x 6 m room halved by a partition 1.9 m high (0.6 m gap below the ceiling); an
    upward panel on the far half's floor lights the far ceiling, and the viewed near half gets
    only what comes through the gap: a region lit only indirectly."""
    surfaces = room_shell([4.0, 2.5, 6.0])
    for k, v in box_faces([0.0, 0.0, 2.95], [4.0, 1.9, 3.05], inward=False).items():
        if k in ("y_max", "z_min", "z_max"):
            surfaces.append(bilinear_surface("partition_" + k, v, "wall"))
    surfaces.append(bilinear_surface("panel", [[1.4, 0.01, 4.0], [1.4, 0.01, 5.2],
                                               [2.6, 0.01, 5.2], [2.6, 0.01, 4.0]], "panel"))
    camera = {"name": "main", "position": [3.5, 1.5, 0.3], "focal_point": [1.2, 1.0, 3.0],
              "view_up": [0, 1, 0], "view_angle": 65.0, "width": 256, "height": 256}
    return {"version": 1, "unit": "m", "materials": ROOM_MATERIALS, "surfaces": surfaces,
            "cameras": [camera]}


ALL = {
    "cornell_box.scene": cornell_box,
    "cornell_box_closed.scene": cornell_box_closed,
    "cornell_box_meshes.scene": cornell_box_meshes,
    "teapot_room.scene": teapot_room,
    "furnace_box.scene": furnace_box,
    "furnace_sphere.scene": furnace_sphere,
    "furnace_clay.scene": furnace_clay,
    "mixed_box.scene": mixed_box,
    "howell_parallel.scene": howell_parallel,
    "howell_perpendicular.scene": howell_perpendicular,
    "howell_disks.scene": howell_disks,
    "textured_floor.scene": textured_floor,
    "cornell_box_textured.scene": cornell_box_textured,
    "metre_room.scene": metre_room,
    "gap_room.scene": gap_room,
}


def main():
    with open(UNIT_DISK_BPT, "w") as f:
        f.write(unit_disk_bpt())
    print("wrote", UNIT_DISK_BPT)
    os.makedirs(TEXTURES, exist_ok=True)
    with open(os.path.join(TEXTURES, "ramp.png"), "wb") as f:
        f.write(ramp_texture())
    with open(os.path.join(TEXTURES, "tiles.png"), "wb") as f:
        f.write(tiles_texture())
    for name, make in ALL.items():
        write_scene(os.path.join(SCENES, name), make())
        print("wrote", os.path.join(SCENES, name))


if __name__ == "__main__":
    main()
