"""Example 3 of Data/examples (scripted VTK pipeline): the EXR it wrote of the Cornell box reads
back through vtkOpenEXRReader as the image the example describes, and the image obeys physics
and geometry:
- the size asked for, with `Radiance` (3 components), `Depth` and `SurfaceId`; the radiance
  finite, non-negative and not all black; SurfaceId a surface of the scene or -1;
- where a surface is seen its depth is positive and lies between the nearest and the farthest
  the surface can be: a Bezier surface lies in the convex hull of its control points, so every
  point of it is at least min_c (c - eye) . view and at most max_c |c - eye| from the eye
  (c the control points, view the unit view direction); where nothing is seen Depth is -1;
- the lamp's pixels show its emission plus the little light it reflects (exitant radiance =
  emitted + reflected, paper §5): at least the emission in every band and at most 2% more
  (the lamp, reflectance 0.78, sees a room about a hundred times dimmer than itself, which
  adds about 1%: 1.1% in red, 0.7% in green, 0.6% in blue at the example's settings);
- every surface in view is lit in every band: each point of the Cornell box sees lit surfaces
  and every material reflects some of every band, so no pixel inside a surface is black;
- the red wall (reflectance 0.57, 0.04, 0.04) is red in every pixel (R > G, R > B) and the
  green wall (0.11, 0.38, 0.08) is green on average (G > R, G > B).
Only the pixels whose 3 x 3 neighbourhood sees one surface are compared (a pixel's radiance
is the mean of its samples, which at an edge mix two surfaces).

usage: python3 TestExampleScriptedPipeline.py DATA_DIR IMAGE.exr WIDTH HEIGHT"""
import os
import sys

import numpy
from sphericalcover import vtkOpenEXRReader, vtkPatchSceneReader
from vtkmodules.util.numpy_support import vtk_to_numpy

data, path = sys.argv[1:3]
width, height = int(sys.argv[3]), int(sys.argv[4])
failures = []

# The scene as the reader gives it: per surface its name, emission, control points; the camera.
scene = vtkPatchSceneReader()
scene.SetFileName(os.path.join(data, "scenes", "cornell_box.scene"))
scene.Update()
surfaces = scene.GetOutput()
cells = surfaces.GetCellData()
names = surfaces.GetFieldData().GetAbstractArray("SurfaceNames")
name_of = {}
control_points = {}
for cell in range(surfaces.GetNumberOfCells()):
    sid = int(cells.GetArray("SurfaceId").GetComponent(cell, 0))
    name_of[sid] = names.GetValue(int(cells.GetArray("SurfaceNameId").GetComponent(cell, 0)))
    ids = surfaces.GetCell(cell).GetPointIds()
    control_points[sid] = numpy.array([surfaces.GetPoint(ids.GetId(k))
                                       for k in range(ids.GetNumberOfIds())])
surface_id = {name: sid for sid, name in name_of.items()}
emission = vtk_to_numpy(cells.GetArray("Emission"))
camera = surfaces.GetFieldData().GetArray("CameraParameters").GetTuple(0)  # the first camera
eye, focal = numpy.array(camera[0:3]), numpy.array(camera[3:6])
view = (focal - eye) / numpy.linalg.norm(focal - eye)

reader = vtkOpenEXRReader()
reader.SetFileName(path)
reader.Update()
image = reader.GetOutput()
arrays = {name: image.GetPointData().GetArray(name) for name in ["Radiance", "Depth", "SurfaceId"]}
if image.GetDimensions() != (width, height, 1):
    failures.append(f"{path}: {image.GetDimensions()}, not {width} x {height}")
elif None in arrays.values() or arrays["Radiance"].GetNumberOfComponents() != 3:
    failures.append(f"{path}: lacks Radiance (RGB), Depth or SurfaceId")
else:
    radiance = vtk_to_numpy(arrays["Radiance"]).reshape(height, width, 3)
    depth = vtk_to_numpy(arrays["Depth"]).reshape(height, width)
    seen = vtk_to_numpy(arrays["SurfaceId"]).reshape(height, width)
    if not numpy.isfinite(radiance).all() or radiance.min() < 0 or radiance.max() <= 0:
        failures.append(f"radiance in [{radiance.min()}, {radiance.max()}]: not finite, "
                        "non-negative and lit")
    if not set(numpy.unique(seen).tolist()) <= set(name_of) | {-1}:
        failures.append(f"SurfaceId values {numpy.unique(seen)} are not surfaces of the scene")
    if not (depth[seen == -1] == -1).all():
        failures.append("pixels that see nothing have a Depth other than -1")
    for sid in sorted(set(numpy.unique(seen).tolist()) - {-1}):
        mine = depth[seen == sid]
        offsets = control_points[sid] - eye
        nearest, farthest = (offsets @ view).min(), numpy.linalg.norm(offsets, axis=1).max()
        # 1e-5: the float Depth channel and the samples' mean.
        if not (mine > 0).all() or mine.min() < nearest * (1 - 1e-5) or \
                mine.max() > farthest * (1 + 1e-5):
            failures.append(f"{name_of[sid]}: Depth in [{mine.min()}, {mine.max()}], outside "
                            f"[{nearest}, {farthest}]")
    if not failures:
        print(f"{path}: {width} x {height}, radiance up to {radiance.max():.4g}, "
              f"{len(set(numpy.unique(seen).tolist()) - {-1})} surfaces in view, depths within "
              "their surfaces' bounds")

    # Interior pixels: the 3 x 3 neighbourhood sees one surface.
    padded = numpy.pad(seen, 1, constant_values=-2)
    interior = numpy.ones_like(seen, dtype=bool)
    for dy in range(3):
        for dx in range(3):
            interior &= padded[dy:dy + height, dx:dx + width] == seen

    dark = interior & (seen >= 0) & (radiance.min(axis=2) <= 0)
    if dark.any():
        rows, columns = numpy.nonzero(dark)
        failures.append(f"{dark.sum()} pixels inside surfaces are black in some band, e.g. "
                        f"({columns[0]}, {rows[0]}) on {name_of[int(seen[rows[0], columns[0]])]}")

    lamp = interior & (seen == surface_id["light"])
    le = emission[surface_id["light"]]
    if lamp.sum() < 10:
        failures.append(f"only {lamp.sum()} interior pixels of the lamp in view")
    else:
        lamp_radiance = radiance[lamp]
        low, high = lamp_radiance.min(axis=0), lamp_radiance.max(axis=0)
        # The lower bound is exact (float rounding aside): nothing is subtracted from emission.
        if (low < le * (1 - 1e-6)).any() or (high > le * 1.02).any():
            failures.append(f"the lamp's pixels {low} .. {high} are not within [Le, 1.02 Le], "
                            f"Le = {le}")
        else:
            print(f"lamp: {lamp.sum()} pixels, radiance / emission from "
                  f"{numpy.round(low / le, 4)} to {numpy.round(high / le, 4)}")

    red = radiance[interior & (seen == surface_id["red_wall"])]
    green = radiance[interior & (seen == surface_id["green_wall"])]
    if len(red) < 10 or len(green) < 10:
        failures.append(f"{len(red)} red and {len(green)} green wall pixels in view")
    else:
        if not ((red[:, 0] > red[:, 1]) & (red[:, 0] > red[:, 2])).all():
            failures.append("a pixel of the red wall is not red")
        mean_green = green.mean(axis=0)
        if not (mean_green[1] > mean_green[0] and mean_green[1] > mean_green[2]):
            failures.append(f"the green wall's mean radiance {mean_green} is not green")
        print(f"red wall: {len(red)} pixels, mean {red.mean(axis=0)}; green wall: "
              f"{len(green)} pixels, mean {mean_green}")

for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
