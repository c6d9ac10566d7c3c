"""Textures (paper §5.4), through `sphcover`.

1. A textured floor under a lamp that reflects nothing (Data/scenes/textured_floor.scene, paper
§5.4): the floor's irradiance is the lamp's alone, the same with and without the texture, so
`sphcover render` of the scene must equal the render of the same scene without its texture times
the texture at each pixel's visible point, pixel by pixel within 1 %. The texture is read here
by VTK's own PNG reader (vtkPNGReader, row 0 at the bottom) and decoded from sRGB; each pixel's
(u, v) comes from its centre ray (one sample per pixel) and the floor's plane, so a texture
turned, flipped or read in the wrong encoding fails.

2. The white furnace (Data/scenes/furnace_box.scene) with a uniform linear texture of value c on
its one material: every surface's mean exitant radiance, in the propagation (the texture's means
over the patches) and in the render (the texture at each visible point), is Le / (1 - rho c)
within 0.5 %, and the box absorbs what it emits; with a checkered texture (no closed form) the box
still absorbs what it emits. And the Illumination Field (vtkIlluminationField) of the floor is
textured as the render is."""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

import numpy
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

from sphericalcover import vtkOpenEXRReader

sphcover, data = sys.argv[1:3]
scenes = os.path.join(data, "scenes")
scene = json.load(open(os.path.join(scenes, "textured_floor.scene")))
folder = tempfile.mkdtemp()
texture_file = os.path.abspath(os.path.join(scenes, scene["materials"]["tiles"]["texture"]))
failures = []


def render(description, name):
    path = os.path.join(folder, name + ".scene")
    json.dump(description, open(path, "w"))
    exr = os.path.join(folder, name + ".exr")
    run = subprocess.run([sphcover, "render", path, "-o", exr, "--spp", "1", "--quiet"],
                         capture_output=True, text=True, timeout=600)
    if run.returncode != 0:
        sys.exit(f"FAILED: render of the {name} floor: {run.stderr.strip()}")
    reader = vtkOpenEXRReader()
    reader.SetFileName(exr)
    reader.Update()
    image = reader.GetOutput()
    width, height = image.GetDimensions()[:2]
    radiance = vtk_to_numpy(image.GetPointData().GetArray("Radiance")).astype(float)
    depth = vtk_to_numpy(image.GetPointData().GetArray("Depth")).astype(float)
    return width, height, radiance, depth


textured = json.loads(json.dumps(scene))
textured["materials"]["tiles"]["texture"] = texture_file
plain = json.loads(json.dumps(scene))
del plain["materials"]["tiles"]["texture"]
width, height, with_texture, depth = render(textured, "textured")
_, _, without_texture, _ = render(plain, "plain")

# The texture, decoded independently: VTK's PNG reader, the sRGB curve (IEC 61966-2-1).
png = vtkPNGReader()
png.SetFileName(texture_file)
png.Update()
tw, th = png.GetOutput().GetDimensions()[:2]
codes = vtk_to_numpy(png.GetOutput().GetPointData().GetScalars()).astype(float)[:, :3] / 255.0
texels = numpy.where(codes <= 0.04045, codes / 12.92, ((codes + 0.055) / 1.055) ** 2.4)
texels = texels.reshape(th, tw, 3)  # [row from the bottom, column]


def texture_at(u, v):
    """Bilinear between the texel centres, clamped to the edge texels (FORMAT.md)."""
    x = min(max(u * tw - 0.5, 0.0), tw - 1.0)
    y = min(max(v * th - 0.5, 0.0), th - 1.0)
    i0, j0 = min(int(x), tw - 1), min(int(y), th - 1)
    i1, j1 = min(i0 + 1, tw - 1), min(j0 + 1, th - 1)
    fx, fy = x - i0, y - j0
    return ((1 - fy) * ((1 - fx) * texels[j0, i0] + fx * texels[j0, i1]) +
            fy * ((1 - fx) * texels[j1, i0] + fx * texels[j1, i1]))


# Each pixel's centre ray (VTK's camera: vertical view angle, row 0 at the bottom) meets the floor
# y = 0 at (x, z); the floor's P(u, v) = (u, 0, 1 - v).
camera = scene["cameras"][0]
eye = numpy.array(camera["position"], float)
forward = numpy.array(camera["focal_point"], float) - eye
forward /= numpy.linalg.norm(forward)
right = numpy.cross(forward, camera["view_up"])
right /= numpy.linalg.norm(right)
up = numpy.cross(right, forward)
half_height = math.tan(math.radians(camera["view_angle"]) / 2)
half_width = half_height * width / height
compared = 0
worst = 0.0
for j in range(height):
    for i in range(width):
        d = (forward + (2 * (i + 0.5) / width - 1) * half_width * right +
             (2 * (j + 0.5) / height - 1) * half_height * up)
        d /= numpy.linalg.norm(d)
        if d[1] >= 0:
            continue
        t = -eye[1] / d[1]
        hit = eye + t * d
        u, v = hit[0], 1.0 - hit[2]
        p = j * width + i
        # Pixels well inside the floor, where the floor is what the ray meets first.
        if not (0.01 < u < 0.99 and 0.01 < v < 0.99) or abs(depth[p] - t) > 1e-3 * t:
            continue
        expected = without_texture[p] * texture_at(u, v)
        if expected.min() <= 0:
            continue
        error = numpy.abs(with_texture[p] / expected - 1).max()
        worst = max(worst, error)
        compared += 1
if compared < width * height // 4:
    failures.append(f"only {compared} floor pixels compared")
if worst > 0.01:
    failures.append(f"textured render differs from untextured x texture by {100 * worst:.2f} % "
                    "(more than 1 %)")
print(f"{compared} floor pixels: textured = untextured x texture within {100 * worst:.4f} %")
# And the texture shows: red grows with u, green with v, so the two renders differ by far more.
ratio = with_texture.sum(axis=0) / without_texture.sum(axis=0)
if not (ratio.min() < 0.9):
    failures.append(f"the texture does not darken the floor (band ratios {ratio})")

# The Illumination Field (ParaView's walk-through geometry) is textured as the render is: at every
# field point of the floor, the textured Radiance is the untextured one times the texture there.
from sphericalcover import (vtkIlluminationField, vtkIntervalSubdivisionFilter,  # noqa: E402
                            vtkLightPropagationFilter, vtkPatchSceneReader, vtkSphericalCoverFilter)


def field_of(name):
    reader = vtkPatchSceneReader()
    reader.SetFileName(os.path.join(folder, name + ".scene"))
    subdivision = vtkIntervalSubdivisionFilter()
    subdivision.SetInputConnection(reader.GetOutputPort())
    cover = vtkSphericalCoverFilter()
    cover.SetInputConnection(subdivision.GetOutputPort(0))
    propagation = vtkLightPropagationFilter()
    propagation.SetInputConnection(cover.GetOutputPort(0))
    field = vtkIlluminationField()
    field.SetInputConnection(0, propagation.GetOutputPort(0))
    field.Update()
    output = field.GetOutput()
    return (vtk_to_numpy(output.GetPoints().GetData()).astype(float),
            vtk_to_numpy(output.GetPointData().GetArray("Radiance")).astype(float),
            vtk_to_numpy(output.GetPointData().GetArray("SurfaceId")))


points, field_textured, surface_ids = field_of("textured")
plain_points, field_plain, _ = field_of("plain")
if points.shape != plain_points.shape or numpy.abs(points - plain_points).max() > 0:
    failures.append("the illumination fields of the textured and plain floors have other points")
else:
    floor = numpy.nonzero((surface_ids == 0) & (field_plain.min(axis=1) > 0))[0]
    worst_field = 0.0
    for p in floor:
        expected = field_plain[p] * texture_at(points[p][0], 1.0 - points[p][2])
        worst_field = max(worst_field, numpy.abs(field_textured[p] / expected - 1).max())
    print(f"illumination field: {len(floor)} floor points textured within {100 * worst_field:.4f} %")
    if len(floor) < 100 or worst_field > 0.01:
        failures.append(f"illumination field: {len(floor)} floor points, textured within "
                        f"{100 * worst_field:.2f} % (more than 1 %)")

# 2. The textured white furnace.
def write_grey_png(path, size, value_of):
    """An 8-bit grey PNG (filter 0, one IDAT), written here so that the test does not depend on
    the files it checks."""
    import struct
    import zlib

    def chunk(kind, payload):
        return (struct.pack(">I", len(payload)) + kind + payload +
                struct.pack(">I", zlib.crc32(kind + payload) & 0xffffffff))
    rows = b"".join(b"\x00" + bytes(value_of(i, j) for i in range(size)) for j in range(size))
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", size, size, 8, 0, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


furnace = json.load(open(os.path.join(scenes, "furnace_box.scene")))
material = list(furnace["materials"].values())[0]
uniform_png = os.path.join(folder, "uniform.png")
code = 128
write_grey_png(uniform_png, 4, lambda i, j: code)
c = code / 255.0
material["texture"] = uniform_png
material["texture_encoding"] = "linear"
path = os.path.join(folder, "furnace_textured.scene")
json.dump(furnace, open(path, "w"))
report_file = os.path.join(folder, "furnace.json")
exr = os.path.join(folder, "furnace.exr")
run = subprocess.run([sphcover, "render", path, "--report", report_file, "-o", exr, "--size", "64x64",
                      "--quiet"], capture_output=True, text=True, timeout=600)
if run.returncode != 0:
    failures.append(f"textured furnace: {run.stderr.strip()}")
else:
    expected = numpy.array([e / (1 - r * c) for e, r in zip(material["emission"], material["reflectance"])])
    report = json.load(open(report_file))
    worst = max(abs(got / want - 1) for s in report["surfaces"]
                for got, want in zip(s["mean_exitant_radiance"], expected))
    imbalance = report["energy"]["relative_imbalance"]
    reader = vtkOpenEXRReader()
    reader.SetFileName(exr)
    reader.Update()
    pixels = vtk_to_numpy(reader.GetOutput().GetPointData().GetArray("Radiance")).astype(float)
    worst_pixel = numpy.abs(pixels / expected - 1).max()
    print(f"textured furnace (c = {c:.4f}): worst |L / (Le / (1 - rho c)) - 1| = {worst:.2e} over the "
          f"surfaces, {worst_pixel:.2e} over the pixels; imbalance {imbalance:.2e}")
    if worst > 0.005:
        failures.append(f"textured furnace: surface radiance off by {100 * worst:.3f} %")
    if worst_pixel > 0.005:
        failures.append(f"textured furnace: a pixel off by {100 * worst_pixel:.3f} %")
    if imbalance > 1e-3:
        failures.append("textured furnace: emitted and absorbed power differ by more than 0.1 %")

checker_png = os.path.join(folder, "checker.png")
write_grey_png(checker_png, 8, lambda i, j: 40 if (i // 2 + j // 2) % 2 else 250)
material["texture"] = checker_png
material.pop("texture_encoding")
json.dump(furnace, open(path, "w"))
run = subprocess.run([sphcover, "solve", path, "--report", report_file, "--quiet"],
                     capture_output=True, text=True, timeout=600)
if run.returncode != 0:
    failures.append(f"checkered furnace: {run.stderr.strip()}")
else:
    imbalance = json.load(open(report_file))["energy"]["relative_imbalance"]
    print(f"checkered furnace: imbalance {imbalance:.2e}")
    if imbalance > 1e-3:
        failures.append("checkered furnace: emitted and absorbed power differ by more than 0.1 %")

shutil.rmtree(folder)
if failures:
    print("FAILED:\n  " + "\n  ".join(failures))
    sys.exit(1)
