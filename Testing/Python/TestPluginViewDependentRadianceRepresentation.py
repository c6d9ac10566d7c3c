"""pvbatch: the plug-in's "View-Dependent Radiance" representation (issue 18): an Illumination
Field shown with it follows the camera, mirrors included, with no pipeline execution and no call
from the script between the views (the representation's mapper evaluates the solution toward
the camera before each render, paper §5.3.1). The mixed box, from two cameras that each see the
white wall (diffuse), the mirror wall and the glossy cube:
- on the white wall the screenshot is the Illumination Field's shown as Surface with DisplayRGB
  (within 1 byte per channel);
- every mirror pixel but a few differs from the field's (which shows the mirror's zero diffuse
  part) and the mirror differs between the two cameras;
- the Illumination Field's output is neither executed again nor written (its own view unchanged);
- back at the first camera the image is the first one again (the evaluation's caches hold values,
  not a history);
- Exposure -1 instead of 0 halves the white wall's radiance: its bytes are the sRGB encoding of
  half the decoded ones (within 2 bytes; quantisation);
- a dataset that is not an Illumination Field gives one error, naming what is missing, and is
  drawn (no crash).
Regions are the pixels of each surface in a view of the field coloured by SurfaceId, shrunk by 2
pixels (an edge pixel may show either surface)."""
import shutil
import sys
import tempfile

import numpy as np
from paraview.simple import (Calculator, ColorBy, CreateRenderView, Delete, GetViews, Hide,
                             LoadPlugin, OpenDataFile, OutputPort, Render, SaveScreenshot, Show,
                             Sphere)
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkIOImage import vtkPNGReader

plugin, data = sys.argv[1:3]
folder = tempfile.mkdtemp()
LoadPlugin(plugin, remote=False, ns=globals())

failures = []
WIDTH, HEIGHT = 320, 240
# The mixed box's surfaces in the scene's order: x_max the mirror, z_min white (diffuse).
MIRROR, WHITE = 1, 4
CAMERAS = [([0.3, 0.45, 0.9], [0.75, 0.5, 0.0]), ([0.5, 0.6, 0.95], [0.9, 0.4, 0.1])]
TYPE = "View-Dependent Radiance"

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


def look(target, camera):
    target.CameraPosition, target.CameraFocalPoint = camera
    target.CameraViewUp = [0, 1, 0]
    target.CameraViewAngle = 60


def shot(name, target):
    path = f"{folder}/{name}.png"
    SaveScreenshot(path, target, ImageResolution=[WIDTH, HEIGHT])
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    pixels = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())
    return pixels.reshape(HEIGHT, WIDTH, -1)[:, :, :3].astype(int)


def unlit(display):
    display.MapScalars = 0
    display.Ambient = 1.0
    display.Diffuse = 0.0


# The Illumination Field as the Surface representation shows it (DisplayRGB, unlit).
field_view = black_view()
field_display = Show(field, field_view)
ColorBy(field_display, ("POINTS", "DisplayRGB"))
unlit(field_display)
# paraview.simple resets the camera on a view's first render: render once before placing it.
Render(field_view)

# Which surface each pixel shows: each vertex coloured (SurfaceId + 1) x 16 in red.
mask_view = black_view()
ids = Calculator(Input=field, ResultArrayName="SurfaceColour", ResultArrayType="Float",
                 Function="(SurfaceId+1)*16/255*iHat")
ids_display = Show(ids, mask_view)
ColorBy(ids_display, ("POINTS", "SurfaceColour"))
unlit(ids_display)
Render(mask_view)


def regions(camera, k):
    """The pixels of each surface, 2 pixels in from its edges (an edge pixel may show either)."""
    look(mask_view, camera)
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
    look(field_view, camera)
    Render(field_view)
    field_shots.append(shot(f"field_{k}", field_view))

# The representation under test, in a view of its own; nothing but the camera changes below.
view = black_view()
display = Show(field, view)
display.SetRepresentationType(TYPE)
Render(view)
executed = field.GetClientSideObject().GetOutputDataObject(0).GetMTime()
view_shots = []
for k, camera in enumerate(CAMERAS + CAMERAS[:1]):
    look(view, camera)
    Render(view)
    view_shots.append(shot(f"view_{k}", view))
if field.GetClientSideObject().GetOutputDataObject(0).GetMTime() != executed:
    failures.append("the Illumination Field's output changed (executed again, or its arrays "
                    "written) while only the camera moved")
# The field's own DisplayRGB is untouched: its Surface view is what it was.
look(field_view, CAMERAS[0])
Render(field_view)
if (shot("field_again", field_view) != field_shots[0]).any():
    failures.append("the Illumination Field's Surface view changed after the view-dependent one "
                    "rendered")

for k in range(len(CAMERAS)):
    white = masks[k]["white"]
    difference = np.abs(view_shots[k] - field_shots[k]).max(axis=2)
    print(f"camera {k}, white wall: {white.sum()} pixels, largest difference from the field "
          f"{difference[white].max() if white.any() else '-'}")
    if white.sum() < 0.02 * WIDTH * HEIGHT:
        failures.append(f"camera {k}: the white wall is hardly in view; the test is wrong")
    elif difference[white].max() > 1:
        failures.append(f"camera {k}: {(difference[white] > 1).sum()} pixels of the white wall "
                        "differ from the Illumination Field's by more than 1")
    mirror = masks[k]["mirror"]
    changed = (difference > 0) & mirror
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
if (view_shots[2] != view_shots[0]).any():
    failures.append(f"back at camera 0, {(view_shots[2] != view_shots[0]).any(axis=2).sum()} "
                    "pixels differ from the first view of it")


def decode(byte):
    c = byte / 255.0
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def encode(linear):
    c = np.clip(linear, 0.0, 1.0)
    return np.rint(255 * np.where(c <= 0.0031308, 12.92 * c, 1.055 * c ** (1 / 2.4) - 0.055))


# Exposure: one stop less halves the radiance shown (camera 0, the white wall, pixels neither
# black nor white).
display.Exposure = -1.0
look(view, CAMERAS[0])
Render(view)
darker = shot("exposure", view)
white = masks[0]["white"]
before = view_shots[0][white]
usable = ((before > 20) & (before < 250)).all(axis=1)
error = np.abs(darker[white][usable] - encode(0.5 * decode(before[usable])))
ratio = np.median(decode(darker[white][usable]) / decode(before[usable]))
# A pixel's bytes are interpolated between vertices in sRGB, so halving the radiance is not
# exactly halving a pixel's decoded value: a few bytes of slack, and the median ratio.
print(f"Exposure -1: {usable.sum()} white-wall pixels, largest error against half the radiance "
      f"{error.max() if usable.any() else '-'} bytes, median ratio {ratio:.4f}")
if usable.sum() < 0.01 * WIDTH * HEIGHT:
    failures.append("too few white-wall pixels between black and white; the test is wrong")
elif error.max() > 3 or abs(ratio - 0.5) > 0.01:
    failures.append(f"Exposure -1: {(error > 3).any(axis=1).sum()} white-wall pixels are not half "
                    f"the radiance (median ratio {ratio})")
display.Exposure = 0.0
Hide(field, view)

# Data that is not an Illumination Field: one clear error, drawn all the same.
sphere = Sphere()
bad = Show(sphere, view)
bad.SetRepresentationType(TYPE)
errors = []
representation = bad.GetClientSideObject().GetActiveRepresentation()
print(f"the sphere's representation: {representation.GetClassName()}")


@calldata_type(VTK_STRING)
def on_error(caller, event, message):
    errors.append(message)


representation.AddObserver("ErrorEvent", on_error)
Render(view)
shot("sphere", view)
print(f"a sphere: {len(errors)} error(s): {errors}")
if len(errors) != 1 or "SurfaceId" not in errors[0]:
    failures.append(f"a sphere gave {len(errors)} errors instead of one naming SurfaceId")

# Views deleted before pvbatch exits: tearing down a view at interpreter exit crashes in X.
for created in GetViews():
    Delete(created)
shutil.rmtree(folder)
for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
