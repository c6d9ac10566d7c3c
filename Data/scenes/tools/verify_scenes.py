#!/usr/bin/env python3
"""Numerical checks of the reference scenes in Data/scenes/ (orientation, closedness, placement,
cameras). Prints a report and exits non-zero if any check fails.

    python3 Data/scenes/tools/verify_scenes.py

Plain python3, no third-party packages.
"""

import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import check_watertight  # noqa: E402
import howell  # noqa: E402
from scenegeom import (bilinear, cross, dist, dot, load_scene, norm, quad_nonplanarity,  # noqa: E402
                       read_obj, sub, unit)

SCENES = os.path.dirname(HERE)
MODELS = os.path.join(os.path.dirname(SCENES), "models")

FAILURES = []
GRID = [(0.1 + 0.2 * i, 0.1 + 0.2 * j) for i in range(5) for j in range(5)] + [(0.5, 0.5)]


def check(cond, what):
    print(("  ok    " if cond else "  FAIL  ") + what)
    if not cond:
        FAILURES.append(what)


def faces_toward(p, point, grid=GRID):
    """True if the front of patch p faces the point at every sample of the grid."""
    for u, v in grid:
        n = p.normal(u, v)
        if norm(n) == 0:
            continue
        if dot(n, sub(point, p.eval(u, v))) <= 0:
            return False
    return True


def faces_away(p, point, grid=GRID):
    for u, v in grid:
        n = p.normal(u, v)
        if norm(n) == 0:
            continue
        if dot(n, sub(point, p.eval(u, v))) >= 0:
            return False
    return True


def centroid(points):
    return [sum(p[i] for p in points) / len(points) for i in range(3)]


def patch_bbox(patches, k=9):
    lo, hi = [math.inf] * 3, [-math.inf] * 3
    for p in patches:
        for i in range(k):
            for j in range(k):
                q = p.eval(i / (k - 1), j / (k - 1))
                lo = [min(a, b) for a, b in zip(lo, q)]
                hi = [max(a, b) for a, b in zip(hi, q)]
    return lo, hi


# --------------------------------------------------------------------------- cameras


class Camera:
    """VTK's perspective camera: view_angle is the vertical field of view."""

    def __init__(self, c):
        self.pos = c["position"]
        self.d = unit(sub(c["focal_point"], self.pos))
        self.right = unit(cross(self.d, c["view_up"]))
        self.up = cross(self.right, self.d)
        self.t = math.tan(math.radians(c["view_angle"]) / 2)
        self.w, self.h = c["width"], c["height"]
        self.aspect = self.w / self.h

    def project(self, p):
        """Normalised image coordinates in [-1, 1]^2 if visible in the frame, else None."""
        v = sub(p, self.pos)
        z = dot(v, self.d)
        if z <= 0:
            return None
        x = dot(v, self.right) / z / (self.t * self.aspect)
        y = dot(v, self.up) / z / self.t
        return (x, y) if abs(x) <= 1 and abs(y) <= 1 else None

    def rays(self, nx=64, ny=48):
        for j in range(ny):
            for i in range(nx):
                x = (2 * (i + 0.5) / nx - 1) * self.t * self.aspect
                y = (1 - 2 * (j + 0.5) / ny) * self.t
                yield unit([self.d[k] + x * self.right[k] + y * self.up[k] for k in range(3)])


def check_camera(scene, inside=None):
    for c in scene.get("cameras", []):
        cam = Camera(c)
        check(norm(cross(cam.d, c["view_up"])) > 1e-6, "camera '%s': view_up not parallel to the view direction" % c["name"])
        check(0 < c["view_angle"] < 180 and c["width"] > 0 and c["height"] > 0, "camera '%s': valid angle and size" % c["name"])
        if inside is not None:
            lo, hi = inside
            check(all(lo[k] < cam.pos[k] < hi[k] for k in range(3)), "camera '%s' is inside the enclosure" % c["name"])


def ray_box_exit(o, d, lo, hi):
    """Exit distance and axis/side of a ray starting inside the box [lo, hi]."""
    best, face = math.inf, None
    for k in range(3):
        if d[k] > 0:
            t, f = (hi[k] - o[k]) / d[k], (k, 1)
        elif d[k] < 0:
            t, f = (lo[k] - o[k]) / d[k], (k, 0)
        else:
            continue
        if t < best:
            best, face = t, f
    return best, face


def ray_hits_box(o, d, lo, hi):
    t0, t1 = 0.0, math.inf
    for k in range(3):
        if abs(d[k]) < 1e-15:
            if not (lo[k] <= o[k] <= hi[k]):
                return False
            continue
        a, b = (lo[k] - o[k]) / d[k], (hi[k] - o[k]) / d[k]
        if a > b:
            a, b = b, a
        t0, t1 = max(t0, a), min(t1, b)
    return t0 <= t1


# --------------------------------------------------------------------------- scenes


def cornell():
    print("cornell_box.scene")
    scene, patches = load_scene(os.path.join(SCENES, "cornell_box.scene"))
    names = [s["name"] for s in scene["surfaces"]]
    check(len(names) == len(set(names)) == 16, "16 uniquely named bilinear surfaces: " + ", ".join(names))
    room_centre = [278.0, 274.4, 279.6]
    for entry, name, p in patches:
        pts = [p.P(0, 0), p.P(1, 0), p.P(1, 1), p.P(0, 1)]
        npl = quad_nonplanarity(pts)
        if "block" in name:
            continue
        check(faces_toward(p, room_centre), "%-12s front faces into the room (normal %s, non-planarity %.3g mm)"
              % (name, [round(x, 4) for x in unit(p.normal(0.5, 0.5))], npl))
    for block in ("short_block", "tall_block"):
        faces = [(n, p) for _, n, p in patches if n.startswith(block)]
        c = centroid([q for _, p in faces for q in p.points] + [[q[0], 0.0, q[2]] for _, p in faces for q in p.points])
        for n, p in faces:
            check(faces_away(p, c), "%-18s front faces out of the block (normal %s)"
                  % (n, [round(x, 4) for x in unit(p.normal(0.5, 0.5))]))
        check(len(faces) == 5, "%s: top + 4 sides (bottom omitted)" % block)
    light = [p for _, n, p in patches if n == "light"][0]
    check(all(abs(q[1] - 548.3) < 1e-9 for q in light.points), "light quad at y = 548.3 (548.8 - 0.5)")
    check_camera(scene)
    cam = Camera(scene["cameras"][0])
    vis = [cam.project(q) is not None for _, _, p in patches for q in p.points if _ != "floor"]
    check(True, "camera main sees %d of %d wall/block corners" % (sum(vis), len(vis)))


def cornell_meshes():
    print("cornell_box_meshes.scene")
    scene, patches = load_scene(os.path.join(SCENES, "cornell_box_meshes.scene"))
    room_centre = [278.0, 274.4, 279.6]
    counts = {}
    for entry, name, p in patches:
        counts[name] = counts.get(name, 0) + 1
    check(counts == {"floor": 1, "ceiling": 2, "back_wall": 1, "red_wall": 1, "green_wall": 1, "light": 1,
                     "short_block": 12, "tall_block": 12}, "patches per entry: %s" % counts)
    seen = {}
    for entry, name, p in patches:
        k = seen.get(name, 0)
        seen[name] = k + 1
        if name in ("short_block", "tall_block"):
            continue
        if name == "ceiling" and k == 1:
            check(faces_away(p, room_centre) and unit(p.normal(0.5, 0.5))[1] > 0.999,
                  "ceiling face 2 (light opening, reversed winding) faces UP, out of the room: expected, see README")
            continue
        check(faces_toward(p, room_centre), "%-12s face %d front faces into the room" % (name, k + 1))
    for block in ("short_block", "tall_block"):
        bp = [p for _, n, p in patches if n == block]
        c = centroid([q for p in bp for q in p.points])
        grid = [(0.5, 0.25), (0.25, 0.1), (0.75, 0.1)]  # triangles: P01 = P11, avoid the collapsed edge
        check(all(faces_away(p, c, grid) for p in bp), "%s: all 12 triangles face out of the block" % block)
        bottoms = [p for p in bp if unit(p.normal(0.5, 0.25))[1] < -0.999]
        check(len(bottoms) == 2 and all(abs(q[1]) < 1e-12 for p in bottoms for q in p.points),
              "%s: 2 bottom triangles at y = 0, facing down onto the floor (kept by the mesh path)" % block)
    light = [p for _, n, p in patches if n == "light"][0]
    check(all(abs(q[1] - 548.3) < 1e-9 for q in light.points), "light translated to y = 548.3")
    # Same geometry as cornell_box.scene: every bilinear quad there is a mesh face (or a pair of
    # triangles) here with the same front.
    _, quads = load_scene(os.path.join(SCENES, "cornell_box.scene"))
    mesh_pts = [p for _, _, p in patches]
    for _, name, q in quads:
        corners = [q.P(0, 0), q.P(1, 0), q.P(1, 1), q.P(0, 1)]
        n = q.normal(0.5, 0.5)
        found = 0
        for m in mesh_pts:
            mc = [m.P(0, 0), m.P(1, 0), m.P(1, 1), m.P(0, 1)]
            if all(min(dist(a, b) for b in corners) < 1e-9 for a in mc) and dot(m.normal(0.5, 0.25), n) > 0:
                found += 1
        check(found in (1, 2), "%-18s matches %d mesh face(s) with the same front" % (name, found))


def furnace_box():
    print("furnace_box.scene")
    scene, patches = load_scene(os.path.join(SCENES, "furnace_box.scene"))
    for _, name, p in patches:
        check(faces_toward(p, [0.5, 0.5, 0.5]), "%-6s front faces into the cube (normal %s)"
              % (name, [round(x, 3) for x in unit(p.normal(0.5, 0.5))]))
    ok, pairs, _, gap = check_watertight.check([p for _, _, p in patches], verbose=False)
    check(ok and pairs == 12, "closed: 12 shared edges, consistently oriented (gap %.3g)" % gap)
    m = scene["materials"]["furnace"]
    Le, rho = m["emission"], m["reflectance"]
    check(True, "analytic radiance Le/(1-rho) = %s" % [round(e / (1 - r), 6) for e, r in zip(Le, rho)])
    check_camera(scene, ([0, 0, 0], [1, 1, 1]))


def mixed_box():
    print("mixed_box.scene")
    scene, patches = load_scene(os.path.join(SCENES, "mixed_box.scene"))
    for _, name, p in patches:
        if name.startswith("cube_"):
            check(faces_away(p, [0.5, 0.5, 0.5]), "%-10s front faces out of the inner cube" % name)
        else:
            check(faces_toward(p, [0.5, 0.5, 0.5]), "%-10s front faces into the room" % name)
    ok, pairs, _, gap = check_watertight.check([p for _, _, p in patches], verbose=False)
    check(ok and pairs == 24, "closed: 24 shared edges (room and cube), consistently oriented (gap %.3g)" % gap)
    kinds = sorted({m["type"] for m in scene["materials"].values()})
    check(kinds == ["diffuse", "mirror", "phong", "tabulated"], "all four reflectance kinds: %s" % kinds)
    check_camera(scene, ([0, 0, 0], [1, 1, 1]))


def furnace_sphere():
    print("furnace_sphere.scene")
    raw = check_watertight.read_bpt(os.path.join(MODELS, "geonum2017", "sphere.bpt"))
    check(all(faces_away(p, [0, 0, 0]) for p in raw), "sphere.bpt as stored: all 8 patches face OUT (so the scene flips them)")
    scene, patches = load_scene(os.path.join(SCENES, "furnace_sphere.scene"))
    check(scene["surfaces"][0].get("flip") is True, "furnace_sphere.scene sets \"flip\": true")
    fine = [((i + 0.5) / 16, (j + 0.5) / 16) for i in range(16) for j in range(16)]
    check(len(patches) == 8 and all(faces_toward(p, [0, 0, 0], fine) for _, _, p in patches),
          "after flip: all 8 patches face the centre at 256 interior points each")
    ok, pairs, ndeg, gap = check_watertight.check([p for _, _, p in patches], verbose=False)
    check(ok and pairs == 12 and ndeg == 8,
          "watertight: 12 shared boundary curves (identical control points), 8 collapsed pole edges, "
          "consistently oriented, sampled gap %.3g" % gap)
    rmin, rmax = math.inf, 0.0
    for _, _, p in patches:
        for i in range(33):
            for j in range(33):
                r = norm(p.eval(i / 32, j / 32))
                rmin, rmax = min(rmin, r), max(rmax, r)
    check(True, "radius over the patches in [%.6f, %.6f] (cubic approximation of the unit sphere)" % (rmin, rmax))
    check_camera(scene, ([-0.7] * 3, [0.7] * 3))


def teapot_room():
    print("teapot_room.scene")
    scene, patches = load_scene(os.path.join(SCENES, "teapot_room.scene"))
    room_lo, room_hi = [-6.0, 0.0, -6.0], [6.0, 8.0, 6.0]
    centre = [0.0, 4.0, 0.0]
    for _, name, p in patches:
        if name in ("teapot", "lamp"):
            continue
        check(faces_toward(p, centre), "%-12s front faces into the room (normal %s)"
              % (name, [round(x, 3) for x in unit(p.normal(0.5, 0.5))]))
    lamp = [p for _, n, p in patches if n == "lamp"][0]
    check(unit(lamp.normal(0.5, 0.5))[1] < -0.999 and all(7.9 < q[1] < 8.0 for q in lamp.points),
          "lamp faces down, %.3g below the ceiling" % (8.0 - lamp.points[0][1]))
    pot = [p for _, n, p in patches if n == "teapot"]
    lo, hi = patch_bbox(pot, 17)
    check(len(pot) == 32, "teapot: 32 bicubic patches")
    check(abs(lo[1]) < 1e-9 and all(room_lo[k] <= lo[k] and hi[k] < room_hi[k] for k in range(3)),
          "teapot stands on the floor (min y = %.2g), bbox %s .. %s inside the room"
          % (lo[1], [round(x, 3) for x in lo], [round(x, 3) for x in hi]))
    # Orientation of the teapot: the body patches (4..11 in teapot.bpt) face away from the
    # teapot's vertical axis; the bottom (28..31) faces down.
    axis_ok = all(dot(p.normal(0.5, 0.5), sub(p.eval(0.5, 0.5), [0.0, p.eval(0.5, 0.5)[1], 0.0])) > 0 for p in pot[4:12])
    bottom_ok = all(unit(p.normal(0.5, 0.5))[1] < -0.9 for p in pot[28:32])
    check(axis_ok and bottom_ok, "teapot patches face outward (body away from its axis, bottom down)")
    check_camera(scene, (room_lo, room_hi))
    cam = Camera(scene["cameras"][0])
    samples = [p.eval(i / 8, j / 8) for p in pot for i in range(9) for j in range(9)]
    proj = [cam.project(q) for q in samples]
    check(all(q is not None for q in proj), "the whole teapot is in the frame (x in [%.2f, %.2f], y in [%.2f, %.2f])"
          % (min(q[0] for q in proj if q), max(q[0] for q in proj if q), min(q[1] for q in proj if q), max(q[1] for q in proj if q)))
    n = mirror = pot_direct = pot_in_mirror = 0
    for d in cam.rays():
        n += 1
        if ray_hits_box(cam.pos, d, lo, hi):
            pot_direct += 1
            continue
        t, face = ray_box_exit(cam.pos, d, room_lo, room_hi)
        if face == (2, 0):  # z = -6: the mirror
            mirror += 1
            hit = [cam.pos[k] + t * d[k] for k in range(3)]
            r = [d[0], d[1], -d[2]]
            if ray_hits_box(hit, r, lo, hi):
                pot_in_mirror += 1
    check(mirror > 0.15 * n and pot_in_mirror > 0.01 * n,
          "image: teapot bbox %.0f%%, mirror wall %.0f%%, teapot seen in the mirror %.1f%% of the pixels"
          % (100.0 * pot_direct / n, 100.0 * mirror / n, 100.0 * pot_in_mirror / n))


def howell_scenes():
    for fname, expect in (("howell_parallel.scene", ("C-11", howell.f_parallel(1, 2, 1), howell.f_parallel(1, 2, 1))),
                          ("howell_perpendicular.scene", ("C-14", howell.f_perpendicular(1, 2, 1.5),
                                                         howell.f_perpendicular(1, 1.5, 2)))):
        print(fname)
        scene, patches = load_scene(os.path.join(SCENES, fname))
        (_, na, A), (_, nb, B) = patches
        ca, cb = A.eval(0.5, 0.5), B.eval(0.5, 0.5)
        check(na == "A" and nb == "B", "surfaces A and B")
        check(faces_toward(A, cb) and faces_toward(B, ca), "A faces B and B faces A")
        area_a, area_b = A.area(8), B.area(8)
        if "parallel" in fname:
            # geometry of C-11: equal coaxial rectangles a x b at separation c
            sep = abs(dot(sub(cb, ca), unit(A.normal(0.5, 0.5))))
            check(abs(area_a - 2) < 1e-12 and abs(area_b - 2) < 1e-12 and abs(sep - 1) < 1e-12,
                  "1 x 2 rectangles, separation 1, coaxial (centres %s, %s)" % (ca, cb))
            q = howell.form_factor_quadrature(
                ([0, 0, 0], [1, 0, 0], [0, 0, 2]), unit(A.normal(0.5, 0.5)),
                ([0, 1, 0], [1, 0, 0], [0, 0, 2]), unit(B.normal(0.5, 0.5)), n=10)
            check(abs(q - expect[1]) < 1e-6, "quadrature on the scene's normals F_AB = %.6f vs %s %.6f" % (q, expect[0], expect[1]))
        else:
            shared = [q for q in A.points if any(dist(q, r) < 1e-12 for r in B.points)]
            check(abs(area_a - 2) < 1e-12 and abs(area_b - 1.5) < 1e-12 and len(shared) == 2
                  and abs(dist(*shared) - 1) < 1e-12 and abs(dot(unit(A.normal(.5, .5)), unit(B.normal(.5, .5)))) < 1e-12,
                  "A 1 x 2, B 1 x 1.5, perpendicular, common edge of length 1")
        check(True, "%s: F_AB = %.6f, F_BA = %.6f, A_A F_AB = %.6f = A_B F_BA = %.6f"
              % (expect[0], expect[1], expect[2], area_a * expect[1], area_b * expect[2]))
        check_camera(scene)
        cam = Camera(scene["cameras"][0])
        check(all(cam.project(q) is not None for q in A.points + B.points), "camera sees all corners of A and B")


def main():
    cornell()
    cornell_meshes()
    furnace_box()
    mixed_box()
    furnace_sphere()
    teapot_room()
    howell_scenes()
    print()
    if FAILURES:
        print("%d check(s) FAILED" % len(FAILURES))
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
