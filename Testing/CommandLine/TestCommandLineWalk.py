"""`sphcover walk` (README.md#command-line, issue 18; paper §1, §5.3: after the solve every view
is cheap, mirrors included): a saved solution rendered through every camera of a path.

- The first frame of a walk is `sphcover render --solution` for the same camera, bit for bit (PNG
  and EXR), from --path and from --orbit (whose first camera is the scene's first).
- A flat mirror under a small lamp: in every frame the lamp's reflection is where the image
  source (the lamp mirrored through the mirror's plane) projects, and it moves with the camera
  as the image source's projection does, while the lamp itself is out of view.
- A furnace (a closed box whose walls all emit Le and reflect a) looks the same from anywhere:
  every pixel of every frame of a walk inside it is Le / (1 - a).
- --orbit N: N frames, the eye on a circle around the focal point.
- Bad input (path JSON, missing keys, zero cameras, bad --orbit, a missing solution, a file as
  the folder) gives one line naming the file, the place and the problem, a non-zero exit and no
  frame written."""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.util.numpy_support import vtk_to_numpy

from sphericalcover import vtkOpenEXRReader

sphcover, data = sys.argv[1:3]
failures = []
folder = tempfile.mkdtemp()
coarse = ["--set", "max_level=1", "--set", "theta_bins=16", "--set", "phi_bins=64"]


def run(*arguments):
    return subprocess.run([sphcover, *arguments], capture_output=True, text=True, timeout=600)


def solve(scene, name, *settings):
    solution = os.path.join(folder, name)
    result = run("solve", scene, "-o", solution, "--quiet", *settings)
    if result.returncode != 0:
        sys.exit(f"solve {scene} failed: {result.stderr.strip()}")
    return solution


def write_path(name, cameras):
    path = os.path.join(folder, name)
    with open(path, "w") as stream:
        json.dump({"cameras": cameras}, stream)
    return path


def png(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    return vtk_to_numpy(image.GetPointData().GetScalars()).reshape(height, width, -1)


def exr(path):
    reader = vtkOpenEXRReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    return vtk_to_numpy(image.GetPointData().GetArray("Radiance")).reshape(height, width, 3)


def same_bytes(a, b):
    with open(a, "rb") as first, open(b, "rb") as second:
        return first.read() == second.read()


def project(camera, point):
    """The continuous pixel position (x, y; pixel (i, j) spans [i, i + 1) x [j, j + 1), row 0 at
    the bottom) of a world point through a camera, as RadianceRenderer casts its rays."""
    def sub(a, b):
        return [a[k] - b[k] for k in range(3)]

    def dot(a, b):
        return sum(a[k] * b[k] for k in range(3))

    def cross(a, b):
        return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]

    def unit(a):
        length = math.sqrt(dot(a, a))
        return [c / length for c in a]

    forward = unit(sub(camera["focal_point"], camera["position"]))
    right = unit(cross(forward, camera["view_up"]))
    up = cross(right, forward)
    half_height = math.tan(math.radians(camera["view_angle"]) / 2)
    half_width = half_height * camera["width"] / camera["height"]
    d = sub(point, camera["position"])
    depth = dot(d, forward)
    x = dot(d, right) / depth / half_width
    y = dot(d, up) / depth / half_height
    return (x + 1) / 2 * camera["width"], (y + 1) / 2 * camera["height"], depth


# --- 1. The first frame is render --solution's image, bit for bit ---------------------------
cornell = f"{data}/scenes/cornell_box.scene"
cornell_solution = solve(cornell, "cornell.vtm", *coarse)
main = {"position": [278, 273, -800], "focal_point": [278, 273, -799], "view_up": [0, 1, 0],
        "view_angle": 39.3077, "width": 48, "height": 40}
moved = dict(main, position=[200, 300, -700])
path = write_path("cornell_path.json", [main, moved])
frames = os.path.join(folder, "cornell_frames")
result = run("walk", cornell_solution, "--path", path, "-o", frames, "--exr", "--spp", "2",
             "--exposure", "1.5", "--quiet")
reference_png = os.path.join(folder, "render.png")
reference_exr = os.path.join(folder, "render.exr")
rendered = run("render", cornell, "--solution", cornell_solution, "--size", "48x40", "--spp", "2",
               "--exposure", "1.5", "-o", reference_exr, "--png", reference_png, "--quiet")
if result.returncode != 0 or rendered.returncode != 0:
    failures.append(f"walk or render failed: {result.stderr.strip()} {rendered.stderr.strip()}")
else:
    listed = sorted(os.listdir(frames))
    if listed != ["frame_0000.exr", "frame_0000.png", "frame_0001.exr", "frame_0001.png"]:
        failures.append(f"the frames' folder holds {listed}")
    for extension, reference in [("png", reference_png), ("exr", reference_exr)]:
        if not same_bytes(os.path.join(frames, f"frame_0000.{extension}"), reference):
            failures.append(f"frame_0000.{extension} differs from render --solution's image")
    if same_bytes(os.path.join(frames, "frame_0001.png"), reference_png):
        failures.append("the second camera of the path gives the first camera's frame")
    # ms per frame, one line per frame and the mean.
    lines = result.stdout.splitlines()
    if not any(line.startswith("frame 0: ") and line.endswith(" ms") for line in lines) or \
            not any(line.startswith("ms per frame: ") for line in lines):
        failures.append(f"walk does not print the milliseconds per frame: {result.stdout!r}")

# --orbit: its first camera is the scene's first (--size as render's).
orbit = os.path.join(folder, "orbit")
report = os.path.join(folder, "orbit.json")
result = run("walk", cornell_solution, "--orbit", "3", "-o", orbit, "--spp", "1", "--quiet",
             "--report", report, "--size", "96x64")
rendered = run("render", cornell, "--solution", cornell_solution, "--spp", "1", "--size", "96x64",
               "-o", os.path.join(folder, "render_orbit.png"), "--quiet")
if result.returncode != 0 or rendered.returncode != 0:
    failures.append(f"walk --orbit or render failed: {result.stderr.strip()} "
                    f"{rendered.stderr.strip()}")
else:
    if sorted(os.listdir(orbit)) != ["frame_0000.png", "frame_0001.png", "frame_0002.png"]:
        failures.append(f"--orbit 3 wrote {sorted(os.listdir(orbit))}")
    if not same_bytes(os.path.join(orbit, "frame_0000.png"),
                      os.path.join(folder, "render_orbit.png")):
        failures.append("--orbit's first frame differs from render --solution's image")
    frames_report = json.load(open(report))["frames"]
    if len(frames_report) != 3 or not all(f["render_ms"] > 0 for f in frames_report):
        failures.append(f"the report's frames: {frames_report}")
    if png(os.path.join(orbit, "frame_0001.png")).shape != (64, 96, 3):
        failures.append("an orbit frame is not of --size")

# --- 2. A mirror shows the image source where it projects, and it moves with the camera ------
# A mirror in the plane y = 0 (k_s 0.9) and a small lamp at y = 1 facing it: the lamp's
# reflection is the lamp mirrored through y = 0, centred at (0, -1, 0) (the image source). Paper
# §5.3.1 gives a mirror's image from the incident radiance E its characteristic points see, so
# the mirror, x in [-1, 1] and z in [0, 2] where the cameras see the reflection, is a mesh of
# 32 x 32 faces, a point each (max_level 0): each face shows the lamp as its point sees it, so
# the image is made of pieces displaced by the parallax of the points' spacing (1/16; the
# centre's error is up to 2.5 px at 1/6 and 1/12); a single point would show, everywhere
# on the mirror, what the mirror's centre sees.
grid = 32
with open(os.path.join(folder, "mirror.obj"), "w") as stream:
    for j in range(grid + 1):
        for i in range(grid + 1):
            stream.write(f"v {-1 + 2 * i / grid} 0 {2 * j / grid}\n")
    for j in range(grid):
        for i in range(grid):
            a = j * (grid + 1) + i + 1  # counter-clockwise seen from +y: facing the lamp
            stream.write(f"f {a} {a + grid + 1} {a + grid + 2} {a + 1}\n")
mirror_scene = os.path.join(folder, "mirror.scene")
with open(mirror_scene, "w") as stream:
    json.dump({
        "version": 1,
        "materials": {
            "mirror": {"type": "mirror", "reflectance": [0.9, 0.9, 0.9]},
            "lamp": {"type": "diffuse", "reflectance": [0.5, 0.5, 0.5],
                     "emission": [10, 10, 10]}},
        "surfaces": [
            {"name": "mirror", "type": "mesh", "file": "mirror.obj", "material": "mirror"},
            {"name": "lamp", "type": "bilinear", "material": "lamp",
             "points": [[-0.15, 1, -0.15], [0.15, 1, -0.15], [0.15, 1, 0.15], [-0.15, 1, 0.15]]}],
        "cameras": [{"name": "front", "position": [0, 0.5, 1.5], "focal_point": [0, -0.8, 0],
                     "view_up": [0, 1, 0], "view_angle": 55, "width": 128, "height": 128}],
        "settings": {"theta_bins": 64, "phi_bins": 256, "max_level": 0, "tolerance": 0.02}},
        stream)
mirror_solution = solve(mirror_scene, "mirror.vtm")
# The lamp mirrored through y = 0: the image source, a square at y = -1.
image_source = [[-0.15, -1, -0.15], [0.15, -1, -0.15], [0.15, -1, 0.15], [-0.15, -1, 0.15]]
lamp_centre = [0, 1, 0]


def projected_centroid(camera, corners):
    """The centroid of the image of a planar polygon through the camera: perspective keeps its
    edges straight, so it is the centroid of the polygon of the projected corners (the
    projection of the polygon's centre is not, by a few pixels at these angles)."""
    points = [project(camera, corner)[:2] for corner in corners]
    area = cx = cy = 0.0
    for (x0, y0), (x1, y1) in zip(points, points[1:] + points[:1]):
        cross = x0 * y1 - x1 * y0
        area += cross / 2
        cx += (x0 + x1) * cross
        cy += (y0 + y1) * cross
    return cx / (6 * area), cy / (6 * area)


mirror_cameras = [
    {"position": position, "focal_point": focal_point, "view_up": [0, 1, 0], "view_angle": 55,
     "width": 128, "height": 128}
    for position, focal_point in [([0, 0.5, 1.5], [0, -0.8, 0]), ([0.6, 0.5, 1.4], [0.2, -0.8, 0.2]),
                                  ([-0.6, 0.45, 1.5], [-0.3, -1.2, 0.1]),
                                  ([0.2, 0.7, 1.6], [0.25, -1.0, -0.2])]
]
frames = os.path.join(folder, "mirror_frames")
result = run("walk", mirror_solution, "--path", write_path("mirror_path.json", mirror_cameras),
             "-o", frames, "--exr", "--spp", "4", "--quiet")
if result.returncode != 0:
    failures.append(f"walk of the mirror failed: {result.stderr.strip()}")
else:
    # Half the diagonal of a hemisphere cell (90 / 64 degrees in theta, 360 / 256 in phi) in
    # pixels of the frames (128 pixels over 55 degrees at the centre).
    tolerance = 0.5 * math.hypot(90 / 64, 360 / 256) * 128 / 55
    centres = []
    for k, camera in enumerate(mirror_cameras):
        x_lamp, y_lamp, depth_lamp = project(camera, lamp_centre)
        # The test's own premise: the lamp is out of view (outside the frame), the image
        # source inside it.
        if depth_lamp > 0 and 0 <= x_lamp < camera["width"] and 0 <= y_lamp < camera["height"]:
            failures.append(f"camera {k}: the lamp itself is in view; the test is wrong")
        radiance = exr(os.path.join(frames, f"frame_{k:04d}.exr")).sum(axis=2)
        # The reflection: the pixels brighter than half the brightest (the mirror elsewhere
        # reflects the black sky); their radiance-weighted centroid, in continuous pixels.
        if not radiance.max() > 0:
            failures.append(f"camera {k}: the mirror shows nothing")
            continue
        bright = radiance > 0.5 * radiance.max()
        rows, columns = bright.nonzero()
        weights = radiance[rows, columns]
        x = float((weights * (columns + 0.5)).sum() / weights.sum())
        y = float((weights * (rows + 0.5)).sum() / weights.sum())
        x_image, y_image = projected_centroid(camera, image_source)
        centres.append((x, y, x_image, y_image))
        # The reflection is resolved to the mirror's hemisphere cells (1.4 degrees at 64 x 256)
        # and interpolated between its characteristic points (paper §5.3.1): its centre within
        # half a cell (tolerance, in pixels) of the image source's projection.
        error = math.hypot(x - x_image, y - y_image)
        print(f"camera {k}: reflection centred at ({x:.2f}, {y:.2f}), image source's at "
              f"({x_image:.2f}, {y_image:.2f}): {error:.2f} px")
        if not error <= tolerance:
            failures.append(f"camera {k}: the reflection's centre ({x:.1f}, {y:.1f}) is "
                            f"{error:.1f} px from the image source's ({x_image:.1f}, "
                            f"{y_image:.1f}), more than {tolerance:.1f}")
    # Between cameras the reflection moves as the image source's projection does (each move
    # is more than 10 pixels; its error within a cell's diagonal, the two frames' errors).
    if len(centres) != len(mirror_cameras):
        failures.append("the reflection was not found in every frame")
    for k in range(1, len(centres)):
        moved_x, moved_y = centres[k][0] - centres[0][0], centres[k][1] - centres[0][1]
        expected_x, expected_y = centres[k][2] - centres[0][2], centres[k][3] - centres[0][3]
        if math.hypot(expected_x, expected_y) < 10:
            failures.append(f"camera {k}: the image source moves too little; the test is wrong")
        if not math.hypot(moved_x - expected_x, moved_y - expected_y) <= 2 * tolerance:
            failures.append(f"camera {k}: the reflection moved by ({moved_x:.1f}, {moved_y:.1f}) "
                            f"px, the image source by ({expected_x:.1f}, {expected_y:.1f})")

# --- 3. A furnace walk is uniform -----------------------------------------------------------
furnace_solution = solve(f"{data}/scenes/furnace_box.scene", "furnace.vtm", *coarse)
inside = [
    {"position": [0.5, 0.5, 0.05], "focal_point": [0.5, 0.5, 1.0], "view_up": [0, 1, 0]},
    {"position": [0.5, 0.5, 0.5], "focal_point": [0.0, 0.2, 0.1], "view_up": [0, 1, 0]},
    {"position": [0.2, 0.8, 0.7], "focal_point": [0.9, 0.1, 0.3], "view_up": [0, 0, 1]},
    {"position": [0.9, 0.1, 0.9], "focal_point": [0.1, 0.9, 0.1], "view_up": [1, 0, 0]},
]
for camera in inside:
    camera.update({"view_angle": 80, "width": 32, "height": 24})
frames = os.path.join(folder, "furnace_frames")
result = run("walk", furnace_solution, "--path", write_path("furnace_path.json", inside),
             "-o", frames, "--exr", "--quiet")
expected = [1.0 / (1.0 - a) for a in (0.3, 0.6, 0.8)]
if result.returncode != 0:
    failures.append(f"walk of the furnace failed: {result.stderr.strip()}")
else:
    for k in range(len(inside)):
        radiance = exr(os.path.join(frames, f"frame_{k:04d}.exr"))
        for band in range(3):
            low, high = radiance[:, :, band].min(), radiance[:, :, band].max()
            if not (abs(low / expected[band] - 1) < 0.01 and abs(high / expected[band] - 1) < 0.01):
                failures.append(f"furnace frame {k}, band {band}: radiance from {low} to {high}, "
                                f"not {expected[band]:.4f} everywhere")

# --- 4. Bad input: one line naming the file, the place and the problem; nothing written -----
good = {"position": [278, 273, -800], "focal_point": [278, 273, 0], "view_up": [0, 1, 0],
        "view_angle": 40, "width": 8, "height": 8}
missing_width = dict(good)
del missing_width["width"]
bad_paths = {
    "syntax.json": ('{"cameras": [', "line 1"),
    "zero.json": ('{"cameras": []}', "/cameras: no cameras"),
    "missing.json": (json.dumps({"cameras": [good, missing_width]}),
                     "/cameras/1: missing key 'width'"),
    "unknown.json": (json.dumps({"cameras": [dict(good, zoom=2)]}), "/cameras/0"),
    "angle.json": (json.dumps({"cameras": [dict(good, view_angle=180)]}),
                   "/cameras/0/view_angle: must be in (0, 180)"),
    "list.json": (json.dumps([good]), "/"),
    "notarray.json": (json.dumps({"cameras": good}), "/cameras"),
}
for name, (text, location) in bad_paths.items():
    path = os.path.join(folder, name)
    with open(path, "w") as stream:
        stream.write(text)
    out = os.path.join(folder, "bad_" + name)
    result = run("walk", cornell_solution, "--path", path, "-o", out)
    lines = result.stderr.strip().splitlines()
    if result.returncode == 0 or len(lines) != 1 or name not in lines[0] or \
            location not in lines[0]:
        failures.append(f"{name}: status {result.returncode}, stderr {result.stderr!r} "
                        f"(expected one line naming {name} and {location!r})")
    if os.path.exists(out):
        failures.append(f"{name}: the frames' folder was created")

not_a_folder = os.path.join(folder, "file.txt")
open(not_a_folder, "w").close()
path = write_path("good.json", [good])
bad_commands = {
    "orbit 0": (["--orbit", "0"], "--orbit"),
    "orbit x": (["--orbit", "x"], "--orbit"),
    "orbit and path": (["--orbit", "2", "--path", path], "--orbit"),
    "no cameras": ([], "--path"),
    "no such path": (["--path", os.path.join(folder, "nothing.json")], "nothing.json"),
    "no such solution": (["--path", path], "nothing.vtm"),
    "file as folder": (["--path", path], "file.txt"),
    "exposure": (["--path", path, "--exposure", "0"], "--exposure"),
    "size": (["--path", path, "--size", "64"], "--size"),
}
for name, (arguments, named) in bad_commands.items():
    solution = os.path.join(folder, "nothing.vtm") if name == "no such solution" \
        else cornell_solution
    out = not_a_folder if name == "file as folder" else os.path.join(folder, "bad_command")
    result = run("walk", solution, *arguments, "-o", out)
    lines = [line for line in result.stderr.strip().splitlines()
             if not line.startswith("Run with --help")]
    if result.returncode == 0 or len(lines) != 1 or named not in lines[0]:
        failures.append(f"walk with {name}: status {result.returncode}, stderr "
                        f"{result.stderr!r} (expected one line naming {named!r})")
    if name != "file as folder" and os.path.exists(out):
        failures.append(f"walk with {name}: the frames' folder was created")

shutil.rmtree(folder)
for failure in failures:
    print("FAIL:", failure)
sys.exit(1 if failures else 0)
