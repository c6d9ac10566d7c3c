"""pvbatch: the solution's view-dependent radiance in ParaView's render view (issue 18, part b,
partial: the evaluation is called from the script, not yet by a representation on every
camera move). The mixed box's Illumination Field is shown with DisplayRGB (Map Scalars off, no
lighting); vtkViewDependentRadiance rewrites the displayed data's DisplayRGB in place for the
camera's eye (no pipeline execution) and the view is rendered again. Two camera positions, each
seeing the white wall (diffuse), the mirror wall and the glossy cube:
- on the diffuse walls the screenshot is the Illumination Field's, byte for byte;
- on the mirror it is not (the Illumination Field shows the mirror's zero diffuse part, the view
  its reflection of the room toward the eye, paper §5.3.1), and it differs between the cameras.
Regions are the pixels of each surface in a view of the field coloured by SurfaceId, shrunk
by 2 pixels (an edge pixel may show either surface)."""
import shutil
import sys
import tempfile

import numpy as np
from paraview.simple import (Calculator, ColorBy, CreateRenderView, Delete, GetViews, LoadPlugin,
                             OpenDataFile, OutputPort, Render, SaveScreenshot, Show)
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

plugin, data = sys.argv[1:3]
folder = tempfile.mkdtemp()
LoadPlugin(plugin, remote=False, ns=globals())
from sphericalcover import vtkViewDependentRadiance  # noqa: E402

failures = []
WIDTH, HEIGHT = 320, 240
# The mixed box's surfaces in the scene's order: x_max the mirror, z_min white (diffuse).
MIRROR, WHITE = 1, 4
CAMERAS = [([0.3, 0.45, 0.9], [0.75, 0.5, 0.0]), ([0.5, 0.6, 0.95], [0.9, 0.4, 0.1])]

scene = OpenDataFile(f"{data}/scenes/mixed_box.scene")
subdivision = globals()["IntervalSubdivision"](Input=scene)
subdivision.MaxLevel = 2
subdivision.ThetaBins = 16
subdivision.PhiBins = 64
cover = globals()["SphericalCover"](Input=OutputPort(subdivision, 0))
cover.ThetaBins = 16
cover.PhiBins = 64
propagation = globals()["LightPropagation"](Input=OutputPort(cover, 0))
field = globals()["IlluminationField"](Input=OutputPort(propagation, 0),
                                       Patches=OutputPort(subdivision, 0))
field.Resolution = 4



def black_view():
    created = CreateRenderView()
    created.ViewSize = [WIDTH, HEIGHT]
    created.OrientationAxesVisibility = 0
    created.UseColorPaletteForBackground = 0
    created.Background = [0, 0, 0]
    return created


view = black_view()
mask_view = black_view()
display = Show(field, view)
ColorBy(display, ("POINTS", "DisplayRGB"))
display.MapScalars = 0
display.Ambient = 1.0
display.Diffuse = 0.0
# paraview.simple resets the camera on a view's first render: render once before placing it.
Render(view)
Render(mask_view)


def look(camera, target=view):
    target.CameraPosition, target.CameraFocalPoint = camera
    target.CameraViewUp = [0, 1, 0]
    target.CameraViewAngle = 60


def shot(name, target=view):
    path = f"{folder}/{name}.png"
    SaveScreenshot(path, target, ImageResolution=[WIDTH, HEIGHT])
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    pixels = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())
    return pixels.reshape(HEIGHT, WIDTH, -1)[:, :, :3].astype(int)


# Which surface each pixel shows: the field again, in a view of its own, each vertex coloured
# (SurfaceId + 1) x 16 in red (a patch's vertices are its own, so every patch is one flat colour).
ids = Calculator(Input=field, ResultArrayName="SurfaceColour", ResultArrayType="Float",
                 Function="(SurfaceId+1)*16/255*iHat")
ids_display = Show(ids, mask_view)
ColorBy(ids_display, ("POINTS", "SurfaceColour"))
ids_display.MapScalars = 0
ids_display.Ambient = 1.0
ids_display.Diffuse = 0.0
Render(mask_view)


def regions(camera, k):
    """The pixels of each surface, 2 pixels in from its edges (an edge pixel may show either)."""
    look(camera, mask_view)
    surface = np.rint(shot(f"surfaces_{k}", mask_view)[:, :, 0] / 16.0).astype(int) - 1
    found = {}
    for name, index in [("white", WHITE), ("mirror", MIRROR)]:
        mask = surface == index
        for _ in range(2):
            mask[1:-1, 1:-1] &= mask[:-2, 1:-1] & mask[2:, 1:-1] & mask[1:-1, :-2] & mask[1:-1, 2:]
            mask[[0, -1], :] = False
            mask[:, [0, -1]] = False
        found[name] = mask
    return found


masks = [regions(camera, k) for k, camera in enumerate(CAMERAS)]
field_shots = []
for k, camera in enumerate(CAMERAS):
    look(camera)
    Render(view)
    field_shots.append(shot(f"field_{k}"))

# The displayed data (the representation's copy of the field), rewritten for each eye.
evaluator = vtkViewDependentRadiance()
if not evaluator.SetSolution(propagation.GetClientSideObject().GetOutputDataObject(0),
                             subdivision.GetClientSideObject().GetOutputDataObject(0)):
    failures.append("the solution was refused")
rendered = display.GetClientSideObject().GetRenderedDataObject(0)
iterator = rendered.NewIterator()
iterator.InitTraversal()
displayed = iterator.GetCurrentDataObject()
view_shots = []
for k, camera in enumerate(CAMERAS):
    look(camera)
    if not evaluator.Update(displayed, *camera[0], 0.0):
        failures.append(f"camera {k}: the view-dependent evaluation failed")
    Render(view)
    view_shots.append(shot(f"view_{k}"))
    print(f"camera {k}: evaluation {1000 * evaluator.GetLastUpdateSeconds():.0f} ms for "
          f"{displayed.GetNumberOfPoints()} vertices")

for k in range(len(CAMERAS)):
    for name in ["white"]:
        mask = masks[k][name]
        differ = (view_shots[k] != field_shots[k]).any(axis=2) & mask
        print(f"camera {k}, {name} wall: {mask.sum()} pixels, {differ.sum()} differ from the field")
        if mask.sum() < 0.02 * WIDTH * HEIGHT:
            failures.append(f"camera {k}: the {name} wall is hardly in view; the test is wrong")
        elif differ.any():
            failures.append(f"camera {k}: {differ.sum()} pixels of the {name} wall differ from "
                            "the Illumination Field's")
    mirror = masks[k]["mirror"]
    changed = (view_shots[k] != field_shots[k]).any(axis=2) & mirror
    print(f"camera {k}, mirror: {mirror.sum()} pixels, {changed.sum()} differ from the field")
    if mirror.sum() < 0.02 * WIDTH * HEIGHT:
        failures.append(f"camera {k}: the mirror is hardly in view; the test is wrong")
    elif changed.sum() < 0.9 * mirror.sum():
        failures.append(f"camera {k}: only {changed.sum()} of {mirror.sum()} mirror pixels show "
                        "more than the field's diffuse part")
means = [view_shots[k][masks[k]["mirror"]].mean(axis=0) for k in range(len(CAMERAS))]
print(f"the mirror's mean colour: {means[0]} and {means[1]}")
if not np.abs(means[0] - means[1]).max() > 2:
    failures.append(f"the mirror looks the same from both cameras ({means[0]}, {means[1]})")

# Views deleted before pvbatch exits: tearing down a view at interpreter exit crashes in X.
for created in GetViews():
    Delete(created)
shutil.rmtree(folder)
for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
