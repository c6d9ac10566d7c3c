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
- each view equals the field's own display rewritten by hand (vtkViewDependentRadiance) for
  that camera's eye, within 1 byte: the representation follows the camera;
- back at the first camera the image is the first one again (the evaluation's caches hold values,
  not a history);
- ExposureStops -1 instead of 0 halves the white wall's radiance: its bytes are the sRGB encoding of
  half the decoded ones (within 2 bytes; quantisation);
- a dataset that is not an Illumination Field gives one error, naming what is missing, and is
  drawn (no crash).
Regions are the pixels of each surface in a view of the field coloured by SurfaceId, shrunk by 2
pixels (an edge pixel may show either surface)."""
import os
import sys

import numpy as np
from paraview.simple import Hide, Render, Show, Sphere
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mixed_box_views import (CAMERAS, HEIGHT, WIDTH, Screenshots, black_view,  # noqa: E402
                             check_views, evaluator_of, look, mixed_box_field)

plugin, data = sys.argv[1:3]
subdivision, propagation, field = mixed_box_field(plugin, data)
failures = []
TYPE = "View-Dependent Radiance"
screenshots = Screenshots()
shot = screenshots.shot

# The Illumination Field as the Surface representation shows it (DisplayRGB, unlit).
field_view, field_display, masks, field_shots = screenshots.field_views(field)

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

check_views(view_shots, field_shots, masks, failures, white_tolerance=1)
if (view_shots[2] != view_shots[0]).any():
    failures.append(f"back at camera 0, {(view_shots[2] != view_shots[0]).any(axis=2).sum()} "
                    "pixels differ from the first view of it")


def decode(byte):
    c = byte / 255.0
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def encode(linear):
    c = np.clip(linear, 0.0, 1.0)
    return np.rint(255 * np.where(c <= 0.0031308, 12.92 * c, 1.055 * c ** (1 / 2.4) - 0.055))


# Each view is the evaluation toward its own camera: the Illumination Field's Surface display,
# its rendered data rewritten by hand by vtkViewDependentRadiance for that eye (as
# ParaView.ViewDependentRadiance does), shows the same pixels (within 1; last, since this writes
# the field's own arrays, which that display shares).
evaluator, displayed = evaluator_of(subdivision, propagation, field_display, failures)
for k, camera in enumerate(CAMERAS):
    look(field_view, camera)
    evaluator.Update(displayed, *camera[0], 0.0)
    Render(field_view)
    by_hand = shot(f"by_hand_{k}", field_view)
    mirror = masks[k]["mirror"]
    difference = np.abs(view_shots[k] - by_hand).max(axis=2)
    print(f"camera {k}: largest difference from the evaluation by hand {difference.max()}, on "
          f"the mirror {difference[mirror].max()}")
    if difference.max() > 1:
        failures.append(f"camera {k}: {(difference > 1).sum()} pixels "
                        f"({(difference[mirror] > 1).sum()} on the mirror) differ from the "
                        "evaluation toward this camera by hand")

# ExposureStops: one stop less halves the radiance shown (camera 0, the white wall, pixels neither
# black nor white).
display.ExposureStops = -1.0
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
print(f"ExposureStops -1: {usable.sum()} white-wall pixels, largest error against half the "
      f"radiance {error.max() if usable.any() else '-'} bytes, median ratio {ratio:.4f}")
if usable.sum() < 0.01 * WIDTH * HEIGHT:
    failures.append("too few white-wall pixels between black and white; the test is wrong")
elif error.max() > 3 or abs(ratio - 0.5) > 0.01:
    failures.append(f"ExposureStops -1: {(error > 3).any(axis=1).sum()} white-wall pixels are "
                    f"not half the radiance (median ratio {ratio})")
display.ExposureStops = 0.0
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

screenshots.close()
for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
