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
import os
import sys

import numpy as np
from paraview.simple import ColorBy, Render, Show

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mixed_box_views import (CAMERAS, HEIGHT, WIDTH, Screenshots, black_view,  # noqa: E402
                             look, mixed_box_field, unlit)

plugin, data = sys.argv[1:3]
subdivision, propagation, field = mixed_box_field(plugin, data)
from sphericalcover import vtkViewDependentRadiance  # noqa: E402

failures = []
screenshots = Screenshots()
view = black_view()
display = Show(field, view)
ColorBy(display, ("POINTS", "DisplayRGB"))
unlit(display)
# paraview.simple resets the camera on a view's first render: render once before placing it.
Render(view)

masks = screenshots.regions(field)
field_shots = []
for k, camera in enumerate(CAMERAS):
    look(view, camera)
    Render(view)
    field_shots.append(screenshots.shot(f"field_{k}", view))

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
    look(view, camera)
    if not evaluator.Update(displayed, *camera[0], 0.0):
        failures.append(f"camera {k}: the view-dependent evaluation failed")
    Render(view)
    view_shots.append(screenshots.shot(f"view_{k}", view))
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

screenshots.close()
for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
